// palpation bench [--quick] [--out DIR] [--meshes ...] [--backends ...] [--precisions ...] [--score] [--review FILE]
#include <cstdio>
#include <string>

#include "cli/bench.h"
#include "cli/cli.h"

namespace palpation::app::cli {

CommandAction add_bench_command(CLI::App& app) {
  auto* sub = app.add_subcommand("bench", "Sweep mesh x backend x precision x solver setting: step time against error");
  auto o = std::make_shared<BenchOptions>();
  sub->add_flag("--quick", o->quick, "Small CPU subset (CI)");
  auto* out = sub->add_option("--out", o->out, "Folder for bench.json, bench.csv, bench.png");
  sub->add_flag("--series", o->series,
                "Also DIR/series.csv: every step of every point (time, CG iterations, contacts, CG tolerance; the warm-up steps marked), "
                "to trace a tail to its steps")
      ->needs(out);
  sub->add_option("--meshes", o->meshes, "Mesh levels (coarse, paper, fine, xfine) or edge lengths in m")->delimiter(',');
  sub->add_option("--backends", o->backends, "Backends (cpu, cuda, cuda-csr, cuda-bsr)")->delimiter(',');
  sub->add_option("--precisions", o->precisions, "double, float")->delimiter(',');
  sub->add_option("--steps", o->steps, "Steps per point")->check(CLI::Range(20, 1000000));
  sub->add_option("--scenario", o->scenario, "Built-in scenario to step (paper-sweep, idle, hertz)");
  sub->add_option("--element", o->element,
                  "Tetrahedral element (linear, nodal-pressure; default: the scenario's, nodal-pressure at Poisson's ratio 0.45 "
                  "and above). The cuda-csr and cuda-bsr baselines have the linear one only")
      ->check(CLI::IsMember(sim::element_names()));
  sub->add_option("--skin", o->skin,
                  "Skin membrane thickness, m (tissue.skin.thickness, 56 kPa unless the scenario says; 0: none; default: the scenario's)")
      ->check(CLI::Range(0.0, sim::kMaxSkinThickness));
  sub->add_option("--path", o->path,
                  "How the finger paths run between their keys (linear, monotone-cubic; default: the scenario's, monotone-cubic "
                  "in the paper sweeps): the same keys either way, to see what the path's velocity jumps cost")
      ->check(CLI::IsMember(sim::path_interpolation_names()));
  sub->add_option("--preconditioner", o->preconditioner,
                  "CG preconditioner (auto, block-jacobi, multigrid, multigrid-chebyshev, multigrid-jacobi; default: the scenario's, auto unless it names one: multigrid on the GPU from " +
                      std::to_string(sim::kGpuMultigridFromNodes) + " nodes, else block-jacobi). Multigrid runs on the cpu and cuda backends: "
                  "the library baselines are skipped")
      ->check(CLI::IsMember(sim::preconditioner_names()));
  sub->add_option("--check", o->check,
                  "Where the error controller's converged check solves its reference (auto, in-step, beside; default: the "
                  "scenario's, auto unless it names one: beside the steps on the cuda backend, on the multiprocessors its solve leaves as "
                  "on the paper mesh, else on the whole GPU a slice at a time after each step as on xfine; in the step on the cpu "
                  "and the library baselines)")
      ->check(CLI::IsMember(sim::check_place_names()));
  sub->add_option("--warm-start", o->warm_start,
                  "How each step's CG starts (auto, extrapolated, last; default: the scenario's, auto unless it names one: last, "
                  "the last solution, extrapolated only after two solves to 3e-3; extrapolated: after every converged solve)")
      ->check(CLI::IsMember(sim::warm_start_names()));
  sub->add_option("--force-error", o->force_error,
                  "Only the error-controlled point, holding this finger-force error (a fraction of the converged force; "
                  "the full sweep has one at 0.01 beside its fixed tolerances), beside those of --tolerances when given")
      ->check(CLI::Range(1e-6, 0.5));
  sub->add_option("--tolerances", o->tolerances,
                  "Only these fixed CG tolerances (cap 1,000 iterations) instead of the full sweep, e.g. 1e-3,1e-6")
      ->delimiter(',')
      ->check(CLI::Range(1e-12, 0.5));
  auto score = std::make_shared<bool>(false);
  sub->add_flag("--score", *score, "Instead: the time to score a 5-minute exam recording (writes DIR/score-bench.json)");
  auto review = std::make_shared<std::string>();
  sub->add_option("--review", *review,
                  "Instead: the memory a review of this recording keeps, re-simulated to its end (writes DIR/review-bench.json)");
  return [o, score, review]() {
    if (!review->empty()) {
      run_review_bench(*o, *review);
      return kExitOk;
    }
    if (*score) {
      run_score_bench(*o);
      return kExitOk;
    }
    run_bench(*o);
    return kExitOk;
  };
}

}  // namespace palpation::app::cli
