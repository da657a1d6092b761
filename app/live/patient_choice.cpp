#include "live/patient_choice.h"

#include "backend.h"
#include "live/workstation.h"

namespace palpation::app::live {

std::vector<std::string> available_backends() { return sim::available_backends(); }

std::optional<sim::Scenario> phantom_patient(const std::string& name) {
  if (name != "phantom:breast" && name != "phantom:box") return std::nullopt;
  sim::Scenario s = default_workstation_scenario();
  if (name == "phantom:box") {
    s.patient.phantom = "box";
    s.patient.size = Eigen::Vector3d(0.1, 0.1, 0.05);
    s.inclusions.clear();
    if (auto e = sim::resolution_edge("box", s.patient.resolution)) s.patient.edge = *e;
  }
  s.source = name;
  return s;
}

std::optional<double> resolution_edge(const std::string& phantom, const std::string& level) {
  return sim::resolution_edge(phantom, level);
}

std::string default_resolution(bool gpu_usable) { return gpu_usable ? "paper" : "coarse"; }

std::string default_resolution() { return default_resolution(sim::cuda_available()); }

bool set_phantom_resolution(sim::Scenario& s, const std::string& level) {
  if (s.patient.phantom.empty()) return false;
  const auto e = sim::resolution_edge(s.patient.phantom, level);
  if (!e) return false;
  s.patient.resolution = level;
  s.patient.edge = *e;
  return true;
}

sim::Scenario case_patient(const std::string& path, const std::string& level) {
  return case_patient(sim::load_scenario(path), path, level);
}

sim::Scenario case_patient(const sim::Scenario& file, const std::string& path, const std::string& level) {
  sim::Scenario s = default_workstation_scenario();
  s.source = path;
  s.patient = file.patient;
  s.young_modulus = file.young_modulus;
  s.poisson_ratio = file.poisson_ratio;
  s.density = file.density;
  s.layers = file.layers;  // the file's tissue, uniform where it names no layers
  s.inclusions = file.inclusions;
  if (!file.patient.phantom.empty() && !set_phantom_resolution(s, level))
    throw sim::ScenarioError(path + ": patient.resolution: unknown level \"" + level + "\" (coarse, paper, fine)");
  return s;
}

}  // namespace palpation::app::live
