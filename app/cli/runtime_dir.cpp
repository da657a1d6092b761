#include "cli/runtime_dir.h"

#include <cstdlib>
#include <filesystem>
#include <string>

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

namespace palpation::app::cli {

void set_runtime_dir() {
  if (const char* e = std::getenv("XDG_RUNTIME_DIR"); e && *e) return;
  const char* tmp = std::getenv("TMPDIR");
  const std::string base = tmp && *tmp ? tmp : "/tmp";
  const uid_t uid = ::geteuid();
  const passwd* pw = ::getpwuid(uid);
  const std::string dir = base + "/runtime-" + (pw ? std::string(pw->pw_name) : std::to_string(uid));
  ::mkdir(dir.c_str(), 0700);
  struct stat st {};
  if (::lstat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == uid &&
      ((st.st_mode & 07777) == 0700 || ::chmod(dir.c_str(), 0700) == 0)) {
    ::setenv("XDG_RUNTIME_DIR", dir.c_str(), 1);
    return;
  }
  static std::string own = base + "/palpation-runtime-XXXXXX";
  if (::mkdtemp(own.data()) == nullptr) return;  // Qt warns then, as it would have
  ::setenv("XDG_RUNTIME_DIR", own.c_str(), 1);
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(own, ec);
  });
}

}  // namespace palpation::app::cli
