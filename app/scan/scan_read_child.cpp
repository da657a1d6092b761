// The scan reader's child process: why a re-executed child and not fork(), see
// sim/self_child.h. Parent: self_child::run (posix_spawn of /proc/self/exe with
// kChildFlag, a socket on the child's stdout, cancel, wall-clock deadline), then the
// child's exit status and message turned into a SurfaceMesh or an ImportError. Child:
// a constructor that runs before main() (before Qt, QtTest or libFuzzer see the
// arguments), sets its limits, reads the file with assimp (read_here) and writes the
// result.
#include "scan/scan_read_child.h"

#include "self_child.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <vector>

extern char** environ;

// AddressSanitizer reserves terabytes of shadow address space at start: an RLIMIT_AS
// would make its every allocation fail, so sanitizer builds (CI's stage 2, the fuzz
// build) run the child without the address-space limit and give ASan the memory budget
// instead (ASAN_OPTIONS max_allocation_size_mb, hard_rss_limit_mb: ASan ends the child,
// without a message); the CPU limit and the wall-clock deadline apply as ever.
#if defined(__SANITIZE_ADDRESS__)
#define PALPATION_SCAN_READER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PALPATION_SCAN_READER_ASAN 1
#endif
#endif

namespace palpation::app::scan::reader {

namespace {

// The child's message on its stdout: magic, kind, counts, then the raw arrays and the
// text. The parent accepts exactly this size, nothing more or less.
constexpr char kMagic[4] = {'P', 'S', 'R', '1'};
enum Kind : std::uint8_t { kOk = 0, kBadFile = 1, kOutOfMemory = 2, kFailed = 3 };
struct Header {
  char magic[4];
  std::uint8_t kind;
  std::uint8_t pad[3];
  std::uint64_t vertices, triangles, text;
};
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "vertices are sent as raw doubles");
static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int), "triangles are sent as raw ints");

constexpr std::uint64_t kGiB = std::uint64_t(1) << 30, kMiB = std::uint64_t(1) << 20;

bool send(Kind kind, const SurfaceMesh* s, const std::string& text) {
  Header h{};
  std::memcpy(h.magic, kMagic, 4);
  h.kind = kind;
  h.vertices = s ? s->vertices.size() : 0;
  h.triangles = s ? s->triangles.size() : 0;
  h.text = text.size();
  return sim::self_child::write_all(STDOUT_FILENO, &h, sizeof h) &&
         (h.vertices == 0 || sim::self_child::write_all(STDOUT_FILENO, s->vertices.data(), h.vertices * sizeof(Eigen::Vector3d))) &&
         (h.triangles == 0 || sim::self_child::write_all(STDOUT_FILENO, s->triangles.data(), h.triangles * sizeof(std::array<int, 3>))) &&
         (text.empty() || sim::self_child::write_all(STDOUT_FILENO, text.data(), text.size()));
}

#ifndef PALPATION_SCAN_READER_ASAN
/// Bytes of address space this process maps now (its executable and libraries).
std::uint64_t mapped_bytes() {
  unsigned long long pages = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%llu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}
#endif

/// The child: argv = {name, kChildFlag, memory bytes, CPU seconds, path}. Returns the
/// exit status; the result goes to stdout (the parent's pipe).
int child_main(int argc, char** argv) {
  if (argc != 5) return 3;
  const std::uint64_t memory = std::strtoull(argv[2], nullptr, 10);
  const double cpu = std::strtod(argv[3], nullptr);
  const std::string path = argv[4];
  const rlimit no_core{0, 0};
  setrlimit(RLIMIT_CORE, &no_core);  // a crash ends quietly
#ifndef PALPATION_SCAN_READER_ASAN
  if (memory > 0) {
    const rlim_t as = static_cast<rlim_t>(mapped_bytes() + memory);
    const rlimit lim{as, as};
    if (setrlimit(RLIMIT_AS, &lim) != 0) return 4;  // never read without the limit
  }
#else
  (void)memory;
#endif
  if (cpu > 0) {
    const rlim_t s = static_cast<rlim_t>(std::ceil(cpu));
    const rlimit lim{s, s + 5};  // SIGXCPU at the soft limit, SIGKILL at the hard one
    if (setrlimit(RLIMIT_CPU, &lim) != 0) return 4;
  }
  try {
    SurfaceMesh s = read_here(path);
    return send(kOk, &s, {}) ? 0 : 5;
  } catch (const ImportError& e) {
    return send(kBadFile, nullptr, e.what()) ? 0 : 5;
  } catch (const std::bad_alloc&) {
    return send(kOutOfMemory, nullptr, {}) ? 0 : 5;
  } catch (const std::exception& e) {
    return send(kFailed, nullptr, e.what()) ? 0 : 5;
  } catch (...) {
    return send(kFailed, nullptr, "unknown exception") ? 0 : 5;
  }
}

