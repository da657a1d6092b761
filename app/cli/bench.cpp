#include "cli/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "backend.h"
#include "json_reader.h"
#include "live/headless_run.h"
#include "model_cache.h"
#include "store/output_dir.h"
#include "phantom.h"
#include "cli/plot_png.h"
#include "scenario.h"
#include "simulation.h"
#include "cli/trace.h"

namespace palpation::app::cli {

using live::percentile;
using store::OutputDir;

namespace {

using clock_type = std::chrono::steady_clock;

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& x : v) out += (out.empty() ? "" : ", ") + x;
  return out;
}

std::string now_iso() {
  std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

}  // namespace

nlohmann::json run_bench(const BenchOptions& opt_in) {
  BenchOptions opt = opt_in;
  std::vector<BenchSetting> settings;
  if (opt.quick) {
    opt.meshes = {"coarse"};
    if (opt.backends.empty()) opt.backends = {"cpu"};
    opt.steps = std::min(opt.steps, 300);
    settings = {{1e-6, 500}, {1e-3, 500}, {1e-10, 10}, {1e-3, 500, sim::kDefaultForceError}};
  } else {
    settings = {{3e-2, 1000}, {1e-2, 1000}, {1e-3, 1000}, {1e-4, 1000}, {1e-6, 1000}, {1e-10, 5}, {1e-10, 10}, {1e-10, 20},
                {1e-3, 200, sim::kDefaultForceError}};
  }
  if (!opt.tolerances.empty()) {
    settings.clear();
    for (double t : opt.tolerances) settings.push_back({t, 1000});
  }
  if (opt.force_error > 0) {
    if (opt.tolerances.empty()) settings.clear();
    settings.push_back({1e-3, 200, opt.force_error});
  }
  const auto avail = sim::available_backends();
  if (opt.backends.empty()) opt.backends = avail;
  for (const auto& b : opt.backends)
    if (std::find(avail.begin(), avail.end(), b) == avail.end())
      throw sim::ScenarioError("--backends: \"" + b + "\" is not available here");
  const std::string ref_backend = std::find(avail.begin(), avail.end(), "cuda") != avail.end() ? "cuda" : "cpu";

  nlohmann::json report;
  report["date"] = now_iso();
  report["commit"] = PALPATION_GIT_COMMIT;
  report["scenario"] = opt.scenario;
  report["steps"] = opt.steps;
  report["warmup"] = live::kWarmupSteps;
  report["reference"] = {{"backend", ref_backend}, {"precision", "double"}, {"cg_tolerance", 1e-10}};
  report["points"] = nlohmann::json::array();
  std::ostringstream series;  // series.csv's rows (BenchOptions::series)
  report["floors"] = nlohmann::json::array();
  std::map<std::string, std::string> devices;

  std::printf("%-7s %-9s %-6s %8s %6s | %9s %9s %6s %6s | %10s %10s | %9s %7s\n", "mesh", "backend", "prec", "tol", "cap",
              "med_ms", "p99_ms", "it_med", "it_max", "force_err", "disp_err", "floor_ms", "x_floor");
  for (const auto& level : opt.meshes) {
    sim::Scenario s = sim::builtin_scenario(opt.scenario);
    // A named level, or an edge length in m (a mesh size between the levels: the 800k
    // tetrahedra of the solver targets, say).
    auto edge = sim::resolution_edge(s.patient.phantom, level);
    s.patient.resolution = level;
    if (!edge) {
      char* end = nullptr;
      const double e = std::strtod(level.c_str(), &end);
      if (level.empty() || *end != 0 || !sim::edge_in_range(e))
        throw sim::ScenarioError("--meshes: \"" + level + "\" is neither a level (" + join(sim::resolution_names()) +
                                 ") nor an edge length in " + sim::kEdgeRange);
      edge = e;
      s.patient.resolution.clear();
    }
    s.patient.edge = *edge;
    s.params.solver.dt = 0.001;
    if (!opt.element.empty())
      s.params.element = sim::parse_element(opt.element);
    report["element"] = sim::element_name(sim::resolve_element(s.params.element, s.poisson_ratio));
    if (opt.skin >= 0) s.skin.thickness = opt.skin;
    report["skin_thickness"] = s.skin.thickness;
    if (!opt.path.empty())
      for (auto& f : s.fingers)
        f.interpolation = sim::parse_path_interpolation(opt.path);
    report["path"] = sim::path_interpolation_name(s.fingers.empty() ? sim::PathInterpolation::Linear
                                                                    : s.fingers.front().interpolation);
    if (!opt.preconditioner.empty()) s.params.solver.preconditioner = sim::parse_preconditioner(opt.preconditioner);
    report["preconditioner"] = sim::preconditioner_name(s.params.solver.preconditioner);
    if (!opt.check.empty()) s.params.solver.check = sim::parse_check_place(opt.check);
    if (!opt.warm_start.empty()) s.params.solver.warm_start = sim::parse_warm_start(opt.warm_start);
    report["warm_start"] = sim::warm_start_name(s.params.solver.warm_start);
    const auto t0 = clock_type::now();
    sim::Model model = sim::build_scenario_model(s, sim::patient_mesh(s));
    const double mesh_s = std::chrono::duration<double>(clock_type::now() - t0).count();
    std::fprintf(stderr, "bench: mesh %s: %d nodes, %d tetrahedra (%.2f s to load/mesh and build)\n", level.c_str(),
                 model.num_nodes(), model.num_tets(), mesh_s);

    // Reference: double, CG to 1e-10, cached by mesh hash and scenario.
    sim::Scenario sref = s;
    sref.params.solver.precision = sim::Precision::Double;
    sref.params.solver.cg_tolerance = 1e-10;
    sref.params.solver.cg_max_iterations = 5000;
    sref.params.solver.corotation_tolerance = 0;  // every element's rotation every step
    sref.params.solver.preconditioner = sim::Preconditioner::BlockJacobi;  // any converges to 1e-10; one cached reference
    sref.params.solver.force_error = 0;
    sref.params.solver.check = sim::CheckPlace::Auto;  // no controller, no check: one cached reference whatever --check says
    sref.params.solver.warm_start = sim::WarmStart::Auto;  // at 1e-10 the start changes round-off only: one reference
    const std::string ref_path =
        (std::filesystem::path(sim::cache_dir()) / (trace_cache_key("ref-v3", model, sref, opt.steps) + ".bin")).string();
    Trace ref;
    if (!load_trace(ref_path, ref)) {
      std::fprintf(stderr, "bench: computing the reference for %s on %s (cached in %s)\n", level.c_str(),
                   ref_backend.c_str(), ref_path.c_str());
      ref = run_trace(sref, model, ref_backend, opt.steps);
      // Errors against a reference that did not converge measure nothing: refused, and not
      // cached.
      if (ref.steps_above_tolerance > 0 || !ref.finite)
        throw std::runtime_error("bench: the reference on " + level + " did not converge: " +
                                 std::to_string(ref.steps_above_tolerance) + " of " + std::to_string(opt.steps) +
                                 " steps ended above CG " + sim::JsonReader::fmt(sref.params.solver.cg_tolerance) +
                                 " within " + std::to_string(sref.params.solver.cg_max_iterations) +
                                 " iterations (worst relative residual " + sim::JsonReader::fmt(ref.worst_residual) +
                                 (ref.finite ? ")" : "; not finite)"));
      std::fprintf(stderr, "bench: the reference converged at every step (worst relative residual %.2e)\n",
                   ref.worst_residual);
      save_trace(ref_path, ref);
    }

    // The GPU floor of this mesh (bytes and barriers of one CG iteration, bandwidth and
    // barrier cost measured now): each GPU point is also shown as measured / floor, with
    // floor = step_fixed + (median iterations) x iteration.
    std::map<std::string, sim::FloorEstimate> floors;
    for (const auto& prec : opt.precisions) {
      sim::FloorEstimate fl;
      if (sim::cuda_floor(model, prec == "float" ? sim::Precision::Float : sim::Precision::Double, fl)) floors[prec] = fl;
    }

    for (const auto& backend : opt.backends) {
      if (sim::is_library_baseline(backend) && sim::is_multigrid(s.params.solver.preconditioner)) {
        std::fprintf(stderr, "bench: skipping %s (the multigrid preconditioner runs on the cpu and cuda backends)\n", backend.c_str());
        continue;
      }
      if (backend == "cpu" && !opt.quick && (level == "xfine") &&
          std::find(opt_in.backends.begin(), opt_in.backends.end(), "cpu") == opt_in.backends.end()) {
        std::fprintf(stderr, "bench: skipping cpu on %s (minutes per point; ask with --backends cpu)\n", level.c_str());
        continue;
      }
      for (const auto& prec : opt.precisions) {
        for (const auto& set : settings) {
          sim::Scenario sp = s;
          sp.params.solver.precision = prec == "float" ? sim::Precision::Float : sim::Precision::Double;
          sp.params.solver.cg_tolerance = set.tolerance;
          sp.params.solver.cg_max_iterations = set.max_iterations;
          sp.params.solver.force_error = set.force_error;
          // Float cannot reach 1e-10: the cap decides; skip loose float points that add nothing.
          Trace tr = run_trace(sp, model, backend, opt.steps);
          const std::vector<double> timed = live::after_warmup(tr.step_ms);
          std::vector<double> its(tr.iterations.begin(), tr.iterations.end());
          const double med = percentile(timed, 50), p99 = percentile(timed, 99);
          const double ferr = rel_l2(tr.force, ref.force), derr = displacement_error(tr, ref, model);
          const int itmax = its.empty() ? 0 : int(*std::max_element(its.begin(), its.end()));
          double floor_ms = 0, x_floor = 0;
          if (backend.rfind("cuda", 0) == 0 && floors.count(prec)) {
            const auto& fl = floors[prec];
            floor_ms = (fl.step_fixed_us + percentile(its, 50) * fl.iteration_us) / 1000.0;
            x_floor = floor_ms > 0 ? med / floor_ms : 0;
          }
          char tol[16];
          if (set.force_error > 0)
            std::snprintf(tol, sizeof tol, "fe%g%%", 100 * set.force_error);  // the error controller's target
          else
            std::snprintf(tol, sizeof tol, "%.0e", set.tolerance);
          if (opt.series) {
            const std::size_t warm = tr.step_ms.size() - live::after_warmup(tr.step_ms).size();
            for (std::size_t k = 0; k < tr.step_ms.size(); ++k)
              series << level << ',' << backend << ',' << prec << ',' << tol << ',' << k << ',' << (k >= warm ? 1 : 0) << ','
                     << tr.step_ms[k] << ',' << tr.iterations[k] << ',' << tr.contacts[k] << ',' << tr.tolerance[k] << '\n';
          }
          std::printf("%-7s %-9s %-6s %8s %6d | %9.4f %9.4f %6.0f %6d | %10.2e %10.2e | %9.4f %7.2f%s\n", level.c_str(),
                      backend.c_str(), prec.c_str(), tol, set.max_iterations, med, p99, percentile(its, 50), itmax, ferr, derr,
                      floor_ms, x_floor, tr.finite ? (tr.fallbacks ? "  FELL BACK TO THE CPU" : "") : "  NOT FINITE");
          if (set.force_error > 0)
            std::printf("        error controller: CG tolerance %.2e at the end, %d checks %s (%d over target), worst check %.2e, "
                        "last %.2e; %d divergence resets\n",
                        tr.control.tolerance, tr.control.checks, tr.check_place.c_str(), tr.control.over_target, tr.control.worst_error,
                        tr.control.last_error, tr.divergences);
          if (sim::is_multigrid(tr.preconditioner))
            std::printf("        multigrid: %ld level builds, finest level smoothed by %s (nodal-pressure share %.2f)%s\n",
                        tr.multigrid.builds, tr.multigrid.smoother(), tr.multigrid.pressure_share,
                        tr.multigrid.failures
                            ? (", " + std::to_string(tr.multigrid.failures) + " builds failed (their steps ran block-Jacobi)").c_str()
                            : "");
          std::fflush(stdout);
          if (!devices.count(backend)) devices[backend] = sim::make_named_backend(backend, model, s.params)->device_name();
          report["points"].push_back({{"mesh", level},
                                      {"nodes", model.num_nodes()},
                                      {"tetrahedra", model.num_tets()},
                                      {"backend", backend},
                                      {"device", devices[backend]},
                                      {"precision", prec},
                                      {"cg_tolerance", set.tolerance},
                                      {"cg_max_iterations", set.max_iterations},
                                      {"force_error_target", set.force_error},
                                      {"controlled_cg_tolerance", tr.control.tolerance},
                                      {"controller_checks", tr.control.checks},
                                      {"controller_check_place", tr.check_place},
                                      {"controller_worst_check_error", tr.control.worst_error},
                                      {"divergence_resets", tr.divergences},
                                      {"backend_fallbacks", tr.fallbacks},
                                      {"preconditioner", sim::preconditioner_name(tr.preconditioner)},
                                      {"warm_start", sim::warm_start_name(tr.warm_start)},
                                      {"multigrid_builds", tr.multigrid.builds},
                                      {"multigrid_failures", tr.multigrid.failures},
                                      {"multigrid_smoother", tr.multigrid.smoother()},
                                      {"multigrid_pressure_share", tr.multigrid.pressure_share},
                                      {"step_ms_median", med},
                                      {"step_ms_p99", p99},
                                      {"cg_iterations_median", percentile(its, 50)},
                                      {"cg_iterations_max", itmax},
                                      {"force_error", ferr},
                                      {"displacement_error", derr},
                                      {"finite", tr.finite},
                                      {"floor_ms", floor_ms},
                                      {"x_floor", x_floor},
                                      {"mesh_seconds", mesh_s}});
        }
      }
    }
    // The floor of one CG iteration on this mesh (GPU only).
    for (const auto& [prec, fl] : floors) {
      {
        report["floors"].push_back({{"mesh", level},
                                    {"precision", prec},
                                    {"bytes_per_iteration", fl.bytes_per_iteration},
                                    {"syncs_per_iteration", fl.syncs_per_iteration},
                                    {"bandwidth_gbs", fl.bandwidth_gbs},
                                    {"sync_us", fl.sync_us},
                                    {"iteration_us", fl.iteration_us},
                                    {"step_fixed_us", fl.step_fixed_us},
                                    {"device", fl.device}});
        std::printf("floor %-7s %-6s: %.0f B/iter, %d syncs/iter, %.0f GB/s, %.2f us/sync -> %.2f us/iter + %.2f us/step\n",
                    level.c_str(), prec.c_str(), fl.bytes_per_iteration, fl.syncs_per_iteration, fl.bandwidth_gbs, fl.sync_us,
                    fl.iteration_us, fl.step_fixed_us);
      }
    }
  }
  report["devices"] = devices;

  if (!opt.out.empty()) {
    OutputDir out(opt.out);
    {
      std::ofstream js(out.path("bench.json"));
      js << report.dump(2) << "\n";
    }
    {
      std::ofstream csv(out.path("bench.csv"));
      csv << "mesh,nodes,tetrahedra,backend,device,precision,cg_tolerance,cg_max_iterations,step_ms_median,step_ms_p99,"
             "cg_iterations_median,cg_iterations_max,force_error,displacement_error,finite,date,commit,floor_ms,x_floor,element,preconditioner,"
             "force_error_target\n";
      for (const auto& p : report["points"])
        csv << p["mesh"].get<std::string>() << ',' << p["nodes"] << ',' << p["tetrahedra"] << ',' << p["backend"].get<std::string>()
            << ",\"" << p["device"].get<std::string>() << "\"," << p["precision"].get<std::string>() << ',' << p["cg_tolerance"]
            << ',' << p["cg_max_iterations"] << ',' << p["step_ms_median"] << ',' << p["step_ms_p99"] << ','
            << p["cg_iterations_median"] << ',' << p["cg_iterations_max"] << ',' << p["force_error"] << ','
            << p["displacement_error"] << ',' << (p["finite"].get<bool>() ? "true" : "false") << ',' << report["date"].get<std::string>()
            << ',' << PALPATION_GIT_COMMIT << ',' << p["floor_ms"] << ',' << p["x_floor"] << ','
            << report["element"].get<std::string>() << ',' << p["preconditioner"].get<std::string>() << ','
            << p["force_error_target"] << '\n';
    }
    if (opt.series) {
      std::ofstream csv(out.path("series.csv"));
      csv << kSeriesHeader << '\n' << series.str();
    }
    if (can_plot()) {
      PlotSpec plot;
      plot.title = "Step time against force error (" + opt.scenario + ", dt = 1 ms)";
      plot.xlabel = "force error (relative L2 vs reference)";
      plot.ylabel = "median step time [ms]";
      plot.log_x = plot.log_y = true;
      std::map<std::string, PlotSeries> curves;
      for (const auto& p : report["points"]) {
        const std::string name = p["mesh"].get<std::string>() + " " + p["backend"].get<std::string>() + " " + p["precision"].get<std::string>();
        auto& c = curves[name];
        c.name = name;
        c.markers = true;
        c.dashed = sim::is_library_baseline(p["backend"].get<std::string>());  // the ports it is measured against
        c.x.push_back(std::max(p["force_error"].get<double>(), 1e-12));
        c.y.push_back(p["step_ms_median"].get<double>());
      }
      for (auto& [name, c] : curves) {
        // Sort by error so the curve reads left to right.
        std::vector<std::size_t> idx(c.x.size());
        for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
        std::sort(idx.begin(), idx.end(), [&c](auto a, auto b) { return c.x[a] < c.x[b]; });
        PlotSeries sorted = c;
        for (std::size_t i = 0; i < idx.size(); ++i) {
          sorted.x[i] = c.x[idx[i]];
          sorted.y[i] = c.y[idx[i]];
        }
        plot.series.push_back(sorted);
      }
      write_plot_png(out.path("bench.png"), plot);
    }
    out.commit();
    std::fprintf(stderr, "bench: wrote %s/bench.json, bench.csv%s%s\n", opt.out.c_str(), opt.series ? ", series.csv" : "",
                 can_plot() ? ", bench.png" : "");
  }
  return report;
}

}  // namespace palpation::app::cli
