// Mesh convergence of what a trainee feels: the same fingertip press, over the first
// tumour, on the patient meshed at several resolutions, with and without the tumour. Per
// level the fingertip force, the tumour/no-tumour contrast and how well the mesh resolves
// each tumour; across levels Richardson's extrapolation to the limit of a fine mesh, so
// an instructor can see what resolution a case needs (`palpation convergence`,
// docs/simulation.md).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "model.h"
#include "phantom.h"
#include "press_probe.h"
#include "scenario.h"

namespace palpation::sim {

/// How one inclusion is meshed.
struct TumourResolution {
  int elements = 0;          // elements given the inclusion's material (centroid inside)
  double volume_ratio = 0;   // their volume over the inclusion's analytic volume
  double mean_edge = 0;      // m, mean edge length of those elements
  double across = 0;         // elements across the smallest diameter: 2 r_min / mean_edge
  /// Resolved: at least kMinAcross elements across and the volume within kVolumeTolerance.
  bool resolved = false;
};
/// At least three elements across the smallest diameter: an interior element between two
/// at the surface, so the stiff region has a core and not only a skin of elements. The
/// breast mesher asks for two elements across the smallest radius (sim/mesh_gmsh.cpp);
/// Gmsh's elements come out longer than asked, and the built-in graded cases measure 3.3
/// to 3.5 across on the coarse breast (tests/app/tst_builtin_cases.cpp).
inline constexpr double kMinAcross = 3.0;
/// The meshed tumour's volume within 10 % of the sphere's or ellipsoid's: the force over a
/// stiff inclusion grows with its volume, and 10 % is below the 15 % Weber fraction for
/// telling two compliances apart (tests/app/tst_builtin_cases.cpp). A faceted sphere of
/// three to four elements across keeps 91-92 % of the volume (the graded cases, coarse).
inline constexpr double kVolumeTolerance = 0.10;

TumourResolution tumour_resolution(const Model& m, const Inclusion& inc);

/// Richardson extrapolation of values f at mesh sizes h (decreasing h, the finest last):
/// f(h) = limit + C h^order fitted to the three finest levels.
struct Extrapolation {
  bool ok = false;
  double limit = std::numeric_limits<double>::quiet_NaN();
  double order = std::numeric_limits<double>::quiet_NaN();
  std::string why;  // when not ok: fewer than three levels, not monotone, order out of range
};
/// The order is solved from (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p) by
/// bisection on p in [0.25, 4]: outside that range the three values are not in the
/// asymptotic regime and no limit is claimed; nor is one that moves the finest value by
/// more than half of it. Equal values give that value, order NaN.
Extrapolation richardson(const std::vector<double>& h, const std::vector<double>& f);

struct ConvergenceOptions {
  /// Levels: named resolutions (coarse, paper, fine, xfine) or edge lengths in m as text;
  /// run coarse to fine whatever their order here.
  std::vector<std::string> levels = {"coarse", "paper", "fine", "xfine"};
  double radius = 0.008;         // m, fingertip (the index finger)
  /// Depth of the press: this fraction of the tissue under the site on the coarsest
  /// level (0.3: the deep press of a clinical examination), held for every level.
  double depth_fraction = 0.3;
  /// The CG tolerance of every step: tight, so that what changes between levels is the
  /// mesh, not the solver (the scenario's tolerance when it is tighter).
  double cg_tolerance = 1e-6;
  PressSchedule schedule;        // quasi-static press: dt 10 ms, 0.4 s ramp, 0.2 s hold
  LogFn log;
};

struct ConvergenceLevel {
  std::string name;          // the level as given
  double edge = 0;           // m, target edge length
  int nodes = 0, tets = 0;
  double force = 0;          // N, normal force at the end of the hold, over the tumour
  double force_plain = 0;    // N, the same press with the tumour's elements given the tissue
  double contrast = std::numeric_limits<double>::quiet_NaN();  // force / force_plain; NaN without a tumour
  std::vector<TumourResolution> tumours;  // one per inclusion
  double seconds = 0;        // wall time of the level (meshing included)
  bool finite = true;
};

struct ConvergenceStudy {
  std::string scenario;
  PressSite site;            // on the coarsest level
  double depth = 0;          // m
  bool has_tumour = false;
  std::vector<ConvergenceLevel> levels;  // coarse to fine
  Extrapolation force, contrast;
  /// The coarsest level from which on what a trainee feels has converged: the contrast
  /// excess (contrast - 1) within 20 % of the extrapolated limit's (without a limit: of
  /// the next finer level's), or within 0.01 near 0; without a tumour the force within
  /// 5 %. Every tumour resolved on it. Empty when no level is (the finest level needs a
  /// limit to be chosen). The force is not required to converge with a tumour: the
  /// device's force scale is set per mesh by a deep press (app/live/force_mapping.h).
  std::string recommended;
};
inline constexpr double kForceTolerance = 0.05;
inline constexpr double kContrastTolerance = 0.20;

/// ConvergenceStudy::recommended from the levels and limits of a study.
std::string recommended_level(const ConvergenceStudy& st);

/// Runs the study. The press is over the first inclusion stiffer than the tissue, else
/// over the highest skin node. Throws ScenarioError for a level that is not a resolution
/// name nor an edge length in [0.0005, 0.05] m, MeshUnavailable when a level cannot be
/// meshed here, and what building a backend throws.
ConvergenceStudy convergence_study(const Scenario& s, const ConvergenceOptions& o = {});

}  // namespace palpation::sim
