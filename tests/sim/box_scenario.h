// The box the sim tests press into: a box phantom on the chest wall (its base fixed) of
// the given size and cell edge, 19 kPa tissue at Poisson's ratio 0.45, one CPU thread.
#pragma once

#include <string>

#include "scenario.h"

inline palpation::sim::Scenario box_scenario(const std::string& source, const Eigen::Vector3d& size, double edge,
                                             const std::string& backend = "auto") {
  palpation::sim::Scenario s;
  s.source = source;
  s.patient.phantom = "box";
  s.patient.resolution.clear();
  s.patient.edge = edge;
  s.patient.size = size;
  s.young_modulus = 19000;
  s.poisson_ratio = 0.45;
  s.backend = backend;
  s.params.solver.threads = 1;
  return s;
}

/// The built-in Hertz scene (a 1 cm sphere pressed 1 mm into the 19 kPa box) on the coarse
/// box, in double, its CG solved to `tolerance` (at most 5,000 iterations).
inline palpation::sim::Scenario hertz_coarse_box(double tolerance) {
  palpation::sim::Scenario s = palpation::sim::builtin_scenario("hertz");
  s.patient.resolution = "coarse";
  s.patient.edge = *palpation::sim::resolution_edge("box", "coarse");
  s.params.solver.precision = palpation::sim::Precision::Double;
  s.params.solver.cg_tolerance = tolerance;
  s.params.solver.cg_max_iterations = 5000;
  return s;
}
