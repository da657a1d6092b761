// See self_child.h: why a re-executed child, and the protocol (socket pair on stdin and
// stdout, deadline, cancel, reaping).
#include "self_child.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace palpation::sim::self_child {

namespace {

std::string why_errno(const char* what, int err) { return std::string(what) + ": " + std::strerror(err); }

/// posix_spawn's attributes and file actions, released on every path.
struct SpawnSetup {
  posix_spawn_file_actions_t fa;
  posix_spawnattr_t at;
  SpawnSetup() {
    posix_spawn_file_actions_init(&fa);
    posix_spawnattr_init(&at);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
};

}  // namespace

Outcome run(const Job& job) {
  if (job.argv.size() < 2) throw std::runtime_error("self_child::run: argv needs a name and a marker");
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    throw std::runtime_error(why_errno("socketpair", errno));
  SpawnSetup s;
  // stdin and stdout: the child's end of the pair (dup2 clears close-on-exec on the
  // copies); stderr: /dev/null (a job's or a sanitizer's messages go nowhere); nothing else.
  posix_spawn_file_actions_adddup2(&s.fa, sv[1], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&s.fa, sv[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&s.fa, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclosefrom_np(&s.fa, 3);
  // No blocked signals, and default actions for the fatal ones and SIGPIPE: a crash ends
  // the child (the parent reports it), not a handler inherited through the exec's mask.
  sigset_t none, dfl;
  sigemptyset(&none);
  sigemptyset(&dfl);
  for (const int sig : {SIGPIPE, SIGXCPU, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGINT, SIGTERM, SIGHUP, SIGQUIT})
    sigaddset(&dfl, sig);
  posix_spawnattr_setsigmask(&s.at, &none);
  posix_spawnattr_setsigdefault(&s.at, &dfl);
  posix_spawnattr_setflags(&s.at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<std::string> args = job.argv;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, "/proc/self/exe", &s.fa, &s.at, argv.data(), job.envp ? job.envp : environ);
  ::close(sv[1]);
  if (rc != 0) {
    ::close(sv[0]);
    throw std::runtime_error(why_errno("posix_spawn /proc/self/exe", rc));
  }
  const int fd = sv[0];
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);

  Outcome out;
  bool reaped = false;
  auto reap = [&](int flags) {
    pid_t w;
    do {
      w = ::wait4(pid, &out.status, flags, &out.usage);
    } while (w < 0 && errno == EINTR);
    if (w == pid) reaped = true;
    return reaped;
  };
  std::size_t sent = 0;
  bool sending = true;
  auto stop_sending = [&] {
    if (sending) ::shutdown(fd, SHUT_WR);  // the child's stdin reaches its end
    sending = false;
  };
  if (job.input.empty()) stop_sending();
  auto drain = [&]() -> bool {  // false at the end of the child's output
    char chunk[1 << 16];
    for (;;) {
      const ssize_t n = ::recv(fd, chunk, sizeof chunk, MSG_DONTWAIT);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
      if (n <= 0) return false;
      out.output.append(chunk, static_cast<std::size_t>(n));
      if (out.output.size() > job.max_output) {
        out.too_long = true;
        return false;
      }
    }
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(job.wall_seconds);
  for (;;) {
    if (job.cancelled && job.cancelled()) {
      out.cancelled = true;
      break;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      out.timed_out = true;
      break;
    }
    pollfd pf{fd, static_cast<short>(POLLIN | (sending ? POLLOUT : 0)), 0};
    const int r = ::poll(&pf, 1, static_cast<int>(std::min<long long>(left.count(), 100)));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) break;
    if (r == 0) {
      // Ended (or ending) without closing: take what is buffered, without waiting.
      if (reap(WNOHANG)) {
        drain();
        break;
      }
      continue;
    }
    if (sending && (pf.revents & POLLOUT)) {
      const ssize_t w = ::send(fd, job.input.data() + sent, job.input.size() - sent, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (w > 0) sent += static_cast<std::size_t>(w);
      else if (w < 0 && errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) stop_sending();  // the child is gone
      if (sent == job.input.size()) stop_sending();
    }
    if (pf.revents & (POLLIN | POLLHUP | POLLERR)) {
      if (!drain()) break;  // end of output (the child closed its stdout; it ends now), or too much
    }
  }
  ::close(fd);
  if (!reaped && (out.cancelled || out.timed_out || out.too_long)) ::kill(pid, SIGKILL);
  if (!reaped) reap(0);
  return out;
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGABRT: return "SIGABRT";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    default: return "signal " + std::to_string(sig);
  }
}

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

bool read_all(int fd, std::string& out) {
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    if (n == 0) return true;
    out.append(chunk, static_cast<std::size_t>(n));
  }
}

}  // namespace palpation::sim::self_child
