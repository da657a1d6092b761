// The force scale between the simulation and the haptic device: the device renders
// s * F_sim (and stiffness s * K, so that the local contact model stays consistent), with
// the safety filter's clamp left as the safety bound only.
//
// Why: the tissue model pushes back harder than the HandHIRO may push (default patient: a
// deep press over the paper's tumour gives 5.8 N simulated quasi-static, the paper's sweep
// 4.3-6.3 N per push, more at real-time dt; the device's limit is 4 N per finger). Sent
// unscaled, every deep press reaches the clamp and feels the same, and the tumour's extra
// force is cut off. A scale below 1 keeps the palpation range, tumour included, inside the
// device's (docs/simulation.md, "Force scale").
//
// The rule, per patient and device: a deep press (30 % of the local tissue thickness, the
// training's deep level) of one fingertip over the stiffest part of the patient
// (sim/press_probe.h) maps to `deep_press_share` (90 %) of the device's limit:
//   s = min(1, share * max_force / F_deep)
// A scale only attenuates (never above 1). The device configuration may fix s instead
// ("force_mapping": {"scale": 0.5}).
//
// Where it applies: the simulation thread builds the contact models it publishes for the
// haptic loop (app/live/simulation_loop.h) with the scale, so the haptic loop, the
// virtual coupling's proxy and the safety filter all work in device units; what the
// simulation reports (StepSample::force, the review's re-simulation, the training's
// pressure levels) stays in simulated units, what the device is sent (TickSample::force,
// fingers.csv of `palpation session`) is in device units.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include <Eigen/Core>

#include "model.h"
#include "press_probe.h"
#include "scenario.h"
#include "simulation.h"

namespace palpation::app::live {

/// The device configuration's part (resources/handhiro.json, "force_mapping").
struct ForceMappingConfig {
  double scale = 0;               // > 0: this scale for every patient (at most 1); 0: per patient ("auto")
  double deep_press_share = 0.9;  // the deep press maps to this share of the device's limit
  double deep_press_depth = 0.3;  // deep press: this fraction of the local tissue thickness
};

/// How the scale was chosen.
enum class ForceScaleRule {
  Unscaled,     // s = 1: nothing measured yet (or no skin to press)
  Patient,      // from the patient's deep press
  Configured,   // the device configuration's fixed scale
};
/// "unscaled", "patient", "configured".
inline const char* force_scale_rule_name(ForceScaleRule r) {
  switch (r) {
    case ForceScaleRule::Unscaled: return "unscaled";
    case ForceScaleRule::Patient: return "patient";
    case ForceScaleRule::Configured: return "configured";
  }
  return "";
}

/// The scale in use and where it came from (plain data: it travels with every StepSample).
struct ForceMapping {
  double scale = 1.0;             // device force per simulated force, in (0, 1]
  ForceScaleRule rule = ForceScaleRule::Unscaled;
  double device_limit_n = 0;      // N per finger (the safety filter's clamp)
  double deep_press_n = 0;        // N, simulated force of the deep press (0: none measured)
  double deep_press_device_n = 0; // N, the same as sent to the device: scale * deep_press_n
  double simulated_at_limit_n = 0;  // N, the simulated force that reaches the device's limit
  double deep_press_share = 0.9;  // the rule's settings (ForceMappingConfig)
  double deep_press_depth = 0.3;
  Eigen::Vector3d press_skin = Eigen::Vector3d::Zero();  // m, world: where the deep press was
  double press_depth_m = 0, thickness_m = 0;            // its depth and the tissue under it
  int presses = 0;                // sites pressed
  double probe_ms = 0;            // wall time of the probe
};

/// The scale for a measured deep press (N, simulated; <= 0 or not finite: none) against a
/// device limit (N), by the rule above or the configuration's fixed scale.
inline ForceMapping force_mapping_for(double deep_press_n, double device_limit_n, const ForceMappingConfig& cfg) {
  ForceMapping fm;
  fm.device_limit_n = device_limit_n;
  fm.deep_press_share = cfg.deep_press_share;
  fm.deep_press_depth = cfg.deep_press_depth;
  fm.deep_press_n = std::isfinite(deep_press_n) && deep_press_n > 0 ? deep_press_n : 0.0;
  if (cfg.scale > 0) {
    fm.scale = std::min(1.0, cfg.scale);
    fm.rule = ForceScaleRule::Configured;
  } else if (fm.deep_press_n > 0 && device_limit_n > 0) {
    fm.scale = std::min(1.0, cfg.deep_press_share * device_limit_n / fm.deep_press_n);
    fm.rule = ForceScaleRule::Patient;
  }
  fm.deep_press_device_n = fm.scale * fm.deep_press_n;
  fm.simulated_at_limit_n = device_limit_n / fm.scale;
  return fm;
}

/// Measures the deep press of `simulation`'s patient (sim::deep_press on a copy of its
/// model with its current materials, fingertip `radius` m, on a backend of the kind it
/// runs on: the GPU's when it runs there, a sixth of the CPU's time on the paper mesh and a
/// tenth on xfine; the CPU's when that kind cannot be made again) and chooses the scale.
/// With a configured scale nothing is pressed. The probe's CPU threads are the patient's
/// backend's (configure_realtime_threads may have set them below the scenario's).
inline ForceMapping measure_force_mapping(const sim::Simulation& simulation, double radius, double device_limit_n,
                                          const ForceMappingConfig& cfg) {
  if (cfg.scale > 0) return force_mapping_for(0.0, device_limit_n, cfg);
  const auto t0 = std::chrono::steady_clock::now();
  sim::Scenario ps = simulation.scenario();
  ps.backend = simulation.backend().name();
  ps.params.solver.threads = simulation.backend().params().solver.threads;
  sim::DeepPress dp;
  try {
    dp = sim::deep_press(ps, simulation.model(), simulation.materials(), radius, cfg.deep_press_depth);
  } catch (const std::exception&) {
    // A second backend of that kind could not be made (the GPU's memory, a device lost
    // since the patient's was): the CPU's press, as on a machine without one.
    if (ps.backend == "cpu") throw;
    ps.backend = "cpu";
    dp = sim::deep_press(ps, simulation.model(), simulation.materials(), radius, cfg.deep_press_depth);
  }
  ForceMapping fm = force_mapping_for(dp.press.finite ? dp.press.force : 0.0, device_limit_n, cfg);
  fm.press_skin = dp.press.site.skin;
  fm.press_depth_m = dp.press.depth;
  fm.thickness_m = dp.press.site.thickness;
  fm.presses = int(dp.tried.size());
  fm.probe_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return fm;
}

}  // namespace palpation::app::live
