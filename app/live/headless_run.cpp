#include "live/headless_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>

namespace palpation::app::live {

using clock_type = std::chrono::steady_clock;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = p / 100.0 * double(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

std::vector<double> after_warmup(const std::vector<double>& step_ms) {
  if (step_ms.size() <= kWarmupSteps) return step_ms;
  return std::vector<double>(step_ms.begin() + std::ptrdiff_t(kWarmupSteps), step_ms.end());
}

RunResult run_headless(const sim::Scenario& s, const RunOptions& opt) {
  const auto t0 = clock_type::now();
  sim::Simulation simulation(s, opt.log);
  const double setup_s = std::chrono::duration<double>(clock_type::now() - t0).count();
  RunResult r = run_headless(simulation, opt);
  r.summary["setup_seconds"] = setup_s;
  return r;
}

RunResult run_headless(sim::Simulation& simulation, const RunOptions& opt) {
  simulation.reset();
  const sim::Scenario& s = simulation.scenario();
  const double tick = 0.001;  // the haptic rate, 1 kHz
  const long ticks = std::lround(s.duration / tick);
  const int nf = static_cast<int>(s.fingers.size());
  RunResult r;
  r.samples.reserve(std::size_t(ticks) * std::size_t(nf));
  r.step_ms.reserve(std::size_t(s.duration / s.params.solver.dt) + 1);
  bool finite = true;
  int cg_max = 0, skipped = 0, not_converged = 0;
  double max_force = 0;
  std::vector<Eigen::Vector3d> step_pos(nf, Eigen::Vector3d::Zero());
  const auto wall0 = clock_type::now();
  auto last_progress = wall0;
  for (long k = 1; k <= ticks; ++k) {
    const double tk = double(k) * tick;
    while (simulation.time() < tk - 1e-9) {
      const auto a = clock_type::now();
      const sim::StepStats st = simulation.step();
      const double ms = std::chrono::duration<double, std::milli>(clock_type::now() - a).count();
      if (st.solved) {
        r.step_ms.push_back(ms);
        if (st.cg_iterations >= s.params.solver.cg_max_iterations) ++not_converged;
      } else {
        ++skipped;
      }
      r.cg_iterations.push_back(st.cg_iterations);
      cg_max = std::max(cg_max, st.cg_iterations);
      finite = finite && st.finite;
      for (int f = 0; f < nf; ++f) step_pos[f] = simulation.fingers()[f].position;
    }
    for (int f = 0; f < nf; ++f) {
      Eigen::Vector3d x, v;
      s.fingers[f].sample(tk, x, v);
      const sim::FingerOutput& o = simulation.outputs()[f];
      // Between simulation updates (dt > 1 ms) the local contact model extrapolates.
      Eigen::Vector3d force = o.force;
      if (o.contacts > 0) force += o.stiffness * (x - step_pos[f]);
      if (!force.allFinite()) finite = false;
      max_force = std::max(max_force, force.norm());
      r.samples.push_back({tk, f, x, force});
    }
    if (opt.progress && std::chrono::duration<double>(clock_type::now() - last_progress).count() > 2.0) {
      last_progress = clock_type::now();
      const double el = std::chrono::duration<double>(last_progress - wall0).count();
      std::fprintf(stderr, "run: %3.0f%%  t = %.2f of %.2f s  (%.1f s elapsed, %.2f ms per step median)\n",
                   100.0 * double(k) / double(ticks), tk, s.duration, el, percentile(r.step_ms, 50));
    }
  }
  const double wall = std::chrono::duration<double>(clock_type::now() - wall0).count();
  const sim::Model& m = simulation.model();
  nlohmann::json& j = r.summary;
  j["scenario"] = s.source;
  j["nodes"] = m.num_nodes();
  j["tetrahedra"] = m.num_tets();
  j["free_nodes"] = m.num_free();
  j["surface_triangles"] = m.surface.size();
  j["steps"] = simulation.steps();
  j["steps_solved"] = r.step_ms.size();
  j["steps_skipped_at_rest"] = skipped;
  j["steps_cg_not_converged"] = not_converged;
  j["backend"] = simulation.backend().name();
  j["backend_reason"] = simulation.backend_reason();
  j["device"] = simulation.backend().device_name();
  j["precision"] = s.params.solver.precision == sim::Precision::Float ? "float" : "double";
  j["dt"] = s.params.solver.dt;
  j["duration"] = s.duration;
  const std::vector<double> timed = after_warmup(r.step_ms);
  j["step_ms_median"] = percentile(timed, 50);
  j["step_ms_p99"] = percentile(timed, 99);
  j["warmup_steps"] = r.step_ms.size() - timed.size();
  j["cg_iterations_max"] = cg_max;
  {
    double sum = 0;
    for (int i : r.cg_iterations) sum += i;
    j["cg_iterations_mean"] = r.cg_iterations.empty() ? 0.0 : sum / double(r.cg_iterations.size());
  }
  j["finite"] = finite;
  j["error_control"] = error_control_json(simulation.error_control(), simulation.check_place());
  add_multigrid_json(j, simulation);
  j["max_force_n"] = max_force;
  j["wall_seconds"] = wall;
  j["realtime_factor"] = wall > 0 ? s.duration / wall : 0.0;
  {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    j["date"] = buf;
  }
  return r;
}

void write_fingers_csv(const std::string& path, const std::vector<FingerSample>& samples) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot be written");
  std::fputs("t,finger,x,y,z,fx,fy,fz\n", f);
  for (const auto& s : samples)
    std::fprintf(f, "%.4f,%d,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g\n", s.t, s.finger, s.x.x(), s.x.y(), s.x.z(), s.f.x(), s.f.y(), s.f.z());
  if (std::fclose(f) != 0) throw std::runtime_error(path + ": write failed (disk full?)");
}

nlohmann::json error_control_json(const sim::ErrorControlStats& c, const std::string& check_place) {
  if (!(c.target > 0)) return {{"force_error_target", 0.0}};
  return {{"force_error_target", c.target},
          {"cg_tolerance", c.tolerance},
          {"checks", c.checks},
          {"check_place", check_place},
          {"checks_over_target", c.over_target},
          {"last_error", c.last_error},
          {"worst_error", c.worst_error},
          {"contact_steps", c.contact_steps}};
}

void add_multigrid_json(nlohmann::json& j, const sim::Simulation& simulation) {
  const sim::Backend::MultigridCounts m = simulation.backend().multigrid_counts();
  j["preconditioner"] = sim::preconditioner_name(simulation.backend().params().solver.preconditioner);  // as it ran
  j["multigrid_builds"] = m.builds;
  j["multigrid_build_failures"] = m.failures;
  j["multigrid_smoother"] = m.smoother();
  j["multigrid_pressure_share"] = m.pressure_share;
}

}  // namespace palpation::app::live
