// palpation check-backends: GPU against CPU on the same scenes (agreement).
//
// For each scenario (default: paper-sweep and hertz) and element (default: linear and
// nodal-pressure; the library baselines have the linear one only) the CPU backend in double precision
// and each CUDA backend are stepped for N steps (default 1,000) with a tight CG tolerance
// (default 1e-10 on both, so that the solvers' own tolerance does not dominate), and
// compared:
//   force     relative L2 norm of the difference of the filtered finger-force series;
//   position  relative L2 norm of the difference of all node positions, at the last step
//             (worst of four snapshots: N/4, N/2, 3N/4, N);
//   disp.     the same over the displacements (x - X) of the four snapshots (stricter).
// Double on the GPU must agree within --limit (1e-6); float on the GPU (CG tolerance
// --float-cg-tolerance) against the CPU in double within --float-limit (2e-2: float
// arithmetic itself, on the CPU too, is 1.33e-2 off on the Hertz scene with triangle
// contact (4.7e-3 with vertex contact), where the first touch of a flat face decides the
// contacts by a rounding of the positions; the paper sweep is 3e-6 off. docs/gpu-notes.md,
// section 4). Exit 0 when everything agrees, 1 on any disagreement,
// 77 when there is no usable GPU (nothing compared).
//
// Qt-free on purpose: the GPU machine has no Qt. The CPU traces are cached in the model
// cache folder (they take minutes on a small machine and do not depend on the GPU).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "backend.h"
#include "cli/cli.h"
#include "live/headless_run.h"
#include "model_cache.h"
#include "store/output_dir.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"
#include "cli/trace.h"

