// A scenario made into a running simulation: mesh -> model (tissue, inclusions, fixed
// chest wall) -> backend, and the finger paths sampled each step. Synchronous; owns no
// thread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "backend.h"
#include "model.h"
#include "phantom.h"
#include "scenario.h"

namespace palpation::sim {

/// Builds the model of a scenario from its mesh: bulk tissue, inclusions (elements whose
/// centroid lies inside), chest wall fixed (nodes at z <= 1e-6 m; for a mesh file the
/// lowest nodes within 1e-6 of the minimum z).
Model build_scenario_model(const Scenario& s, TetMesh mesh);

/// Applies inclusions to a model's elements (centroid test). Returns elements changed.
int apply_inclusions(Model& m, const std::vector<Inclusion>& inclusions);

BackendKind parse_backend_kind(const std::string& name);

class Simulation {
 public:
  /// Throws ScenarioError for a bad patient, std::runtime_error for an unavailable backend.
  Simulation(const Scenario& s, const LogFn& log = {});
  /// Uses an already built model (tests, benchmarks sharing one mesh).
  Simulation(const Scenario& s, Model model, const LogFn& log = {});

  const Scenario& scenario() const { return s_; }
  Model& model() { return model_; }
  const Model& model() const { return model_; }
  Backend& backend() { return *backend_; }
  std::string backend_reason() const { return reason_; }

  /// Advances one step: samples the finger paths at t + dt, steps, returns stats.
  StepStats step();
  double time() const { return t_; }
  int steps() const { return steps_; }
  const std::vector<FingerInput>& fingers() const { return fingers_; }
  const std::vector<FingerOutput>& outputs() const { return outputs_; }
  void reset();

 private:
  void init(const LogFn& log);
  Scenario s_;
  Model model_;
  std::unique_ptr<Backend> backend_;
  std::string reason_;
  std::vector<FingerInput> fingers_;
  std::vector<FingerOutput> outputs_;
  double t_ = 0.0;
  int steps_ = 0;
};

}  // namespace palpation::sim
