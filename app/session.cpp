// The real-time pipeline of a session (design.md section 3):
//
//   emulator thread (1 kHz, robot side)  <-- UDP loopback -->  haptic thread (1 kHz)
//                                                                 |  poses   ^ contact models
//                                                                 v          |  (triple buffers)
//                                                              simulation thread (as fast as the FEM goes)
//   main thread: drains the haptic thread's telemetry ring into fingers.csv rows.
#include "session.h"

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
#include <spawn.h>
#include <csignal>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "device_bridge.h"
#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "recording.h"
#include "haptic_thread.h"
#include "scripted_device.h"
#include "sim_fingers.h"
#include "simulation.h"

extern char** environ;

namespace palpation::app {

namespace dv = palpation::device;
using nlohmann::json;

namespace {

// The simulation thread: newest poses -> step -> publish the local contact models.
class SimulationThread {
 public:
  /// coupling_stiffness > 0: virtual coupling (the simulated fingertip is the proxy, see
  /// device/contact_model.h couple()); 0: the simulated fingertip is the device's.
  SimulationThread(sim::Simulation& simulation, dv::TripleBuffer<dv::PoseFrame>& poses,
                   dv::TripleBuffer<dv::ContactFrame>& contacts, const DeviceConfig& cfg, bool realtime, double max_dt,
                   double coupling_stiffness)
      : sim_(simulation), poses_(poses), contacts_(contacts), cfg_(cfg), realtime_(realtime), max_dt_(max_dt),
        kc_(coupling_stiffness) {}
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

 private:
  void run() {
    const sim::Scenario& s = sim_.scenario();
    const int nf = int(s.fingers.size());
    const auto& reg = cfg_.hand.registration;
    std::vector<sim::FingerInput> in(nf);
    std::vector<sim::FingerOutput> out(nf);
    std::vector<Eigen::Vector3d> x0(nf);
    for (int k = 0; k < nf; ++k) in[k].radius = s.fingers[k].radius;
    sim::Backend* be = &sim_.backend();
    sim::SimParams params = be->params();
    // On a small machine the haptic (and emulator) threads need a core of their own:
    // OpenMP teams that must all be scheduled at every barrier then cost far more than
    // they save. solver.threads = 0 (auto) becomes 1 there.
    if (params.solver.threads == 0 && std::thread::hardware_concurrency() <= 3) {
      params.solver.threads = 1;
      be->set_params(params);
    }
    const double dt = s.params.solver.dt;
    step_ms.reserve(1 << 16);
    dt_ms.reserve(1 << 16);
    cg_iterations.reserve(1 << 16);
    std::int64_t prev_start = 0;
    std::uint64_t seq = 0;
    while (!stop_.load(std::memory_order_acquire)) {
      poses_.update();
      const dv::PoseFrame& pf = poses_.read();
      if (pf.tick == 0) {
        dv::sleep_until_ns(dv::monotonic_ns() + 1000000);
        continue;
      }
      std::int64_t now = dv::monotonic_ns();
      double h = dt;
      if (prev_start == 0) {
        first_step_ns = now;
      } else if (realtime_) {
        // The tissue keeps wall-clock time: dt = time since the previous step, at least the
        // scenario's dt (never faster than real time), at most max_dt (implicit Euler is
        // stable at any dt; the cap bounds the latency one step adds).
        const std::int64_t due = prev_start + std::int64_t(dt * 1e9);
        if (now < due) {
          dv::sleep_until_ns(due);
          continue;
        }
        h = std::min(double(now - prev_start) * 1e-9, max_dt_);
      } else {
        // Fixed dt, paced to real time when the FEM is faster.
        const std::int64_t due = first_step_ns + std::int64_t(sim_time * 1e9);
        if (now < due) {
          dv::sleep_until_ns(due);
          continue;
        }
      }
      const double since = prev_start == 0 ? 0.0 : double(now - prev_start) * 1e-9;
      prev_start = now;
      for (int k = 0; k < nf; ++k) {
        // The simulated fingertip (app/sim_fingers.h, shared with the workstation): with
        // the virtual coupling, the proxy balanced against this thread's newest contact
        // model at the newest device position (computed here, not taken from the haptic
        // loop, whose proxy may still be one model behind); with direct coupling, the
        // device's fingertip.
        finger_from_pose(pf, cfg_.finger_map[k], last_[cfg_.finger_map[k]], kc_, reg, since, in[k]);
        x0[k] = in[k].position;
      }
      if (params.solver.dt != h) {
        params.solver.dt = h;
        be->set_params(params);
      }
      const auto a = std::chrono::steady_clock::now();
      sim::StepStats st;
      try {
        st = be->step(in, out);
      } catch (const std::exception& e) {
        // A backend error mid-session (a CUDA error): continue on the CPU from rest. The
        // haptic loop keeps rendering the last contact model, fades the new one in, and
        // the safety filter rate-limits whatever differs: no force spike.
        if (!sim_.fall_back_to_cpu(e.what())) throw;
        be = &sim_.backend();
        be->set_params(params);
        ++fallbacks;
        st = be->step(in, out);
      }
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
      ++steps;
      if (st.solved) ++solved;
      step_ms.push_back(ms);
      dt_ms.push_back(h * 1e3);
      cg_iterations.push_back(st.cg_iterations);
      sim_time += h;
      // Divergence (design.md section 7: NaN/Inf or an energy blow-up): the check puts the
      // body back to rest and logs it; no forces until it steps again.
      const bool ok = !sim_.check_divergence(st, out).diverged;
      dv::ContactFrame& cf = contacts_.write_slot();
      cf.fingers = {};
      if (!ok) {
        finite = false;
        ++resets;
      } else {
        for (int k = 0; k < nf; ++k)
          if (in[k].active) cf.fingers[cfg_.finger_map[k]] = contact_model(out[k], x0[k], reg);
      }
      last_ = cf.fingers;
      cf.sequence = ++seq;
      cf.sim_time = sim_time;
      cf.published_ns = dv::monotonic_ns();
      contacts_.publish();
      last_step_ns = cf.published_ns;
    }
  }

