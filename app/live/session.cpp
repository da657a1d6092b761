// The real-time pipeline of a session (design.md section 3):
//
//   emulator thread (1 kHz, robot side)  <-- UDP loopback -->  haptic thread (1 kHz)
//                                                                 |  poses   ^ contact models
//                                                                 v          |  (triple buffers)
//                                                              simulation thread (as fast as the FEM goes)
//   main thread: drains the haptic thread's telemetry ring into fingers.csv rows.
#include "live/session.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "live/device_bridge.h"
#include "live/device_factory.h"
#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "store/recording.h"
#include "live/haptic_thread.h"
#include "scripted_device.h"
#include "live/sim_fingers.h"
#include "simulation.h"
#include "live/simulation_loop.h"

namespace palpation::app::live {

using store::RecordingError;
using store::RecordingWriter;

namespace dv = palpation::device;
using nlohmann::json;

namespace {

// The simulation thread (app/live/simulation_loop.h) and the figures loop.json reports of it.
class SimulationThread {
 public:
  SimulationThread(sim::Simulation& simulation, dv::TripleBuffer<dv::PoseFrame>& poses,
                   dv::TripleBuffer<dv::ContactFrame>& contacts, SimulationLoopOptions opt)
      : sim_(simulation), loop_(poses, contacts, std::move(opt)) {}
  ~SimulationThread() { stop(); }

  void start() {
    stop_.store(false);
    thread_ = std::thread([this] { run(); });
  }
  void stop() {
    if (!thread_.joinable()) return;
    stop_.store(true, std::memory_order_release);
    thread_.join();
  }

  std::vector<double> step_ms, dt_ms;
  std::vector<int> cg_iterations;
  std::uint64_t steps = 0, resets = 0, solved = 0, fallbacks = 0;
  bool finite = true;
  double sim_time = 0;
  std::int64_t first_step_ns = 0, last_step_ns = 0;
  const SimulationLoop& loop() const { return loop_; }

 private:
  void run() {
    configure_realtime_threads(sim_);
    step_ms.reserve(1 << 16);
    dt_ms.reserve(1 << 16);
    cg_iterations.reserve(1 << 16);
    SimulationLoop::Hooks hooks;
    hooks.after_step = [this](const LoopStep& ls) {
      const sim::Simulation::Outcome& r = *ls.outcome;
      if (steps == 0) first_step_ns = ls.start_ns;
      ++steps;
      if (r.stats.solved) ++solved;
      if (r.fell_back) ++fallbacks;
      if (!r.ok) {
        finite = false;
        ++resets;
      }
      step_ms.push_back(ls.step_ms);
      dt_ms.push_back(ls.h * 1e3);
      cg_iterations.push_back(r.stats.cg_iterations);
      sim_time = ls.sim_time;
      last_step_ns = ls.published_ns;
    };
    loop_.run(sim_, stop_, hooks);
  }

