// The deep-press probe: the simulated force of one fingertip pressed slowly into a
// patient at rest. A deep press (clinical breast examination: about 30 % of the tissue
// between skin and chest wall, docs/training.md) over the stiffest part of a patient is
// the largest force a palpation asks of the model; the live pipeline maps it into the
// haptic device's range (app/live/force_mapping.h).
//
// The press is the real step (on a copy of the model, with the patient's materials and
// solver settings, on the backend the scenario names: the CPU's for "auto"; the live
// pipeline names the one its patient runs on), at dt = 10 ms: implicit Euler at that dt is
// close to quasi-static for this tissue, and the live workstation steps at up to the same
// dt.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "model.h"
#include "scenario.h"

namespace palpation::sim {

/// A point of the skin to press: where, the outward normal there (smoothed over the
/// fingertip's footprint) and the tissue thickness under it (skin to the far side of the
/// body along -normal: the chest wall for the breast).
struct PressSite {
  Eigen::Vector3d skin = Eigen::Vector3d::Zero();    // m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, outward
  double thickness = 0;                               // m
};

/// The skin point above `p` along the chest wall's outward normal (+z): the highest
/// boundary triangle that the vertical line through p crosses, its normal averaged over
/// the boundary triangles within `footprint` (m) of the hit. nullopt when no boundary
/// triangle lies on that line.
std::optional<PressSite> skin_site_above(const Model& m, const Eigen::Vector3d& p, double footprint = 0.008);

/// What one press gave.
struct PressResult {
  PressSite site;
  double radius = 0;      // m, fingertip
  double depth = 0;       // m, the sphere's reach below the rest skin along -normal
  double force = 0;       // N, |force on the fingertip| at the end of the hold
  double force_normal = 0;  // N, its component along the site's normal
  int steps = 0;
  bool finite = true;
  int multigrid_builds = 0;  // multigrid levels the press's solver built (Backend::multigrid_counts)
};

/// Timing of a probe press: from `clearance` above the skin down to the depth over
/// `ramp` s, then held for `hold` s, in steps of `dt`.
struct PressSchedule {
  double dt = 0.01;         // s
  double ramp = 0.4;        // s
  double hold = 0.2;        // s
  double clearance = 0.002; // m
};

/// Presses a fingertip of `radius` into the body at rest with the given element
/// materials (s's solver and contact settings, the backend s names, the CPU's for
/// "auto"). Throws what building the backend throws.
PressResult press_probe(const Scenario& s, const Model& m, const Materials& materials, const PressSite& site,
                        double radius, double depth, const PressSchedule& schedule = {});

/// The stiffest deep press of a patient.
struct DeepPress {
  PressResult press;                // the largest force among the sites tried
  std::vector<PressResult> tried;   // every site, in the order tried
  double depth_fraction = 0.3;
};

/// Sites tried, each pressed to depth_fraction of its thickness: above the centre of every
/// inclusion of `s` stiffer than the tissue, above the stiffest element of `materials` when
/// it is stiffer than the tissue and outside those inclusions (a painted tumour), and above
/// the highest skin node (the thickest tissue: the apex of the breast). Sites closer than
/// the fingertip's radius to one already tried are skipped. `tried` is empty when no site
/// has skin above it. The presses precondition with block-Jacobi whatever `s` names: a few
/// presses do not repay a multigrid's levels, built on the host when each press's
/// simulation loads (11 s on xfine), and the force converges to the same tolerance.
DeepPress deep_press(const Scenario& s, const Model& m, const Materials& materials, double radius,
                     double depth_fraction = 0.3, const PressSchedule& schedule = {});

}  // namespace palpation::sim
