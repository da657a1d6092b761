#include "simulation.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace palpation::sim {

int apply_inclusions(Model& m, const std::vector<Inclusion>& inclusions) {
  int changed = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    const Eigen::Vector3d c = 0.25 * (m.rest[t[0]] + m.rest[t[1]] + m.rest[t[2]] + m.rest[t[3]]);
    for (const auto& inc : inclusions)
      if (inc.contains(c)) {
        m.set_element_material(e, inc.young_modulus, inc.poisson_ratio);
        ++changed;
        break;
      }
  }
  return changed;
}

Model build_scenario_model(const Scenario& s, TetMesh mesh) {
  Material tissue{s.young_modulus, s.poisson_ratio, s.density};
  double zmin = std::numeric_limits<double>::max();
  for (const auto& p : mesh.nodes) zmin = std::min(zmin, p.z());
  Model m = build_model(std::move(mesh), tissue, fix_base(zmin + 1e-6));
  apply_inclusions(m, s.inclusions);
  return m;
}

BackendKind parse_backend_kind(const std::string& name) {
  if (name == "cpu") return BackendKind::Cpu;
  if (name == "cuda") return BackendKind::Cuda;
  return BackendKind::Auto;
}

Simulation::Simulation(const Scenario& s, const LogFn& log) : s_(s) {
  model_ = build_scenario_model(s_, patient_mesh(s_, log));
  init(log);
}

Simulation::Simulation(const Scenario& s, Model model, const LogFn& log) : s_(s), model_(std::move(model)) {
  init(log);
}

void Simulation::init(const LogFn& log) {
  SimParams p = s_.params;
  backend_ = make_backend(parse_backend_kind(s_.backend), model_, p, &reason_);
  if (log && !reason_.empty()) log("backend: " + reason_);
  fingers_.resize(s_.fingers.size());
  outputs_.resize(s_.fingers.size());
  for (std::size_t i = 0; i < s_.fingers.size(); ++i) fingers_[i].radius = s_.fingers[i].radius;
}

StepStats Simulation::step() {
  const double t1 = t_ + s_.params.solver.dt;
  for (std::size_t i = 0; i < s_.fingers.size(); ++i) s_.fingers[i].sample(t1, fingers_[i].position, fingers_[i].velocity);
  const StepStats st = backend_->step(fingers_, outputs_);
  t_ = t1;
  ++steps_;
  return st;
}

void Simulation::reset() {
  backend_->reset();
  t_ = 0;
  steps_ = 0;
}

}  // namespace palpation::sim