  sim::Simulation& sim_;
  SimulationLoop loop_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

json percentiles(const dv::MicrosecondHistogram& h) {
  return json{{"p50", h.percentile(50)}, {"p99", h.percentile(99)}, {"max", h.max()}};
}

std::string now_utc() {
  std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

dv::HandScript script_from_recording(const std::string& path, const DeviceConfig& cfg) {
  std::vector<std::vector<dv::PathKey>> rec;
  try {
    rec = dv::load_fingers_csv(path);
  } catch (const std::runtime_error& e) {
    throw sim::ScenarioError(e.what());
  }
  dv::HandScript script;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    if (rec[k].empty()) continue;
    for (auto& key : rec[k]) key.p = cfg.hand.registration.to_device(key.p);
    script.set_path(cfg.finger_map[k], std::move(rec[k]));
  }
  return script;
}

}  // namespace

Vibration force_vibration(const std::vector<FingerSample>& samples, int finger, double from, double to) {
  std::vector<double> fz;
  for (const auto& s : samples)
    if (s.finger == finger && s.t >= from && s.t <= to) fz.push_back(s.f.z());
  Vibration v;
  constexpr int half = 15;  // 31-sample centred moving average
  if (int(fz.size()) <= 2 * half) return v;
  double sum2 = 0, lo = 1e300, hi = -1e300;
  double acc = 0;
  for (int i = 0; i < 2 * half + 1; ++i) acc += fz[i];
  for (int i = half; i + half < int(fz.size()); ++i) {
    if (i > half) acc += fz[i + half] - fz[i - half - 1];
    const double r = fz[i] - acc / (2 * half + 1);
    sum2 += r * r;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    ++v.samples;
  }
  v.rms = std::sqrt(sum2 / v.samples);
  v.peak_to_peak = hi - lo;
  return v;
}

SessionResult run_session(const sim::Scenario& s, const SessionOptions& opt) {
  const DeviceConfig& cfg = opt.config;
  const auto& reg = cfg.hand.registration;
  const auto& caps = cfg.hand.capabilities;
  const double duration = opt.duration > 0 ? opt.duration : s.duration;
  if (!(duration > 0)) throw sim::ScenarioError(s.source + ": duration: must be > 0");
  if (opt.device != "emulator" && opt.device != "scripted" && opt.device != "replay")
    throw sim::ScenarioError("--device: must be emulator, scripted or replay, got \"" + opt.device + "\"");
  if (opt.device == "replay" && opt.recording.empty())
    throw sim::ScenarioError("--device replay: needs --recording FINGERS.csv");
  const int nf = int(s.fingers.size());
  if (nf < 1 || nf > dv::kMaxFingers)
    throw sim::ScenarioError(s.source + ": fingers: the device has 1 to 5 fingers, the scenario " + std::to_string(nf));

  // The operator's hand (before anything starts: bad input fails early).
  dv::HandScript script;
  try {
    script = opt.recording.empty() ? script_from_scenario(s, reg, cfg.finger_map) : script_from_recording(opt.recording, cfg);
  } catch (const std::invalid_argument& e) {
    throw sim::ScenarioError(s.source + ": fingers: " + e.what());
  }

  // The simulation: meshing and precomputation happen here, not in real time.
  sim::Simulation simulation(s, opt.log);
  if (opt.prepare_simulation) opt.prepare_simulation(simulation);
  simulation.reset();

  // The device.
  DeviceRequest req;
  req.kind = opt.device;
  req.config = cfg;
  req.script = script;
  req.recording = opt.recording;
  req.rigid_hand = opt.rigid_hand;
  if (opt.device == "emulator" && !opt.emulator_exe.empty()) {
    std::vector<std::string>& args = req.emulator_command;
    args = {opt.emulator_exe, "--exit-after-idle", "3", "--quiet"};
    if (!opt.recording.empty()) args.insert(args.end(), {"--recording", opt.recording});
    else args.insert(args.end(), {"--scenario", opt.scenario_arg.empty() ? s.source : opt.scenario_arg});
    if (!opt.device_config_path.empty()) args.insert(args.end(), {"--config", opt.device_config_path});
    if (opt.rigid_hand) args.push_back("--rigid-hand");
    if (opt.priority > 0) args.insert(args.end(), {"--priority", std::to_string(std::max(1, opt.priority - 10))});
  }
  DeviceWiring wiring = open_device(std::move(req));
  dv::HapticDevice* dev = wiring.device.get();
  dv::HandHiroEmulator* emulator = wiring.emulator.get();
  ChildProcess& child = wiring.child;
  dv::HandHiroLink* link = wiring.link;
  dv::ScriptedDevice* scripted = wiring.scripted;

  // Hand-offs and the loop.
  dv::TripleBuffer<dv::PoseFrame> poses;
  dv::TripleBuffer<dv::ContactFrame> contacts;
  dv::SpscRing<dv::TickRecord> telemetry(1 << 15);  // 32 s of ticks: the recorder drains every 10 ms
  auto loop = std::make_unique<dv::HapticLoop>(*dev, poses, contacts, &telemetry, cfg.loop);
  // The force scale of this patient on this device (live/force_mapping.h): the scenario's
  // first fingertip pressed deep over the stiffest part, before anything runs.
  const ForceMapping mapping = measure_force_mapping(simulation, s.fingers[0].radius, loop->params().safety.max_force,
                                                     cfg.force_mapping);
  if (opt.log)
    opt.log("session: force scale " + std::to_string(mapping.scale) + " (" + force_scale_rule_name(mapping.rule) + ", deep press " +
            std::to_string(mapping.deep_press_n) + " N simulated)");
  SimulationLoopOptions lo;
  for (int k = 0; k < nf; ++k) {
    lo.finger_map.push_back(cfg.finger_map[std::size_t(k)]);
    lo.radius.push_back(s.fingers[std::size_t(k)].radius);
  }
  lo.registration = reg;
  lo.dt = s.params.solver.dt;
  lo.realtime = opt.sim_realtime;
  lo.max_dt = opt.sim_max_dt;
  lo.coupling_stiffness = loop->params().virtual_coupling ? loop->params().coupling_stiffness : 0.0;
  lo.force_scale = mapping.scale;
  SimulationThread sim_thread(simulation, poses, contacts, std::move(lo));
  PeriodicThread emulator_thread;
  HapticThread haptic(*loop);

  if (emulator)
    emulator_thread.start(std::int64_t(1e6), opt.priority > 0 ? std::max(1, opt.priority - 10) : 0,
                          [&](std::int64_t now, std::int64_t) { emulator->tick(now); });
  sim_thread.start();
  haptic.start(opt.priority);

  // The session recording (every session records when a path is given): the patient and
  // all settings in the header, then the device input and forces sent at 1 kHz. A write
  // failure (disk full) stops the recording only: the device and the loop carry on.
  std::unique_ptr<RecordingWriter> recorder;
  if (!opt.record_path.empty()) {
    json header;
    header["scenario"] = json::parse(sim::scenario_to_json(s));
    header["scenario_source"] = s.source;
    header["device_config"] = device_config_to_json(cfg);
    header["session"] = {{"device", opt.device},
                         {"duration_s", duration},
                         {"sim_dt", opt.sim_realtime ? "realtime" : "fixed"},
                         {"sim_max_dt", opt.sim_max_dt},
                         {"coupling", cfg.loop.virtual_coupling ? "virtual" : "direct"},
                         {"rigid_hand", opt.rigid_hand},
                         {"force_scale", mapping.scale},
                         {"backend", simulation.backend().name()},
                         {"program", std::string("palpation ") + PALPATION_VERSION + " (" + PALPATION_GIT_COMMIT + ")"}};
    if (!opt.record_settings.is_null()) header["settings"] = opt.record_settings;
    try {
      recorder = std::make_unique<RecordingWriter>(opt.record_path, std::move(header), nf);
    } catch (const RecordingError& e) {
      throw std::runtime_error(e.what());
    }
    recorder->add_event(0.0, "session", {{"event", "start"}});
  }
  bool record_error_said = false;

  // The recorder: drain the telemetry until the session's duration has passed.
  SessionResult res;
  res.samples.reserve(std::size_t(duration * 1000.0 + 100) * std::size_t(nf));
  std::int64_t t_start = -1;
  bool done = false;
  const double period = cfg.loop.period;
  const auto wall0 = std::chrono::steady_clock::now();
  auto last_progress = wall0;
  double max_sent = 0;
  std::uint64_t bad_sent = 0, over_sent = 0;
  auto drain = [&]() {
    dv::TickRecord r;
    while (telemetry.pop(r)) {
      if (t_start < 0) t_start = r.time_ns;
      const double t = double(r.time_ns - t_start) * 1e-9 + period;
      if (t > duration + 1e-9) {
        done = true;
        continue;
      }
      std::array<Eigen::Vector3d, dv::kMaxFingers> rx, rf;
      for (int k = 0; k < nf; ++k) {
        const int d = cfg.finger_map[k];
        const dv::Vec3 f = r.force[d];
        rx[k] = to_eigen(reg.to_world(r.position[d]));
        rf[k] = to_eigen(reg.vector_to_world(f));
        if (!dv::finite(f)) ++bad_sent;
        else {
          max_sent = std::max(max_sent, dv::norm(f));
          if (dv::norm(f) > caps.max_force) ++over_sent;
        }
        res.samples.push_back({t, k, rx[k], rf[k]});
      }
      if (recorder) recorder->add_tick(t, rx.data(), rf.data());
    }
    if (recorder && recorder->failed() && !record_error_said) {
      record_error_said = true;
      if (opt.log) opt.log("session: recording stopped: " + recorder->error() + " (the session goes on)");
    }
  };
  while (!done) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    drain();
    if (recorder) recorder->flush();  // syncs at least every second
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (el > duration + 60.0) break;  // a loop that never started: do not hang
    if (!opt.emulator_exe.empty() && !child.alive()) throw std::runtime_error("emulator: the child process exited early");
    if (opt.progress && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_progress).count() > 2.0) {
      last_progress = std::chrono::steady_clock::now();
      const double t = res.samples.empty() ? 0.0 : res.samples.back().t;
      std::fprintf(stderr, "session: %3.0f%%  t = %.1f of %.1f s\n", 100.0 * t / duration, t, duration);
    }
  }
  haptic.stop();
  sim_thread.stop();
  emulator_thread.stop();
  child.end();
  drain();

