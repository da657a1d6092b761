// Running a job in a child process that is this same executable, re-executed.
//
// Untrusted input (volume mesh files for Gmsh's readers, scans for assimp) and Gmsh's
// mesher run in a child, so a crash, hang or runaway allocation there costs an error
// message, never the workstation. The child is /proc/self/exe started with posix_spawn
// (glibc: clone(CLONE_VFORK) and exec at once) and a marker argument that a constructor
// in the job's own source file recognises before main() runs; it does its work and
// _exit()s. Not fork() without exec: the workstation is multithreaded (haptic,
// simulation, recorder, Qt, VTK, llvmpipe threads), and in a forked child any lock that
// another thread held at the moment of the fork stays locked for ever. Measured: with
// three threads allocating, one of 40 forked Gmsh children of an AddressSanitizer build
// hung on the allocator's lock (GCC 12's ASan does not lock it around fork); CI's
// sanitizer stage lost tst_review to exactly that.
//
// The child's stdin and stdout are one end of a socket pair: the parent sends `input`
// (then end of file) and reads everything the child writes until it closes its stdout,
// under a wall-clock deadline and a cancel callback. stderr is /dev/null; no other
// descriptor of this process reaches the child. Linux (glibc).
#pragma once

#include <sys/resource.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace palpation::sim::self_child {

struct Job {
  std::vector<std::string> argv;          // argv[0] (a name for ps), argv[1] the marker, then arguments
  std::string input;                      // the child's stdin
  double wall_seconds = 60;               // killed (SIGKILL) after this long
  std::function<bool()> cancelled;        // polled every 100 ms; true kills the child
  std::size_t max_output = std::size_t(1) << 34;  // more output than this kills the child
  char** envp = nullptr;                  // nullptr: this process's environment
};

struct Outcome {
  std::string output;  // what the child wrote to stdout
  int status = 0;      // waitpid status (valid: the child was always reaped)
  rusage usage{};      // the child's resource usage
  bool timed_out = false, cancelled = false, too_long = false;
};

/// Starts the child, feeds it, collects its output and reaps it. Throws
/// std::runtime_error (naming the call and errno) only when no child could be started.
Outcome run(const Job& job);

/// "SIGSEGV", "SIGABRT", ... or "signal N".
std::string signal_name(int sig);

/// Writes all of [data, data + n) to `fd` (EINTR retried). The children's side.
bool write_all(int fd, const void* data, std::size_t n);

/// Reads `fd` to its end. The children's side (their stdin).
bool read_all(int fd, std::string& out);

}  // namespace palpation::sim::self_child
