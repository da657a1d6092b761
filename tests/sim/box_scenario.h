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