  // loop.json
  const dv::LoopStats& st = loop->stats();
  const dv::SafetyCounters& sc = loop->safety().counters();
  const auto rt = haptic.realtime();
  json& j = res.loop;
  j["scenario"] = s.source;
  j["device"] = dev->name() + (emulator ? " (handhiro-emulator, in-process thread, UDP loopback)"
                                        : (opt.emulator_exe.empty() ? "" : " (handhiro-emulator, child process, UDP loopback)"));
  j["duration_s"] = duration;
  j["date"] = now_utc();
  j["commit"] = PALPATION_GIT_COMMIT;
  j["haptic"] = {{"ticks", st.ticks},
                 {"rate_hz", st.rate_hz()},
                 {"period_us", percentiles(st.period_us)},
                 {"jitter_us", percentiles(st.jitter_us)},
                 {"wake_latency_us", percentiles(st.latency_us)},
                 {"compute_us", percentiles(st.compute_us)},
                 {"overruns", st.overruns},
                 {"missed_deadlines", st.missed},
                 {"scheduling", rt.policy},
                 {"realtime", rt.granted},
                 {"scheduling_note", rt.note},
                 {"device_states", st.device_updates},
                 {"contact_models_taken", st.model_updates},
                 {"coupling", loop->params().virtual_coupling ? "virtual" : "direct"},
                 {"coupling_stiffness_n_per_m", loop->params().coupling_stiffness},
                 {"telemetry_dropped", st.telemetry_dropped}};
  {
    const double wall = sim_thread.last_step_ns > sim_thread.first_step_ns
                            ? double(sim_thread.last_step_ns - sim_thread.first_step_ns) * 1e-9
                            : 0.0;
    int cg_max = 0;
    for (int i : sim_thread.cg_iterations) cg_max = std::max(cg_max, i);
    const std::vector<double> timed_steps = after_warmup(sim_thread.step_ms), timed_dt = after_warmup(sim_thread.dt_ms);
    const sim::Model& m = simulation.model();
    j["simulation"] = {{"backend", simulation.backend().name()},
                       {"cpu_or_gpu", simulation.backend().device_name()},
                       {"nodes", m.num_nodes()},
                       {"tetrahedra", m.num_tets()},
                       {"steps", sim_thread.steps},
                       {"steps_solved", sim_thread.solved},
                       {"step_rate_hz", wall > 0 ? double(sim_thread.steps - 1) / wall : 0.0},
                       {"step_ms_median", percentile(timed_steps, 50)},
                       {"step_ms_p99", percentile(timed_steps, 99)},
                       {"step_ms_max", percentile(timed_steps, 100)},
                       {"warmup_steps", sim_thread.step_ms.size() - timed_steps.size()},
                       {"dt_mode", opt.sim_realtime ? "realtime" : "fixed"},
                       {"dt_ms_median", percentile(timed_dt, 50)},
                       {"dt_ms_max", percentile(timed_dt, 100)},
                       {"dt_ms_limit", sim_thread.loop().dt_limit_s() * 1e3},
                       {"dt_sweeps", sim_thread.loop().dt_sweeps()},
                       {"simulated_time_s", sim_thread.sim_time},
                       // Simulated seconds a wall second over the steps (1: real time; below
                       // where no dt fits, step_pacer.h).
                       {"pace", wall > 0 ? sim_thread.sim_time / wall : 0.0},
                       {"cg_iterations_max", cg_max},
                       {"divergence_resets", sim_thread.resets},
                       {"backend_fallbacks", sim_thread.fallbacks},
                       {"finite", sim_thread.finite},
                       {"error_control", error_control_json(simulation.error_control(), simulation.check_place())}};
    add_multigrid_json(j["simulation"], simulation);
  }
  j["force_mapping"] = {{"scale", mapping.scale},
                        {"rule", force_scale_rule_name(mapping.rule)},
                        {"device_limit_n", mapping.device_limit_n},
                        {"deep_press_n", mapping.deep_press_n},
                        {"deep_press_device_n", mapping.deep_press_device_n},
                        {"simulated_at_limit_n", mapping.simulated_at_limit_n},
                        {"press_skin_m", {mapping.press_skin.x(), mapping.press_skin.y(), mapping.press_skin.z()}},
                        {"press_depth_m", mapping.press_depth_m},
                        {"thickness_m", mapping.thickness_m},
                        {"presses", mapping.presses},
                        {"probe_ms", mapping.probe_ms},
                        {"note", "fingers.csv and forces: device units (scale x simulated force)"}};
  j["forces"] = {{"limit_n", caps.max_force},
                 {"largest_sent_n", max_sent},
                 {"largest_desired_n", sc.max_desired},
                 {"largest_step_before_safety_n", st.max_model_step},
                 {"nonfinite_sent", bad_sent},
                 {"above_limit_sent", over_sent}};
  j["safety"] = {{"clamped_finger_ticks", sc.clamped},
                 {"rate_limited_finger_ticks", sc.rate_limited},
                 {"nonfinite_inputs", sc.nonfinite},
                 {"passivity", cfg.loop.safety.passivity},
                 {"passivity_active_finger_ticks", sc.passivity_active},
                 {"passivity_dissipated_j", sc.dissipated},
                 {"releases", sc.releases},
                 {"reattaches", sc.reattaches},
                 {"final_guard", sc.final_guard}};
  std::uint64_t robot_watchdog = 0;
  if (emulator) {
    const auto& ec = emulator->counters();
    const auto& rc = emulator->robot().counters();
    robot_watchdog = ec.watchdog_events;
    j["emulator"] = {{"ticks", ec.ticks},
                     {"commands_accepted", ec.commands},
                     {"commands_lost", ec.lost},
                     {"commands_duplicate", ec.duplicates},
                     {"commands_late", ec.late},
                     {"commands_corrupt", ec.corrupt},
                     {"commands_refused_nonfinite", ec.refused_nonfinite},
                     {"commands_over_limit", ec.over_limit},
                     {"largest_force_received_n", ec.max_force_received},
                     {"watchdog_events", ec.watchdog_events},
                     {"magnet_releases", rc.releases},
                     {"magnet_reattaches", rc.reattaches},
                     {"torque_limited_finger_steps", rc.torque_limited},
                     {"ik_misses", rc.ik_misses},
                     {"largest_force_applied_n", rc.max_applied},
                     {"hand", opt.rigid_hand ? "rigid" : "compliant"}};
  }
  // The watchdog loop starts with one "stale" event before the first update and one
  // "link lost" only after a connection existed; report them as counted.
  j["watchdog_events"] = {{"simulation_stale", sc.stale_events}, {"link_lost", sc.link_events}, {"robot_watchdog", robot_watchdog}};
  if (link) {
    const auto lc = link->counters();
    j["link"] = {{"states_accepted", lc.received}, {"commands_sent", lc.sent},   {"states_lost", lc.lost},
                 {"states_duplicate", lc.duplicates}, {"states_late", lc.reordered}, {"states_corrupt", lc.corrupt},
                 {"send_errors", lc.send_errors},   {"link_losses", lc.link_losses}, {"rtt_us", percentiles(link->rtt_us())}};
  }
  if (scripted) {
    const auto& rx = scripted->received();
    j["device_received"] = {{"writes", rx.writes}, {"nonfinite", rx.nonfinite}, {"over_limit", rx.over_limit}, {"largest_n", rx.max_force}};
  }
  {
    const double from = opt.vibration_from >= 0 ? opt.vibration_from : 0.5 * duration;
    const double to = opt.vibration_to > from ? opt.vibration_to : duration;
    json fingers = json::array();
    for (int k = 0; k < nf; ++k) {
      const Vibration v = force_vibration(res.samples, k, from, to);
      fingers.push_back({{"finger", k}, {"fz_rms_n", v.rms}, {"fz_peak_to_peak_n", v.peak_to_peak}, {"samples", v.samples}});
    }
    j["vibration"] = {{"window_s", json::array({from, to})},
                      {"method", "fz minus its 31-sample centred moving average (high-pass, -3 dB near 24 Hz)"},
                      {"fingers", fingers}};
  }
  res.ok = bad_sent == 0 && over_sent == 0 && sim_thread.finite && st.ticks > 0;
  j["ok"] = res.ok;
  if (recorder) {
    const double t_end = res.samples.empty() ? 0.0 : res.samples.back().t;
    recorder->add_event(t_end, "session", {{"event", "end"}});
    recorder->close({{"ok", res.ok}, {"loop", j}});
    res.recording = {{"path", recorder->path()}, {"bytes", recorder->bytes()}, {"ticks", recorder->ticks()},
                     {"complete", !recorder->failed()}};
    if (recorder->failed()) res.recording["error"] = recorder->error();
    j["recording"] = res.recording;
  }
  return res;
}

}  // namespace palpation::app::live
