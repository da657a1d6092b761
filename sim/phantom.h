// Phantoms: the built-in patient geometries, and how a scenario's patient becomes a mesh.
#pragma once

#include <functional>
#include <string>

#include <Eigen/Core>

#include "mesh.h"
#include "scenario.h"

namespace palpation::sim {

/// The breast phantom: a half-ellipsoid dome on the chest wall (z = 0, fixed), axis
/// vertical through (center_x, 0). Volume 2/3 pi a^2 c ~ 870 mL, in the typical range
/// (facts.md: 560-975 mL). Its axis is 0.125 m from the body midline (x = 0), so the
/// paper's tumour at x = 0.125 m lies on the axis (central, subareolar), 1.5 cm below
/// the skin: a sweep across it sees the same tissue thickness on both sides.
struct BreastShape {
  double center_x = 0.125;    // m
  double base_radius = 0.08;  // m
  double height = 0.065;      // m
  double skin_edge = 0.0;     // m, target edge at the skin (0: the mesh's edge; PatientSpec)
  /// Height of the skin above the chest wall at (x, y); 0 outside the base.
  double surface_z(double x, double y) const;
  bool contains(const Eigen::Vector3d& p) const;
};

/// The breast mesh cannot be had on this machine: not in the model cache and no Gmsh in
/// this build. Not a fault of the scenario nor of the simulation: callers may skip.
class MeshUnavailable : public ScenarioError {
 public:
  using ScenarioError::ScenarioError;
};

/// Progress/log sink for long steps (meshing): one line per call.
using LogFn = std::function<void(const std::string&)>;

/// Builds the mesh of a scenario's patient: box phantoms by the structured mesher
/// (graded toward the top centre when `grading` > 1), the breast by Gmsh, mesh files by
/// their reader; all through the model cache. Throws ScenarioError on failure, naming
/// the file and the reason (MeshUnavailable when the breast needs Gmsh and has none).
TetMesh patient_mesh(const Scenario& s, const LogFn& log = {});

}  // namespace palpation::sim
