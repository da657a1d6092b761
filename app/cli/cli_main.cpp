#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "scenario.h"

namespace {

// Qt looks up the runtime folder ($XDG_RUNTIME_DIR) when it starts its GUI part (the
// offscreen platform that plots, reports and their fonts need) and, when the variable is
// not set (no desktop session: ssh, a service, CI), warns on stderr. The command line's
// stderr is for its own messages, so without the variable it names the folder Qt would
// have used ($TMPDIR or /tmp, "runtime-USER", private to the user), or, when that one is
// not the user's own, a private folder of its own removed at exit.
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

}  // namespace

int main(int argc, char** argv) {
  using namespace palpation::app::cli;
  set_runtime_dir();
  CLI::App app{"palpation: breast-cancer palpation trainer, command line (see README)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("palpation ") + PALPATION_VERSION + " (" + PALPATION_GIT_COMMIT + ")");
  std::map<CLI::App*, CommandAction> actions;
  auto reg = [&](CommandAction (*add)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    CommandAction a = add(app);
    auto subs = app.get_subcommands({});
    if (subs.size() > before) actions[subs.back()] = std::move(a);
  };
  reg(add_scenario_command);
  reg(add_run_command);
  reg(add_bench_command);
  reg(add_session_command);
  reg(add_check_backends_command);
  reg(add_stress_command);
  reg(add_replay_command);
  reg(add_score_command);
  reg(add_case_command);
  reg(add_curriculum_command);
  reg(add_convergence_command);
#ifdef PALPATION_HAVE_SQL
  reg(add_patient_command);
  reg(add_trainee_command);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : kExitBadInput;
  }
  for (auto& [sub, action] : actions)
    if (sub->parsed()) {
      try {
        return action();
      } catch (const palpation::sim::ScenarioError& e) {
        std::fprintf(stderr, "palpation: %s\n", e.what());
        return kExitBadInput;
      } catch (const std::exception& e) {
        std::fprintf(stderr, "palpation: error: %s\n", e.what());
        return kExitFailure;
      }
    }
  return kExitBadInput;
}
