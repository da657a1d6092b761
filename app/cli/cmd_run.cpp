// palpation run SCENARIO.json --out DIR: headless run, fingers.csv + summary.json
// (+ forces.png where the build has Qt).
#include <cstdio>
#include <fstream>

#include "cli/cli.h"
#include "live/headless_run.h"
#include "store/output_dir.h"
#include "cli/plot_png.h"
#include "scenario.h"
#include "cli/sweep_analysis.h"

namespace palpation::app::cli {

using live::RunOptions;
using live::RunResult;
using live::run_headless;
using live::write_fingers_csv;
using store::OutputDir;


CommandAction add_run_command(CLI::App& app) {
  auto* sub = app.add_subcommand("run", "Run a scenario headless; writes DIR/fingers.csv and DIR/summary.json");
  struct Opts {
    std::string scenario, out, backend, resolution;
    double force_error = -1;
    bool quiet = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("scenario", o->scenario, "Scenario JSON file (or a built-in name)")->required();
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_option("--backend", o->backend, "Override solver.backend (auto, cpu, cuda)")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}));
  sub->add_option("--resolution", o->resolution, "Override patient.resolution (coarse, paper, fine, xfine)");
  add_force_error_option(sub, o->force_error);
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return [o]() {
    sim::Scenario s = load_scenario_arg(o->scenario, o->backend, o->resolution, o->force_error);
    OutputDir out(o->out);  // created before the run: an unwritable folder fails early
    RunOptions opt;
    opt.progress = !o->quiet;
    if (!o->quiet) opt.log = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    RunResult r = run_headless(s, opt);
    write_fingers_csv(out.path("fingers.csv"), r.samples);
    if (can_plot()) {
      PlotSpec plot;
      plot.title = "Finger x and reaction force fz (" + s.source + ")";
      plot.xlabel = "time [s]";
      plot.ylabel = "fz [N]";
      plot.ylabel_right = "finger x [m]";
      const int nf = static_cast<int>(s.fingers.size());
      for (int f = 0; f < nf; ++f) {
        PlotSeries fz{"fz finger " + std::to_string(f), {}, {}, false, false};
        PlotSeries x{"x finger " + std::to_string(f), {}, {}, true, true};
        for (const auto& smp : r.samples)
          if (smp.finger == f) {
            fz.x.push_back(smp.t);
            fz.y.push_back(smp.f.z());
            x.x.push_back(smp.t);
            x.y.push_back(smp.x.x());
          }
        plot.series.push_back(std::move(fz));
        plot.series.push_back(std::move(x));
      }
      std::string why;
      if (!write_plot_png(out.path("forces.png"), plot, &why)) throw std::runtime_error(why);
    }
    // Sweeps (periodic pushes): the peak of each push and where each pass peaked.
    const SweepAnalysis sweep = analyze_sweep(r.samples);
    if (!sweep.pushes.empty()) r.summary["sweep"] = sweep.to_json();
    {
      std::ofstream js(out.path("summary.json"));
      js << r.summary.dump(2) << "\n";
      if (!js) throw std::runtime_error(out.path("summary.json") + ": write failed");
    }
    out.commit();
    if (!o->quiet)
      std::fprintf(stderr, "run: %d steps, %.3f ms per step (median), backend %s, finite %s -> %s\n",
                   r.summary["steps"].get<int>(), r.summary["step_ms_median"].get<double>(),
                   r.summary["backend"].get<std::string>().c_str(), r.summary["finite"].get<bool>() ? "yes" : "NO",
                   o->out.c_str());
    return r.summary["finite"].get<bool>() ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
