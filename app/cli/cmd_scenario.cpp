// palpation scenario NAME: prints a built-in scenario as JSON.
#include <cstdio>

#include "cli/cli.h"
#include "scenario.h"

namespace palpation::app::cli {

CommandAction add_scenario_command(CLI::App& app) {
  auto* sub = app.add_subcommand("scenario",
                                 "Print a built-in scenario as JSON (paper-sweep, paper-sweep-no-tumour, their layered twins "
                                 "paper-sweep-layered and paper-sweep-layered-no-tumour, hertz, idle)");
  auto name = std::make_shared<std::string>();
  auto list = std::make_shared<bool>(false);
  sub->add_option("name", *name, "Built-in scenario name");
  sub->add_flag("--list", *list, "List the built-in scenarios");
  return [name, list]() {
    if (*list || name->empty()) {
      for (const auto& n : sim::builtin_scenario_names()) std::printf("%s\n", n.c_str());
      return *list ? kExitOk : kExitBadInput;
    }
    std::printf("%s\n", sim::scenario_to_json(sim::builtin_scenario(*name)).c_str());
    return kExitOk;
  };
}

}  // namespace palpation::app::cli
