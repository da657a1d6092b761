#include "cli/cli.h"

#include <filesystem>

#ifdef PALPATION_HAVE_SQL
#include "store/patient_library.h"
#endif

namespace palpation::app::cli {

void add_force_error_option(CLI::App* sub, double& force_error) {
  sub->add_option("--force-error", force_error,
                  "Override solver.force_error: the finger-force error the CG tolerance is chosen to hold, a fraction of the "
                  "converged force (0: the scenario's cg_tolerance, fixed)")
      ->check(CLI::Range(0.0, 0.5));
}

sim::Scenario load_scenario_arg(const std::string& arg, const std::string& backend, const std::string& resolution,
                                double force_error) {
  sim::Scenario s;
  bool builtin = false;
  for (const auto& n : sim::builtin_scenario_names())
    if (arg == n || arg == "builtin:" + n) {
      s = sim::builtin_scenario(n);
      builtin = true;
    }
#ifdef PALPATION_HAVE_SQL
  // A built-in patient of the library (no file of that name here): its default press.
  if (!builtin && !std::filesystem::exists(arg))
    for (const auto& p : store::PatientLibrary::builtin_patients())
      if (p.name == arg) {
        s = sim::parse_scenario(store::patient_scenario(p).dump(), p.name);
        builtin = true;
      }
#endif
  if (!builtin) s = sim::load_scenario(arg);
  if (!backend.empty()) s.backend = backend;
  if (force_error >= 0) s.params.solver.force_error = force_error;
  if (!resolution.empty()) {
    auto e = sim::resolution_edge(s.patient.phantom, resolution);
    if (!e) throw sim::ScenarioError("--resolution: unknown level \"" + resolution + "\"");
    s.patient.resolution = resolution;
    s.patient.edge = *e;
  }
  return s;
}

store::Recording read_recording_arg(const std::string& path) {
  try {
    return store::read_recording(path);
  } catch (const store::RecordingError& e) {
    throw sim::ScenarioError(e.what());
  }
}

}  // namespace palpation::app::cli
