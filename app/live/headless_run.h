// Runs a scenario headless: the simulation stepped as fast as it goes, finger forces
// sampled at the 1 kHz haptic rate (design.md section 5: fingers.csv, summary.json).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenario.h"
#include "simulation.h"

namespace palpation::app::live {

/// One row of fingers.csv: what a 1 kHz haptic tick sends for one finger.
struct FingerSample {
  double t;
  int finger;
  Eigen::Vector3d x, f;
};

struct RunResult {
  std::vector<FingerSample> samples;   // (ticks x fingers)
  std::vector<double> step_ms;         // wall time per solved step
  std::vector<int> cg_iterations;      // per step
  nlohmann::json summary;
};

struct RunOptions {
  bool progress = false;               // progress lines on stderr
  sim::LogFn log;                      // meshing/backend lines
};

/// Steps left out of every step-time statistic a report quotes (`palpation bench`, `run`,
/// `session`): the first steps pay for the GPU's module load, first-touch allocations and
/// cold caches, and would otherwise set the p99 of a short run.
inline constexpr std::size_t kWarmupSteps = 50;
/// `step_ms` without its first kWarmupSteps (all of it when it has no more than that).
std::vector<double> after_warmup(const std::vector<double>& step_ms);

/// Runs the scenario to its duration. Throws ScenarioError / std::runtime_error.
RunResult run_headless(const sim::Scenario& s, const RunOptions& opt);
/// Same, on an existing simulation (reset first).
RunResult run_headless(sim::Simulation& sim, const RunOptions& opt);

/// Writes fingers.csv (header t,finger,x,y,z,fx,fy,fz).
void write_fingers_csv(const std::string& path, const std::vector<FingerSample>& samples);

/// Median and percentile of a sample (copy sorted), 0 for an empty one.
double percentile(std::vector<double> v, double p);

/// The error controller's record for summaries (run, session), with where its checks were
/// solved (Simulation::check_place): {"force_error_target": 0} alone when it is off.
nlohmann::json error_control_json(const sim::ErrorControlStats& c, const std::string& check_place);

/// Adds the preconditioner and its multigrid levels' record (builds, failures, the finest
/// level's smoother, the nodal-pressure share at the last build) to a summary (run, session).
void add_multigrid_json(nlohmann::json& j, const sim::Simulation& simulation);

}  // namespace palpation::app::live
