// The scan reader's child process (docs/fuzzing.md, finding 7): assimp parses untrusted
// scans, and a 3.9 kB PLY made it allocate 3.1 GB at once (and keep growing past 12 GB);
// others made it hang, crash or abort. So read_surface (app/scan/scan_import.h) runs assimp in
// a child process with an address-space limit (setrlimit RLIMIT_AS) and a CPU-time limit
// (RLIMIT_CPU) under a wall-clock deadline; the child sends the vertices and triangles,
// or the error text, back through a pipe. Whatever assimp does there costs an
// ImportError naming the file, never the GUI, the CLI or the machine's memory.
//
// The child is this same executable, re-executed (/proc/self/exe, sim/self_child.h) with
// a marker argument that a constructor in scan_read_child.cpp recognises before main()
// runs: it reads the file and _exit()s. Not a plain fork(): the workstation is multithreaded (haptic,
// simulation, recorder, Qt, VTK threads), and after fork() only async-signal-safe calls
// are allowed in the child, while assimp allocates, uses iostreams and locales, whose
// locks another thread may hold at the moment of the fork. posix_spawn (glibc: clone with
// CLONE_VFORK, exec at once) is safe from any thread, copies no page tables of a large
// GUI process, and every binary that links read_surface (palpation, the GUI, the tests,
// the fuzz target) can serve as its own reader without a helper to find on disk.
// Internal to app/ (tests use it to compare with the in-process reader). Linux.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "scan/scan_import.h"

namespace palpation::app::scan::reader {

/// The argv[1] that turns an executable into the scan reader's child.
inline constexpr const char* kChildFlag = "--palpation-internal-scan-reader";

struct Limits {
  /// Bytes the reader may map beyond what the freshly started executable already maps
  /// (its libraries: Qt and VTK in the GUI): the child's RLIMIT_AS is that plus this.
  std::uint64_t memory_bytes = 0;
  double cpu_seconds = 0;   // RLIMIT_CPU (soft; SIGKILL 5 s later)
  double wall_seconds = 0;  // the parent kills the child after this long
};

/// The limits for a file of this size: memory 2 GiB, or 16 bytes per byte of the file
/// where that is more, but at most half of the physical memory (and at least 256 MiB);
/// CPU time 30 s + 2 s per MB; wall clock 3 x the CPU time + 30 s (a loaded machine).
Limits limits_for(std::uint64_t file_bytes);
Limits limits_for(const std::string& path);

/// "2 GiB", "512 MiB": a memory size for messages.
std::string memory_words(std::uint64_t bytes);

/// The cheap checks of the file, in the calling process (exists, regular, extension,
/// not empty, a PLY header that is text and ends): ImportError otherwise.
void check_file(const std::string& path);

/// assimp's reading, in this process (the child's work; tests compare with it). Throws
/// ImportError, or std::bad_alloc when assimp ran out of memory.
SurfaceMesh read_here(const std::string& path);

/// Reads `path` (already checked) in a child process under `limits`. Throws ImportError
/// (bad file, or the child exceeded a limit, crashed or stopped without a result),
/// std::runtime_error("cancelled") when `cancelled` returned true, std::runtime_error
/// when no child could be started.
SurfaceMesh read_in_child(const std::string& path, const Limits& limits, const std::function<bool()>& cancelled = {});

}  // namespace palpation::app::scan::reader