#if defined(__GLIBC__)
// glibc passes (argc, argv, envp) to ELF constructors. This runs before main() of any
// executable that links read_surface: started as the reader's child, the process reads
// and ends here (_exit: no static destructors, no atexit handlers, no leak checks).
__attribute__((constructor)) void scan_reader_child_hook(int argc, char** argv, char**) {
  if (argc >= 2 && argv && argv[1] && std::strcmp(argv[1], kChildFlag) == 0) _exit(child_main(argc, argv));
}
#else
#error "the scan reader's child needs glibc (constructor arguments); see scan_read_child.h"
#endif


/// The child's message, or false when it is not exactly one well-formed message.
bool decode(const std::string& b, Kind& kind, SurfaceMesh& s, std::string& text) {
  Header h{};
  if (b.size() < sizeof h) return false;
  std::memcpy(&h, b.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, 4) != 0 || h.kind > kFailed) return false;
  const std::uint64_t rest = b.size() - sizeof h;
  if (h.vertices > rest / sizeof(Eigen::Vector3d) || h.triangles > rest / sizeof(std::array<int, 3>) || h.text > rest)
    return false;
  if (h.vertices * sizeof(Eigen::Vector3d) + h.triangles * sizeof(std::array<int, 3>) + h.text != rest) return false;
  const char* p = b.data() + sizeof h;
  s.vertices.resize(h.vertices);
  s.triangles.resize(h.triangles);
  if (h.vertices) std::memcpy(static_cast<void*>(s.vertices.data()), p, h.vertices * sizeof(Eigen::Vector3d));
  p += h.vertices * sizeof(Eigen::Vector3d);
  if (h.triangles) std::memcpy(static_cast<void*>(s.triangles.data()), p, h.triangles * sizeof(std::array<int, 3>));
  p += h.triangles * sizeof(std::array<int, 3>);
  text.assign(p, h.text);
  kind = static_cast<Kind>(h.kind);
  return true;
}

}  // namespace

std::string memory_words(std::uint64_t bytes) {
  char b[32];
  if (bytes >= kGiB && bytes % kGiB == 0) std::snprintf(b, sizeof b, "%llu GiB", static_cast<unsigned long long>(bytes / kGiB));
  else if (bytes >= kGiB) std::snprintf(b, sizeof b, "%.1f GiB", double(bytes) / double(kGiB));
  else std::snprintf(b, sizeof b, "%llu MiB", static_cast<unsigned long long>((bytes + kMiB / 2) / kMiB));
  return b;
}

Limits limits_for(std::uint64_t file_bytes) {
  Limits l;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const std::uint64_t half_ram = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) / 2 : 2 * kGiB;
  l.memory_bytes = std::max<std::uint64_t>(2 * kGiB, file_bytes <= (~std::uint64_t(0)) / 16 ? 16 * file_bytes : ~std::uint64_t(0));
  l.memory_bytes = std::max<std::uint64_t>(256 * kMiB, std::min(l.memory_bytes, half_ram));
  l.cpu_seconds = 30.0 + 2.0 * double(file_bytes) / 1e6;
  l.wall_seconds = 3.0 * l.cpu_seconds + 30.0;
  return l;
}

