// The `palpation` command line (design.md section 5): one executable, subcommands.
// Exit codes: 0 success, 2 bad input (one line naming file, field and reason), 1 other
// failures (a broken device, an internal error).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "scenario.h"
#include "store/recording.h"

namespace palpation::app::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

/// A subcommand registers its options on `sub` and returns the action to run.
using CommandAction = std::function<int()>;

/// A scenario argument (a JSON file, a built-in name or "builtin:NAME", or, where the
/// build has the patient library, a built-in patient's name with its default press) with the
/// command-line overrides of --backend, --resolution (empty: none) and --force-error
/// (negative: none) applied.
/// Throws sim::ScenarioError naming the argument.
sim::Scenario load_scenario_arg(const std::string& arg, const std::string& backend = {},
                                const std::string& resolution = {}, double force_error = -1);
/// Adds --force-error to a command that runs a scenario: the solver's force-error target
/// (SolverParams::force_error), 0 for the scenario's CG tolerance kept fixed.
void add_force_error_option(CLI::App* sub, double& force_error);

/// A recording argument, read (app/store/recording.h); a bad file is bad input: throws
/// sim::ScenarioError with the reader's message (file, chunk, offset, reason).
store::Recording read_recording_arg(const std::string& path);

CommandAction add_scenario_command(CLI::App& app);
CommandAction add_run_command(CLI::App& app);
CommandAction add_bench_command(CLI::App& app);
CommandAction add_session_command(CLI::App& app);
CommandAction add_check_backends_command(CLI::App& app);
CommandAction add_stress_command(CLI::App& app);
CommandAction add_replay_command(CLI::App& app);
CommandAction add_score_command(CLI::App& app);
CommandAction add_case_command(CLI::App& app);
CommandAction add_curriculum_command(CLI::App& app);
CommandAction add_convergence_command(CLI::App& app);
CommandAction add_hertz_command(CLI::App& app);
#ifdef PALPATION_HAVE_SQL
CommandAction add_patient_command(CLI::App& app);
CommandAction add_trainee_command(CLI::App& app);
#endif

}  // namespace palpation::app::cli
