#include "cli/cli.h"

#include <filesystem>

#ifdef PALPATION_HAVE_SQL
#include "store/patient_library.h"
#endif

namespace palpation::app::cli {

sim::Scenario load_scenario_arg(const std::string& arg, const std::string& backend, const std::string& resolution) {
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
