#include "review/replay.h"

#include <cmath>

namespace palpation::app::review {

using live::RunOptions;
using live::run_headless;
using store::Recording;

sim::Scenario replay_scenario(const Recording& rec) {
  if (rec.ticks() < 2) throw sim::ScenarioError(rec.path + ": fewer than 2 ticks recorded: nothing to replay");
  const nlohmann::json& js = rec.header["scenario"];
  sim::Scenario s = sim::parse_scenario(js.dump(), rec.path + ": header.scenario");
  if (int(s.fingers.size()) != rec.fingers)
    throw sim::ScenarioError(rec.path + ": header.scenario.fingers: " + std::to_string(s.fingers.size()) +
                             " fingers, the recording has " + std::to_string(rec.fingers));
  // The device input as the finger paths: one keyframe per recorded tick.
  for (int k = 0; k < rec.fingers; ++k) {
    auto& keys = s.fingers[k].keys;
    keys.clear();
    keys.reserve(rec.ticks());
    for (std::size_t i = 0; i < rec.ticks(); ++i) {
      const Eigen::Vector3d& x = rec.x[i * std::size_t(rec.fingers) + std::size_t(k)];
      keys.push_back({rec.t[i], x.x(), x.y(), x.z()});
    }
  }
  // As many 1 kHz ticks as were recorded (run_headless samples at k ms, k = 1..n).
  s.duration = double(rec.ticks()) * 0.001;
  s.source = rec.path;
  return s;
}

ReplayResult replay_recording(const Recording& rec, const ReplayOptions& opt) {
  sim::Scenario s = replay_scenario(rec);
  if (!opt.backend.empty()) s.backend = opt.backend;
  RunOptions ro;
  ro.progress = opt.progress;
  ro.log = opt.log;
  ReplayResult r;
  r.run = run_headless(s, ro);
  // Tick i of the recording against tick i of the replay (both 1 kHz from the start). A
  // session recorded the device's forces: the simulated ones times its force scale
  // (live/force_mapping.h; 1 in recordings made before the scale).
  const double scale = store::recorded_force_scale(rec);
  const std::size_t nf = std::size_t(rec.fingers);
  const std::size_t n = std::min(rec.ticks(), r.run.samples.size() / nf);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < nf; ++k) {
      const Eigen::Vector3d& fr = rec.f[i * nf + k];
      const Eigen::Vector3d fp = r.run.samples[i * nf + k].f * scale;
      if (!fr.allFinite()) continue;
      r.max_recorded_force = std::max(r.max_recorded_force, fr.norm());
      const double d = (fp - fr).norm();
      if (!(d <= r.max_force_diff)) {  // NaN counts as the largest
        r.max_force_diff = std::isfinite(d) ? d : HUGE_VAL;
        r.max_diff_t = rec.t[i];
        r.max_diff_finger = int(k);
      }
      ++r.compared;
    }
  auto& j = r.run.summary;
  j["replay"] = {{"recording", rec.path},
                 {"recorded_ticks", rec.ticks()},
                 {"recording_complete", rec.complete},
                 {"recording_recovered", rec.recovered},
                 {"compared_finger_ticks", r.compared},
                 {"max_force_diff_n", r.max_force_diff},
                 {"max_force_diff_t", r.max_diff_t},
                 {"max_force_diff_finger", r.max_diff_finger},
                 {"max_recorded_force_n", r.max_recorded_force},
                 {"recorded_backend", rec.header.contains("session") ? rec.header["session"].value("backend", "") : ""}};
  return r;
}

}  // namespace palpation::app::review
