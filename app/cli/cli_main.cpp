#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "cli/cli.h"
#include "cli/runtime_dir.h"
#include "scenario.h"

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
  reg(add_hertz_command);
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
