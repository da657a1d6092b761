// The series a headless run of a scenario produces, for error measurement: `palpation
// bench` (step time against error) and `palpation check-backends` (GPU against CPU) step
// the same way and compare the same figures.
#pragma once

#include <string>
#include <vector>

#include "backend.h"
#include "error_control.h"
#include "model.h"
#include "scenario.h"

namespace palpation::app::cli {

struct Trace {
  std::vector<double> force;               // (steps x fingers x 3) filtered finger force, N
  std::vector<int> iterations, contacts;   // (steps)
  std::vector<double> step_ms;             // (steps) wall time of the backend's step
  std::vector<double> tolerance;           // (steps) the CG tolerance in force at the step's end (the
                                           // error controller's; after a check in the step, the one it then chose)
  std::vector<std::vector<double>> snaps;  // node positions (nnode x 3, m) at snapshot_steps(steps)
  bool finite = true;
  double worst_residual = 0;               // largest relative CG residual a solved step ended at
  int steps_above_tolerance = 0;           // solved steps that ended above the CG tolerance
  sim::ErrorControlStats control;          // the error controller at the end (solver.force_error > 0)
  std::string check_place;                 // where its checks were solved: "in-step", "beside" (none: "")
  int divergences = 0;                     // steps the guard put back at rest
  int fallbacks = 0;                       // the backend failed and the run went on on the CPU
  sim::Backend::MultigridCounts multigrid; // the multigrid builds of the backend at the end
  sim::Preconditioner preconditioner = sim::Preconditioner::Auto;  // the one that ran (Auto resolved)
  sim::WarmStart warm_start = sim::WarmStart::Auto;                // the one that ran (Auto resolved)
};

/// The steps whose positions a trace keeps: N/4, N/2, 3N/4, N.
std::vector<int> snapshot_steps(int steps);

/// Steps the scenario's finger paths for `steps` steps of its dt through Simulation::step
/// (the guarded step every session takes) on a backend by name (sim::make_named_backend);
/// step_ms times that whole step.
Trace run_trace(const sim::Scenario& s, const sim::Model& model, const std::string& backend, int steps);

/// Relative L2 norm of a - ref (absolute when ref is zero; infinite when the sizes differ).
double rel_l2(const std::vector<double>& a, const std::vector<double>& ref);
/// Relative L2 norm of the displacements (x - X) over all snapshots.
double displacement_error(const Trace& a, const Trace& ref, const sim::Model& m);

/// The name of a cached trace of `s` on `model` over `steps` steps (a file in
/// sim::cache_dir()): `kind`, then hashes of the mesh, of the scenario's text and of the
/// finger inputs its steps sample (every finger's centre at every step's end), so a
/// change in how a path is followed between its keys is a new reference even where the
/// scenario's text is the same.
std::string trace_cache_key(const std::string& kind, const sim::Model& model, const sim::Scenario& s, int steps);

/// Cached traces: a binary file (magic, the series, an FNV sum of the forces), written
/// through a temporary file and renamed. load_trace is false for a missing, foreign or
/// damaged file.
bool load_trace(const std::string& path, Trace& t);
void save_trace(const std::string& path, const Trace& t);

}  // namespace palpation::app::cli
