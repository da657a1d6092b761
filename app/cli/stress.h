// Numerical-stability stress test (`palpation stress`): a matrix of extreme
// scenarios (time step, stiffness contrast, Poisson ratio, fingers to the chest wall, fast
// and jumping fingers, five fingers squeezing, sliver and inverted elements, long runs),
// each run on every available backend and checked for:
//   finite  - no NaN/Inf anywhere and no divergence event (sim::DivergenceLimits);
//   energy  - kinetic energy and displacement bounded (StressCase::max_speed_ok);
//   device  - after the device safety filter (device/safety_filter.h) every force sent is
//             finite and within the device limit;
//   rest    - after the fingers are lifted the body returns to rest;
//   cg      - every solved step's CG residual met the tolerance.
// docs/stability.md lists the bounds found and where input validation enforces them.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "backend.h"
#include "mesh.h"
#include "scenario.h"

namespace palpation::app::cli {

struct StressCase {
  std::string name;
  std::string group;          // "dt", "contrast", "poisson", "contact", "mesh", "long"
  std::string description;
  sim::Scenario scenario;
  /// Edits the box mesh before the model is built (slivers, inverted elements).
  std::function<void(sim::TetMesh&)> mesh_edit;
  double release_time = 0;    // s, when the last finger has left the body (0: none)
  double max_speed_ok = 5.0;  // m/s, energy bound: no node faster after the first 10 ms
  bool breast = false;        // runs on the coarse breast phantom (needs Gmsh or a cache)
};

struct StressResult {
  std::string name, group, backend, description;
  bool pass = false, skipped = false;
  std::string skip_reason;
  std::vector<std::string> failures;  // one line each
  // Figures.
  int nodes = 0, tets = 0, steps = 0;
  double dt = 0, wall_s = 0, ms_per_step = 0;
  double max_raw_force = 0;           // N, largest simulated finger force
  double max_device_force = 0;        // N, largest force the safety filter sent
  std::uint64_t device_nonfinite = 0, device_over_limit = 0, clamped_ticks = 0;
  double max_speed = 0, max_displacement = 0, max_kinetic_energy = 0;  // after the first 10 ms
  double rest_displacement = -1;      // m, largest |x - rest| at the end (after release)
  double rest_speed = -1;             // m/s, at the end
  int cg_max_iterations = 0, cg_unconverged = 0;
  int cg_rescued = 0;  // steps whose solve went past the cap (SolverParams::cg_rescue_tolerance)
  double cg_worst_residual = 0;
  int divergences = 0;
  double min_quality = -1;            // lowest element quality of an edited mesh (-1: not computed)
  nlohmann::json to_json() const;
};

/// Makes the backend named `name` for a case (default: sim::make_named_backend). Tests
/// inject a failing backend here.
using StressBackendFactory =
    std::function<std::unique_ptr<sim::Backend>(const std::string& name, const sim::Model&, const sim::SimParams&)>;

struct StressOptions {
  std::vector<std::string> backends;  // empty: sim::available_backends()
  bool quick = false;                 // long runs 10,000 steps instead of 100,000
  std::string only;                   // run only cases whose name contains this
  std::function<void(const std::string&)> progress;
  StressBackendFactory make_backend;  // empty: sim::make_named_backend
};

/// The case matrix.
std::vector<StressCase> stress_cases(bool quick);
/// Runs one case on one backend. A case is skipped (skipped, not passed) only when its
/// mesh cannot be had here (the breast without Gmsh or a cached mesh), saying so; a
/// backend that fell back to the CPU mid-run fails it. Other errors propagate.
StressResult run_stress_case(const StressCase& c, const std::string& backend, const StressBackendFactory& make_backend = {});
/// Runs the matrix. An error in a case (an exception: a CUDA error, a failed meshing) is
/// that case's failure, with its message.
std::vector<StressResult> run_stress(const StressOptions& opt);
/// The reports: stress.json and the markdown table of stress.md.
nlohmann::json stress_json(const std::vector<StressResult>& r, const StressOptions& opt, double wall_s);
std::string stress_markdown(const std::vector<StressResult>& r, const StressOptions& opt, double wall_s);

}  // namespace palpation::app::cli