  sim::Simulation& sim_;
  dv::TripleBuffer<dv::PoseFrame>& poses_;
  dv::TripleBuffer<dv::ContactFrame>& contacts_;
  const DeviceConfig& cfg_;
  bool realtime_;
  double max_dt_;
  double kc_;
  std::array<dv::FingerContactModel, dv::kMaxFingers> last_{};  // newest published, device frame
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

// handhiro-emulator as a child process (posix_spawn), ended with SIGTERM.
class ChildProcess {
 public:
  ~ChildProcess() { end(); }
  void spawn(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int rc = ::posix_spawn(&pid_, args[0].c_str(), nullptr, nullptr, argv.data(), environ);
    if (rc != 0) {
      pid_ = -1;
      throw std::runtime_error(args[0] + ": cannot start the emulator (" + std::strerror(rc) + ")");
    }
  }
  bool alive() {
    if (pid_ <= 0) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }
  void end() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    int status = 0;
    for (int i = 0; i < 300; ++i) {  // up to 3 s, then SIGKILL
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
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
  std::unique_ptr<dv::HapticDevice> dev;
  std::unique_ptr<dv::HandHiroEmulator> emulator;
  ChildProcess child;
  dv::HandHiroLink* link = nullptr;
  dv::ScriptedDevice* scripted = nullptr;
  if (opt.device == "scripted") {
    auto d = std::make_unique<dv::ScriptedDevice>(script, caps);
    scripted = d.get();
    dev = std::move(d);
  } else if (opt.device == "replay") {
    std::unique_ptr<dv::ReplayDevice> d;
    try {
      d = std::make_unique<dv::ReplayDevice>(opt.recording, reg, cfg.finger_map, caps);
    } catch (const std::runtime_error& e) {
      throw sim::ScenarioError(e.what());
    }
    scripted = d.get();
    dev = std::move(d);
  } else {
    dv::LinkConfig lc = cfg.link;
    lc.robot_address = "127.0.0.1";
    lc.bind_address = "127.0.0.1";
    lc.bind_port = 0;
    std::string err;
    if (opt.emulator_exe.empty()) {
      dv::EmulatorOptions eo;
      eo.bind_address = "127.0.0.1";
      eo.port = 0;
      eo.rigid_hand = opt.rigid_hand;
      emulator = std::make_unique<dv::HandHiroEmulator>(cfg.hand, script, eo);
      if (!emulator->open(&err)) throw std::runtime_error("emulator: " + err);
      lc.robot_port = emulator->port();
    } else {
      dv::UdpSocket probe;  // a free loopback port for the child
      if (!probe.open("127.0.0.1", 0, &err)) throw std::runtime_error("emulator: " + err);
      lc.robot_port = probe.local_port();
      probe.close();
      std::vector<std::string> args{opt.emulator_exe, "--port", std::to_string(lc.robot_port), "--exit-after-idle", "3", "--quiet"};
      if (!opt.recording.empty()) args.insert(args.end(), {"--recording", opt.recording});
      else args.insert(args.end(), {"--scenario", opt.scenario_arg.empty() ? s.source : opt.scenario_arg});
      if (!opt.device_config_path.empty()) args.insert(args.end(), {"--config", opt.device_config_path});
      if (opt.rigid_hand) args.push_back("--rigid-hand");
      if (opt.priority > 0) args.insert(args.end(), {"--priority", std::to_string(std::max(1, opt.priority - 10))});
      child.spawn(args);
    }
    auto l = std::make_unique<dv::HandHiroLink>(caps, lc);
    if (!l->open(&err)) throw std::runtime_error("link: " + err);
    link = l.get();
    dev = std::move(l);
  }

  // Hand-offs and the loop.
  dv::TripleBuffer<dv::PoseFrame> poses;
  dv::TripleBuffer<dv::ContactFrame> contacts;
  dv::SpscRing<dv::TickRecord> telemetry(1 << 15);  // 32 s of ticks: the recorder drains every 10 ms
  auto loop = std::make_unique<dv::HapticLoop>(*dev, poses, contacts, &telemetry, cfg.loop);
  SimulationThread sim_thread(simulation, poses, contacts, cfg, opt.sim_realtime, opt.sim_max_dt,
                              loop->params().virtual_coupling ? loop->params().coupling_stiffness : 0.0);
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
    const sim::Model& m = simulation.model();
    j["simulation"] = {{"backend", simulation.backend().name()},
                       {"cpu_or_gpu", simulation.backend().device_name()},
                       {"nodes", m.num_nodes()},
                       {"tetrahedra", m.num_tets()},
                       {"steps", sim_thread.steps},
                       {"steps_solved", sim_thread.solved},
                       {"step_rate_hz", wall > 0 ? double(sim_thread.steps - 1) / wall : 0.0},
                       {"step_ms_median", percentile(sim_thread.step_ms, 50)},
                       {"step_ms_p99", percentile(sim_thread.step_ms, 99)},
                       {"step_ms_max", percentile(sim_thread.step_ms, 100)},
                       {"dt_mode", opt.sim_realtime ? "realtime" : "fixed"},
                       {"dt_ms_median", percentile(sim_thread.dt_ms, 50)},
                       {"dt_ms_max", percentile(sim_thread.dt_ms, 100)},
                       {"simulated_time_s", sim_thread.sim_time},
                       {"cg_iterations_max", cg_max},
                       {"divergence_resets", sim_thread.resets},
                       {"backend_fallbacks", sim_thread.fallbacks},
                       {"finite", sim_thread.finite}};
  }
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

}  // namespace palpation::app
