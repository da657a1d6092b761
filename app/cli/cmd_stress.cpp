// palpation stress --out DIR [--backend NAME]... [--quick] [--only TEXT]: the numerical
// stability matrix (app/cli/stress.h); writes DIR/stress.json and DIR/stress.md. Exit 0 when
// every case passes, 1 when one fails, 2 on bad input.
#include <chrono>
#include <cstdio>
#include <fstream>

#include "backend.h"
#include "cli/cli.h"
#include "store/output_dir.h"
#include "cli/stress.h"

namespace palpation::app::cli {

using store::OutputDir;

CommandAction add_stress_command(CLI::App& app) {
  auto* sub = app.add_subcommand("stress", "Numerical-stability stress matrix; writes DIR/stress.json and DIR/stress.md");
  struct Opts {
    std::string out, only;
    std::vector<std::string> backends;
    bool quick = false, quiet = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_option("--backend", o->backends, "Backend(s) to run (default: every available one)");
  sub->add_flag("--quick", o->quick, "Long run of 10,000 steps instead of 100,000");
  sub->add_option("--only", o->only, "Run only the cases whose name contains this text");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return [o]() {
    const auto avail = sim::available_backends();
    for (const auto& b : o->backends)
      if (std::find(avail.begin(), avail.end(), b) == avail.end()) {
        std::string list;
        for (const auto& a : avail) list += (list.empty() ? "" : ", ") + a;
        throw sim::ScenarioError("--backend: \"" + b + "\" is not available here (available: " + list + ")");
      }
    OutputDir out(o->out);
    StressOptions opt;
    opt.backends = o->backends;
    opt.quick = o->quick;
    opt.only = o->only;
    if (!o->quiet) opt.progress = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    const auto t0 = std::chrono::steady_clock::now();
    const auto results = run_stress(opt);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (results.empty()) throw sim::ScenarioError("--only: no case name contains \"" + o->only + "\"");
    const auto j = stress_json(results, opt, wall);
    {
      std::ofstream js(out.path("stress.json"));
      js << j.dump(2) << "\n";
      if (!js) throw std::runtime_error(out.path("stress.json") + ": write failed");
      std::ofstream md(out.path("stress.md"));
      md << stress_markdown(results, opt, wall);
      if (!md) throw std::runtime_error(out.path("stress.md") + ": write failed");
    }
    out.commit();
    if (!o->quiet)
      std::fprintf(stderr, "stress: %d passed, %d failed, %d skipped in %.1f s -> %s\n", j["passed"].get<int>(),
                   j["failed"].get<int>(), j["skipped"].get<int>(), wall, o->out.c_str());
    return j["all_pass"].get<bool>() ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
