// palpation bench: step time against error (design.md section 6).
//
// For each mesh level x backend x precision x solver setting, the paper-sweep scenario is
// stepped for a fixed window (dt = 1 ms, the first pushes over the tumour). Per point:
// median and p99 step time (warm-up excluded), CG iterations, and the error against a
// reference run on the same mesh (double, CG to 1e-10): force error = relative L2 norm of
// the finger-force time series, displacement error = relative L2 norm of the node
// displacements at fixed times. References are cached (model cache folder).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace palpation::app::cli {

struct BenchOptions {
  std::vector<std::string> meshes{"coarse", "paper", "xfine"};
  std::vector<std::string> backends;           // empty: every available one
  std::vector<std::string> precisions{"double", "float"};
  int steps = 1000;                            // window length
  bool quick = false;                          // CI subset: coarse, cpu, few settings
  std::string out;                             // folder for bench.json/csv/png
  std::string scenario = "paper-sweep";
  std::string check;                           // "in-step" | "beside" | "auto"; empty: the scenario's
  std::string preconditioner;                  // "block-jacobi" | "multigrid"; empty: the scenario's
  std::string warm_start;                      // "extrapolated" | "last" | "auto"; empty: the scenario's
  std::string element;                         // "linear" | "nodal-pressure"; empty: the scenario's
  double skin = -1;                            // >= 0: the skin membrane's thickness, m (0: none); < 0: the scenario's
  std::string path;                            // "linear" | "monotone-cubic": every finger path's interpolation; empty: the scenario's
  double force_error = 0;                      // > 0: only the error-controlled point, at this target
  std::vector<double> tolerances;              // not empty: only these fixed CG tolerances (cap 1,000)
  bool series = false;                         // also series.csv in `out`: every step of every point
};

struct BenchSetting {
  double tolerance;        // the CG tolerance, or where the error controller starts
  int max_iterations;
  double force_error = 0;  // > 0: the error controller holds this (SolverParams::force_error)
};

/// The columns of series.csv (BenchOptions::series): one row per step of each point, the
/// warm-up steps included (`timed` 0), so that a tail can be traced to its steps.
/// cg_tolerance: the tolerance in force at the step's end (Trace::tolerance).
inline constexpr const char* kSeriesHeader =
    "mesh,backend,precision,setting,step,timed,step_ms,cg_iterations,contacts,cg_tolerance";

/// Runs the sweep; prints the table on stdout. Returns the JSON report.
nlohmann::json run_bench(const BenchOptions& opt);
/// The time to score a 5-minute exam recording (palpation bench --score; bench_score.cpp).
nlohmann::json run_score_bench(const BenchOptions& opt);
/// The memory a review of `recording` keeps, and the time to show a frame (palpation bench
/// --review FILE; bench_review.cpp).
nlohmann::json run_review_bench(const BenchOptions& opt, const std::string& recording);

}  // namespace palpation::app::cli
