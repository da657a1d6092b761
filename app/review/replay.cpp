#include "review/replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>

#include "haptic_loop.h"
#include "live/device_bridge.h"
#include "live/device_config.h"
#include "live/force_mapping.h"
#include "live/sim_fingers.h"
#include "live/simulation_loop.h"
#include "live/workstation.h"
#include "scripted_device.h"
#include "store/recorded_scenario.h"
#include "simulation.h"
#include "triple_buffer.h"

namespace palpation::app::review {

namespace dv = palpation::device;

using live::RunOptions;
using live::run_headless;
using nlohmann::json;
using store::RecordedStep;
using store::Recording;

const char* replay_force_name(ReplayForce f) { return f == ReplayForce::Simulated ? "simulated" : "sent"; }

void ReplayResult::set_headline(ReplayForce f, const ForceDiff& d) {
  compared_force = f;
  max_force_diff = d.max_diff;
  max_diff_t = d.at_t;
  max_diff_finger = d.finger;
  max_recorded_force = d.max_recorded_force;
  compared = d.compared;
}

void ForceDiff::add(double t, int k, const Eigen::Vector3d& replayed, const Eigen::Vector3d& recorded) {
  if (!recorded.allFinite()) return;
  max_recorded_force = std::max(max_recorded_force, recorded.norm());
  const double d = (replayed - recorded).norm();
  if (!(d <= max_diff)) {  // NaN counts as the largest
    max_diff = std::isfinite(d) ? d : HUGE_VAL;
    at_t = t;
    finger = k;
  }
  if (std::isfinite(d)) sum_sq_diff += d * d;
  ++compared;
}

sim::Scenario replay_scenario(const Recording& rec) {
  if (rec.ticks() < 2) throw sim::ScenarioError(rec.path + ": fewer than 2 ticks recorded: nothing to replay");
  const nlohmann::json& js = rec.header["scenario"];
  sim::Scenario s = store::parse_recorded_scenario(js, rec.path + ": header.scenario");
  if (int(s.fingers.size()) != rec.fingers)
    throw sim::ScenarioError(rec.path + ": header.scenario.fingers: " + std::to_string(s.fingers.size()) +
                             " fingers, the recording has " + std::to_string(rec.fingers));
  // The device input as the finger paths: one keyframe per recorded tick.
  for (int k = 0; k < rec.fingers; ++k) {
    s.fingers[k].interpolation = sim::PathInterpolation::Linear;  // the ticks are the path
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

std::vector<RecordedCommand> recorded_commands(const store::RecordingInfo& rec) {
  std::vector<RecordedCommand> v;
  const bool mesh_order = store::young_in_mesh_order(rec);
  for (const json& e : rec.events) {
    if (!e.is_object() || e.value("kind", "") != "parameter" || !e.contains("index") || !e["index"].is_number_unsigned())
      continue;
    RecordedCommand c;
    c.index = e["index"].get<std::uint64_t>();
    c.kind = e.value("command", "");
    c.young_in_mesh_order = mesh_order;
    if (c.kind == "young") {
      c.young = store::recorded_young_changes(e);
    } else if ((c.kind == "params" || c.kind == "patient") && e.contains("scenario")) {
      c.scenario = e["scenario"];
    }
    v.push_back(std::move(c));
  }
  std::stable_sort(v.begin(), v.end(), [](const RecordedCommand& a, const RecordedCommand& b) { return a.index < b.index; });
  return v;
}

void apply_recorded_young(sim::Simulation& s, const RecordedCommand& c) {
  live::apply_element_young(s, store::young_in_model_order(s.model(), c.young, c.young_in_mesh_order));
}

namespace {

using clock_type = std::chrono::steady_clock;

// The force scales a workstation recorded as it chose them (a "session" event
// {"event": "force_scale", "scale": s} whenever the scale changed), in time order.
std::vector<std::pair<double, double>> recorded_scale_events(const Recording& rec) {
  std::vector<std::pair<double, double>> v;
  for (const json& e : rec.events)
    if (e.is_object() && e.value("kind", "") == "session" && e.value("event", "") == "force_scale" && e.contains("t") &&
        e["t"].is_number() && e.contains("scale") && e["scale"].is_number()) {
      const double s = e["scale"].get<double>();
      if (std::isfinite(s) && s > 0) v.emplace_back(e["t"].get<double>(), s);
    }
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return v;
}

std::int64_t to_ns(double t) { return std::int64_t(std::llround(t * 1e9)); }

// A recording with steps: the steps re-run exactly, their forces through the device's path.
ReplayResult replay_steps(const Recording& rec, const ReplayOptions& opt) {
  const auto wall0 = clock_type::now();
  const int nf = rec.fingers;
  if (nf < 1 || nf > dv::kMaxFingers)
    throw sim::ScenarioError(rec.path + ": " + std::to_string(nf) + " fingers: a workstation recording has at most " +
                             std::to_string(dv::kMaxFingers));
  sim::Scenario s = store::parse_recorded_scenario(rec.header["scenario"], rec.path + ": header.scenario");
  if (!opt.backend.empty()) s.backend = opt.backend;
  live::DeviceConfig cfg = live::default_device_config();
  if (rec.header.contains("device_config") && rec.header["device_config"].is_object())
    cfg = live::parse_device_config(rec.header["device_config"].dump(), rec.path + ": header.device_config");
  const auto& reg = cfg.hand.registration;

  // The haptic loop on the recorded fingertips (recording finger d is device finger d: the
  // workstation records device fingers), ticked at the recorded tick times.
  dv::HandScript script;
  for (int d = 0; d < nf; ++d) {
    std::vector<dv::PathKey> keys;
    keys.reserve(rec.ticks());
    for (std::size_t i = 0; i < rec.ticks(); ++i)
      keys.push_back({rec.t[i] - rec.t.front(), reg.to_device(live::to_dev(rec.x[i * std::size_t(nf) + std::size_t(d)]))});
    script.set_path(d, std::move(keys));
  }
  dv::ScriptedDevice device(script, cfg.hand.capabilities);
  dv::TripleBuffer<dv::PoseFrame> poses;
  dv::TripleBuffer<dv::ContactFrame> contacts;
  dv::HapticLoop loop(device, poses, contacts, nullptr, cfg.loop);
  const double limit = loop.params().safety.max_force;

  // The force scale: as recorded (events, or the header of a `palpation session`), else
  // measured again the way the workstation chose it when the patient loaded.
  const std::vector<std::pair<double, double>> scale_events = recorded_scale_events(rec);
  const bool header_scale = rec.header.contains("session") && rec.header["session"].is_object() &&
                            rec.header["session"].contains("force_scale");
  ReplayResult r;
  r.force_scale_source = !scale_events.empty() || header_scale ? "recorded" : "re-measured";
  double measured_scale = 1.0;
  bool first_patient = true;
  auto scale_at = [&](double t) {
    if (!scale_events.empty()) {
      double v = scale_events.front().second;
      for (const auto& [te, se] : scale_events)
        if (te <= t) v = se;
      return v;
    }
    return header_scale ? store::recorded_force_scale(rec) : measured_scale;
  };

  auto build = [&](const sim::Scenario& sc) {
    auto sim = std::make_unique<sim::Simulation>(sc);
    sim->reset();
    live::configure_realtime_threads(*sim);
    if (scale_events.empty() && !header_scale) {
      const double radius = sc.fingers.empty() ? 0.008 : sc.fingers[0].radius;
      try {
        measured_scale = live::measure_force_mapping(*sim, radius, limit, cfg.force_mapping).scale;
      } catch (const std::exception&) {
        measured_scale = live::force_mapping_for(0.0, limit, cfg.force_mapping).scale;  // as the workstation falls back
      }
    }
    return sim;
  };
  std::unique_ptr<sim::Simulation> simulation = build(s);
  const std::vector<RecordedCommand> commands = recorded_commands(rec);

  std::vector<sim::FingerInput> in(static_cast<std::size_t>(nf));
  std::vector<sim::FingerOutput> out(static_cast<std::size_t>(nf));
  std::vector<Eigen::Vector3d> prev_force(static_cast<std::size_t>(nf), Eigen::Vector3d::Zero());
  ForceDiff simulated;
  bool finite = true;
  double max_sent = 0;
  std::size_t ci = 0, tick = 0;
  std::uint64_t seq = 0;
  r.run.samples.reserve(rec.ticks() * std::size_t(nf));
  // Ticks up to (not including) `until` with the contact models published so far.
  auto run_ticks = [&](double until) {
    for (; tick < rec.ticks() && rec.t[tick] < until; ++tick) {
      const std::int64_t ns = to_ns(rec.t[tick]);
      loop.tick(ns, ns);
      for (int d = 0; d < nf; ++d) {
        const Eigen::Vector3d f = live::to_eigen(reg.vector_to_world(loop.command().force[d]));
        const Eigen::Vector3d& x = rec.x[tick * std::size_t(nf) + std::size_t(d)];
        r.sent.add(rec.t[tick], d, f, rec.f[tick * std::size_t(nf) + std::size_t(d)]);
        finite = finite && f.allFinite();
        max_sent = std::max(max_sent, f.norm());
        r.run.samples.push_back({rec.t[tick], d, x, f});
      }
    }
  };
  auto last_progress = wall0;
  for (std::size_t i = 0; i < rec.steps.size(); ++i) {
    const RecordedStep& st = rec.steps[i];
    // The commands this step saw, applied as the workstation's simulation thread applies a
    // batch: in order on the current model, a patient swap after the batch.
    const json* swap = nullptr;
    while (ci < commands.size() && commands[ci].index < st.commands_applied) {
      const RecordedCommand& c = commands[ci++];
      if (c.kind == "young") apply_recorded_young(*simulation, c);
      else if (c.kind == "params") live::apply_params(*simulation, store::parse_recorded_scenario(c.scenario, rec.path + ": params change").params);
      else if (c.kind == "patient") swap = &c.scenario;
    }
    if (swap) {
      sim::Scenario s2 = store::parse_recorded_scenario(*swap, rec.path + ": patient change");
      if (!opt.backend.empty()) s2.backend = opt.backend;
      simulation = build(s2);
      std::fill(prev_force.begin(), prev_force.end(), Eigen::Vector3d::Zero());
    }
    if (first_patient) {
      r.force_scale = scale_at(st.t);
      first_patient = false;
    }
    store::recorded_inputs(st, in);
    // The workstation's guarded step (a backend error falls back to the CPU from rest, the
    // divergence guard resets the body).
    const bool ok = simulation->advance(in, out, st.h).ok;
    for (int k = 0; k < nf; ++k) {
      const Eigen::Vector3d f = ok ? Eigen::Vector3d(out[std::size_t(k)].force) : Eigen::Vector3d::Zero();
      simulated.add(st.t, k, f, st.fingers[std::size_t(k)].f);
      finite = finite && f.allFinite();
    }
    // The step's contact models reach the haptic loop when it ends: at the next step's start
    // (the thread steps back to back), the last one dt later.
    const double published = i + 1 < rec.steps.size() ? rec.steps[i + 1].t : st.t + st.h;
    run_ticks(published);
    dv::ContactFrame& cf = contacts.write_slot();
    cf.fingers = {};
    const double scale = scale_at(st.t);
    for (int k = 0; k < nf; ++k) {
      const std::size_t u = std::size_t(k);
      if (ok && in[u].active)
        cf.fingers[u] = live::contact_model(live::guard_force_spike(out[u], prev_force[u]), in[u].position, reg, scale);
      prev_force[u] = ok && in[u].active && out[u].contacts > 0 ? Eigen::Vector3d(out[u].force) : Eigen::Vector3d::Zero();
    }
    cf.sequence = ++seq;
    cf.published_ns = to_ns(published);
    cf.sim_time = simulation->time();
    contacts.publish();
    if (opt.progress && std::chrono::duration<double>(clock_type::now() - last_progress).count() > 2.0) {
      last_progress = clock_type::now();
      std::fprintf(stderr, "replay: %3.0f%%  step %zu of %zu (t = %.2f of %.2f s)\n", 100.0 * double(i + 1) / double(rec.steps.size()),
                   i + 1, rec.steps.size(), st.t, rec.steps.back().t);
    }
  }
  run_ticks(HUGE_VAL);

  r.set_headline(ReplayForce::Simulated, simulated);
  const double wall = std::chrono::duration<double>(clock_type::now() - wall0).count();
  const sim::Model& m = simulation->model();
  json& j = r.run.summary;
  j["scenario"] = rec.path;
  j["nodes"] = m.num_nodes();
  j["tetrahedra"] = m.num_tets();
  j["steps"] = rec.steps.size();
  j["backend"] = simulation->backend().name();
  j["precision"] = simulation->backend().params().solver.precision == sim::Precision::Float ? "float" : "double";
  j["dt"] = "recorded";
  j["duration"] = rec.duration();
  j["finite"] = finite;
  j["max_force_n"] = max_sent;
  j["wall_seconds"] = wall;
  {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    j["date"] = buf;
  }
  return r;
}

}  // namespace

ReplayResult replay_recording(const Recording& rec, const ReplayOptions& opt) {
  if (!rec.steps.empty()) {
    ReplayResult r = replay_steps(rec, opt);
    auto& j = r.run.summary;
    j["replay"] = {{"recording", rec.path},
                   {"recorded_ticks", rec.ticks()},
                   {"recorded_steps", rec.steps.size()},
                   {"recording_complete", rec.complete},
                   {"recording_recovered", rec.recovered},
                   {"compared_force", replay_force_name(r.compared_force)},
                   {"compared", "the simulated force of every recorded step against the same step re-simulated (its dt, "
                                "fingertip inputs and the changes before it), N, simulated units"},
                   {"compared_finger_steps", r.compared},
                   {"max_force_diff_n", r.max_force_diff},
                   {"max_force_diff_t", r.max_diff_t},
                   {"max_force_diff_finger", r.max_diff_finger},
                   {"max_recorded_force_n", r.max_recorded_force},
                   {"sent", {{"compared", "the force sent to the device at every recorded tick against the re-simulated steps "
                                          "through the device's force path (force scale, spike guard, local contact model, "
                                          "haptic loop: virtual coupling, fades, safety filter), N, device units"},
                             {"force_scale", r.force_scale},
                             {"force_scale_source", r.force_scale_source},
                             {"compared_finger_ticks", r.sent.compared},
                             {"max_force_diff_n", r.sent.max_diff},
                             {"max_force_diff_t", r.sent.at_t},
                             {"max_force_diff_finger", r.sent.finger},
                             {"max_recorded_force_n", r.sent.max_recorded_force}}},
                   {"recorded_backend", rec.header.contains("session") ? rec.header["session"].value("backend", "") : ""}};
    return r;
  }
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
  r.force_scale = scale;
  r.force_scale_source = rec.header.contains("session") && rec.header["session"].is_object() &&
                                 rec.header["session"].contains("force_scale")
                             ? "recorded"
                             : "none";
  const std::size_t nf = std::size_t(rec.fingers);
  const std::size_t n = std::min(rec.ticks(), r.run.samples.size() / nf);
  ForceDiff sent;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < nf; ++k) sent.add(rec.t[i], int(k), r.run.samples[i * nf + k].f * scale, rec.f[i * nf + k]);
  r.set_headline(ReplayForce::Sent, sent);
  auto& j = r.run.summary;
  j["replay"] = {{"recording", rec.path},
                 {"recorded_ticks", rec.ticks()},
                 {"recording_complete", rec.complete},
                 {"recording_recovered", rec.recovered},
                 {"compared_force", replay_force_name(r.compared_force)},
                 {"compared", "the force recorded at every tick (sent to the device) against the re-simulated force at "
                              "the same tick times the recorded force scale, N, device units; the re-simulation steps at "
                              "the scenario's dt from the recorded fingertip positions"},
                 {"force_scale", r.force_scale},
                 {"force_scale_source", r.force_scale_source},
                 {"compared_finger_ticks", r.compared},
                 {"max_force_diff_n", r.max_force_diff},
                 {"max_force_diff_t", r.max_diff_t},
                 {"max_force_diff_finger", r.max_diff_finger},
                 {"max_recorded_force_n", r.max_recorded_force},
                 {"recorded_backend", rec.header.contains("session") ? rec.header["session"].value("backend", "") : ""}};
  return r;
}

}  // namespace palpation::app::review