namespace palpation::app::cli {

using live::percentile;
using store::OutputDir;

namespace {

struct CheckOptions {
  std::vector<std::string> scenarios{"paper-sweep", "hertz"};
  std::vector<std::string> backends;  // empty: every CUDA backend available
  std::vector<std::string> elements = sim::element_names();  // tissue.element, each scenario with each
  std::string resolution;             // empty: each scenario's own
  int steps = 1000;
  double tolerance = 1e-10;
  int max_iterations = 5000;
  double limit = 1e-6;
  double float_cg_tolerance = 1e-6;
  double float_limit = 2e-2;
  bool with_float = true;
  bool no_cache = false;
  bool cpu_only = false;  // only compute (and cache) the CPU references
  std::string out;
};

struct Comparison {
  double force = 0, force_max = 0, position = 0, displacement = 0;
  int first_step = -1;  // first step whose force deviates by more than the limit (x max |F|)
  double its_mean = 0, its_mean_ref = 0, ms_median = 0, ms_median_ref = 0;
};

Comparison compare(const Trace& a, const Trace& ref, const sim::Model& m, int nfing, double limit) {
  Comparison c;
  c.force = rel_l2(a.force, ref.force);
  double fmax = 0;
  for (std::size_t i = 0; i + 2 < ref.force.size(); i += 3)
    fmax = std::max(fmax, std::hypot(ref.force[i], ref.force[i + 1], ref.force[i + 2]));
  const std::size_t per_step = 3 * std::size_t(std::max(nfing, 1));
  for (std::size_t i = 0; i + 2 < ref.force.size() && i + 2 < a.force.size(); i += 3) {
    const double d = std::hypot(a.force[i] - ref.force[i], a.force[i + 1] - ref.force[i + 1], a.force[i + 2] - ref.force[i + 2]);
    const double rel = fmax > 0 ? d / fmax : d;
    c.force_max = std::max(c.force_max, rel);
    if (c.first_step < 0 && rel > limit) c.first_step = static_cast<int>(i / per_step) + 1;
  }
  for (std::size_t s = 0; s < ref.snaps.size() && s < a.snaps.size(); ++s)
    c.position = std::max(c.position, rel_l2(a.snaps[s], ref.snaps[s]));
  if (a.snaps.size() != ref.snaps.size()) c.position = INFINITY;
  c.displacement = displacement_error(a, ref, m);
  auto mean = [](const std::vector<int>& v) {
    double s = 0;
    for (int x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
  };
  c.its_mean = mean(a.iterations);
  c.its_mean_ref = mean(ref.iterations);
  c.ms_median = percentile(live::after_warmup(a.step_ms), 50);
  c.ms_median_ref = percentile(live::after_warmup(ref.step_ms), 50);
  return c;
}

int run_check(const CheckOptions& o) {
  std::string why;
  const bool cpu_vs_cpu = !o.backends.empty() && std::all_of(o.backends.begin(), o.backends.end(),
                                                             [](const std::string& b) { return b == "cpu"; });
  if (!o.cpu_only && !cpu_vs_cpu && !sim::cuda_available(&why)) {
    std::printf("check-backends: SKIP: %s (nothing to compare)\n", why.c_str());
    return 77;
  }
  std::vector<std::string> backends = o.backends;
  if (backends.empty())
    for (const auto& b : sim::available_backends())
      if (b != "cpu") backends.push_back(b);

  nlohmann::json report;
  report["commit"] = PALPATION_GIT_COMMIT;
  report["steps"] = o.steps;
  report["cg_tolerance"] = o.tolerance;
  report["limit"] = o.limit;
  report["float_limit"] = o.float_limit;
  report["float_cg_tolerance"] = o.float_cg_tolerance;
  report["results"] = nlohmann::json::array();
  bool all_ok = true;

  std::printf("%-22s %-9s %-6s | %9s %9s %9s %9s | %6s %6s | %8s %8s | %s\n", "scenario", "backend", "prec", "force", "force_max",
              "position", "disp", "its", "its_cpu", "ms", "ms_cpu", "verdict");
  for (const auto& name : o.scenarios) {
    sim::Scenario s = sim::builtin_scenario(name);
    if (!o.resolution.empty()) {
      auto e = sim::resolution_edge(s.patient.phantom, o.resolution);
      if (!e) throw sim::ScenarioError("--resolution: unknown level \"" + o.resolution + "\"");
      s.patient.resolution = o.resolution;
      s.patient.edge = *e;
    }
    const sim::Model model = sim::build_scenario_model(s, sim::patient_mesh(s));
    std::fprintf(stderr, "check-backends: %s: %d nodes, %d tetrahedra\n", name.c_str(), model.num_nodes(), model.num_tets());
    if (!o.cpu_only && !cpu_vs_cpu) {
      std::string reason;
      sim::Scenario sa = s;
      auto b = sim::make_backend(sim::BackendKind::Auto, model, sa.params, &reason);
      std::fprintf(stderr, "check-backends: solver.backend auto -> %s\n", reason.c_str());
      if (b->name() != "cuda") {
        std::printf("check-backends: FAIL: auto picked %s although a GPU is usable\n", b->name().c_str());
        all_ok = false;
      }
    }
    for (const auto& element : o.elements) {
      const bool nodal = sim::parse_element(element) == sim::Element::NodalPressure;
      const std::string label = nodal ? name + "/nodal" : name;
      sim::Scenario sd = s;
      sd.params.solver.precision = sim::Precision::Double;
      sd.params.solver.cg_tolerance = o.tolerance;
      sd.params.solver.force_error = 0;  // the same fixed tolerance on both sides
      sd.params.solver.cg_max_iterations = o.max_iterations;
      sd.params.solver.corotation_tolerance = 0;  // the CPU updates every element every step, as the GPU does
      sd.params.element = sim::parse_element(element);

      // CPU reference, cached.
      // v4: the finger inputs hashed too; bump whenever the CPU step changes results.
      const std::string path =
          (std::filesystem::path(sim::cache_dir()) / (trace_cache_key("cpu-trace-v4", model, sd, o.steps) + ".bin")).string();
      Trace cpu;
      if (o.no_cache || !load_trace(path, cpu)) {
        std::fprintf(stderr, "check-backends: %s: CPU reference (%d steps, CG %.0e) -> %s\n", label.c_str(), o.steps,
                     o.tolerance, path.c_str());
        cpu = run_trace(sd, model, "cpu", o.steps);
        save_trace(path, cpu);
      } else {
        std::fprintf(stderr, "check-backends: %s: CPU reference from %s\n", label.c_str(), path.c_str());
      }

      if (o.cpu_only) continue;
      struct Run {
        std::string backend;
        sim::Precision prec;
        double limit;
      };
      std::vector<Run> runs;
      for (const auto& b : backends)
        if (b != "cpu" && !(nodal && sim::is_library_baseline(b)))  // the baselines have the linear element only
          runs.push_back({b, sim::Precision::Double, o.limit});
      // Float on the GPU; "cpu" in --backends adds float on the CPU: the error that float
      // arithmetic itself brings, whichever device runs it.
      if (o.with_float)
        for (const auto& b : backends)
          if (b == "cuda" || b == "cpu") runs.push_back({b, sim::Precision::Float, o.float_limit});
      for (const auto& r : runs) {
        sim::Scenario sg = sd;
        sg.params.solver.precision = r.prec;
        if (r.prec == sim::Precision::Float) {
          sg.params.solver.cg_tolerance = o.float_cg_tolerance;
          sg.params.solver.cg_max_iterations = 1000;
        }
        Trace g;
        std::string error;
        try {
          g = run_trace(sg, model, r.backend, o.steps);
          // The run goes through Simulation, which survives a backend error on the CPU:
          // that is not the backend under test agreeing.
          if (g.fallbacks > 0) error = r.backend + " failed and the run went on on the cpu";
        } catch (const std::exception& e) {
          error = e.what();
        }
        const char* prec = r.prec == sim::Precision::Float ? "float" : "double";
        if (!error.empty()) {
          std::printf("%-22s %-9s %-6s | FAILED: %s\n", label.c_str(), r.backend.c_str(), prec, error.c_str());
          all_ok = false;
          report["results"].push_back({{"scenario", label}, {"backend", r.backend}, {"precision", prec}, {"error", error}});
          continue;
        }
        const int nfing = static_cast<int>(s.fingers.size());
        const Comparison c = compare(g, cpu, model, nfing, r.limit);
        const bool ok = g.finite && c.force <= r.limit && c.position <= r.limit && c.displacement <= r.limit;
        all_ok = all_ok && ok;
        std::printf("%-22s %-9s %-6s | %9.2e %9.2e %9.2e %9.2e | %6.1f %6.1f | %8.3f %8.3f | %s", label.c_str(),
                    r.backend.c_str(), prec, c.force, c.force_max, c.position, c.displacement, c.its_mean, c.its_mean_ref,
                    c.ms_median, c.ms_median_ref, ok ? "ok" : "DISAGREE");
        if (!ok && c.first_step > 0) {
          const int k = c.first_step - 1;
          std::printf(" (first deviation at step %d: contacts %d/%d, iterations %d/%d)", c.first_step, g.contacts[k],
                      cpu.contacts[k], g.iterations[k], cpu.iterations[k]);
        }
        std::printf("%s\n", g.finite ? "" : " NOT FINITE");
        std::fflush(stdout);
        report["results"].push_back({{"scenario", label},
                                     {"nodes", model.num_nodes()},
                                     {"tetrahedra", model.num_tets()},
                                     {"backend", r.backend},
                                     {"precision", prec},
                                     {"limit", r.limit},
                                     {"force_error", c.force},
                                     {"force_max_error", c.force_max},
                                     {"position_error", c.position},
                                     {"displacement_error", c.displacement},
                                     {"cg_iterations_mean", c.its_mean},
                                     {"cg_iterations_mean_cpu", c.its_mean_ref},
                                     {"step_ms_median", c.ms_median},
                                     {"step_ms_median_cpu", c.ms_median_ref},
                                     {"finite", g.finite},
                                     {"ok", ok}});
      }
    }
  }
  report["ok"] = all_ok;
  if (!o.out.empty()) {
    OutputDir out(o.out);
    std::ofstream(out.path("check.json")) << report.dump(2) << "\n";
    out.commit();
  }
  std::printf("check-backends: %s\n", all_ok ? "all backends agree" : "DISAGREEMENT");
  return all_ok ? kExitOk : kExitFailure;
}

}  // namespace

CommandAction add_check_backends_command(CLI::App& app) {
  auto* sub = app.add_subcommand("check-backends",
                                 "GPU against CPU on the same scenes: forces and positions after N steps (exit 1 on "
                                 "disagreement, 77 without a GPU)");
  auto o = std::make_shared<CheckOptions>();
  sub->add_option("--scenarios", o->scenarios, "Built-in scenarios (paper-sweep, hertz, ...)")->delimiter(',');
  sub->add_option("--backends", o->backends,
                  "Backends to check (cuda, cuda-csr, cuda-bsr; cpu adds float on the CPU against double); default all GPU ones")
      ->delimiter(',');
  sub->add_option("--elements", o->elements, "tissue.element values to check each scenario with (linear, nodal-pressure)")
      ->delimiter(',')
      ->check(CLI::IsMember(sim::element_names()));
  sub->add_option("--resolution", o->resolution, "Override patient.resolution (coarse, paper, ...)");
  sub->add_option("--steps", o->steps, "Steps per run")->check(CLI::Range(4, 1000000));
  sub->add_option("--tolerance", o->tolerance, "CG tolerance of both (double) runs")->check(CLI::PositiveNumber);
  sub->add_option("--limit", o->limit, "Largest relative difference allowed, double")->check(CLI::PositiveNumber);
  sub->add_option("--float-cg-tolerance", o->float_cg_tolerance, "CG tolerance of the float GPU run")
      ->check(CLI::PositiveNumber);
  sub->add_option("--float-limit", o->float_limit, "Largest relative difference allowed, float GPU vs double CPU")
      ->check(CLI::PositiveNumber);
  sub->add_flag("!--no-float", o->with_float, "Skip the float GPU run");
  sub->add_flag("--no-cache", o->no_cache, "Recompute the CPU reference even when cached");
  sub->add_flag("--cpu-only", o->cpu_only, "Only compute and cache the CPU references (no GPU needed)");
  sub->add_option("--out", o->out, "Folder for check.json");
  return [o]() { return run_check(*o); };
}

}  // namespace palpation::app::cli