Limits limits_for(const std::string& path) {
  std::error_code ec;
  const auto n = std::filesystem::file_size(path, ec);
  return limits_for(ec ? std::uint64_t(0) : std::uint64_t(n));
}

SurfaceMesh read_in_child(const std::string& path, const Limits& lim, const std::function<bool()>& cancelled) {
  // The child (sim/self_child.h): stdin at its end, stdout to us, stderr /dev/null
  // (assimp's messages and a sanitizer's report go nowhere), no other descriptor of this
  // process (the library's database, the device's sockets), no blocked or ignored signals.
  sim::self_child::Job job;
  job.argv = {"palpation-scan-reader", kChildFlag, std::to_string(lim.memory_bytes),
              std::to_string(static_cast<long long>(std::ceil(lim.cpu_seconds))), path};
  job.wall_seconds = lim.wall_seconds;
  job.cancelled = cancelled;
  job.max_output = static_cast<std::size_t>(std::min<std::uint64_t>(lim.memory_bytes + kMiB, SIZE_MAX / 2));
#ifdef PALPATION_SCAN_READER_ASAN
  std::vector<std::string> env_strings;
  std::string asan = "ASAN_OPTIONS=";
  for (char** e = environ; e && *e; ++e) {
    if (std::strncmp(*e, "ASAN_OPTIONS=", 13) == 0) asan = std::string(*e) + ":";
    else env_strings.emplace_back(*e);
  }
  const std::string mb = std::to_string(lim.memory_bytes / kMiB);
  env_strings.push_back(asan + "max_allocation_size_mb=" + mb + ":hard_rss_limit_mb=" + mb);
  std::vector<char*> env_ptrs;
  for (auto& e : env_strings) env_ptrs.push_back(e.data());
  env_ptrs.push_back(nullptr);
  job.envp = env_ptrs.data();
#endif
  sim::self_child::Outcome o;
  try {
    o = sim::self_child::run(job);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": the scan reader could not be started (" + e.what() + ")");
  }
  if (o.cancelled) throw std::runtime_error("cancelled");
  const int status = o.status;
  const rusage& ru = o.usage;
  const double cpu = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  char num[64];
  if (o.timed_out) {
    std::snprintf(num, sizeof num, "%.0f", lim.wall_seconds);
    throw ImportError(path + ": the scan reader did not finish within " + num + " s (stopped): a malformed or hostile file?");
  }
  const std::string limit_words = memory_words(lim.memory_bytes);
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGXCPU || (sig == SIGKILL && cpu >= std::ceil(lim.cpu_seconds))) {
      std::snprintf(num, sizeof num, "%.0f", std::ceil(lim.cpu_seconds));
      throw ImportError(path + ": the scan reader exceeded its " + num + " s CPU-time limit (a malformed or hostile file)");
    }
    if (sig == SIGKILL)
      throw ImportError(path + ": the scan reader was killed (SIGKILL; out of memory?): a malformed or hostile file?");
    throw ImportError(path + ": the scan reader crashed (" + sim::self_child::signal_name(sig) + "): a malformed or hostile file?");
  }
  Kind kind = kFailed;
  SurfaceMesh s;
  std::string text;
  if (o.too_long || !decode(o.output, kind, s, text)) {
    std::snprintf(num, sizeof num, "%d", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    throw ImportError(path + ": the scan reader stopped without a result (exit status " + num + "): a malformed or hostile file?");
  }
  switch (kind) {
    case kOk: return s;
    case kBadFile: throw ImportError(text);
    case kOutOfMemory:
      throw ImportError(path + ": the scan reader exceeded its " + limit_words + " memory limit (a malformed or hostile file)");
    case kFailed: break;
  }
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  if (text.size() > 200) text = text.substr(0, 200) + "...";
  throw ImportError(path + ": the scan reader failed (" + text + "): a malformed or hostile file?");
}

}  // namespace palpation::app::scan::reader
