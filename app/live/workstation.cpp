#include "live/workstation.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "live/device_bridge.h"
#include "live/device_factory.h"
#include "fem_stress.h"
#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "live/haptic_thread.h"
#include "phantom.h"
#include "rt_clock.h"
#include "live/sim_fingers.h"
#include "simulation.h"
#include "live/simulation_loop.h"
#include "train/exam.h"

namespace palpation::app::live {

namespace dv = palpation::device;

// ---------------------------------------------------------------------------------------
// Defaults

sim::Scenario default_workstation_scenario() {
  sim::Scenario s = sim::builtin_scenario("paper-sweep-layered");
  s.source = "default patient (paper breast, layered, coarse)";
  s.patient.resolution = "coarse";
  s.patient.edge = *sim::resolution_edge("breast", "coarse");
  s.backend = "auto";
  // Real time on a CPU (docs/benchmarks.md): on the coarse breast float and CG
  // 1e-2 give the same force error as double and CG 1e-6 (1.2e-4: the kept rotations'
  // error dominates) at 0.6-0.8 ms a step on this project's 2-core VM, against 1.3 ms at
  // the scenario defaults (double, 1e-3). The Simulation panel changes them.
  s.params.solver.precision = sim::Precision::Float;
  s.params.solver.cg_tolerance = 1e-2;
  // ... which is where the error controller starts: it holds the finger force within 1 %
  // of the converged one and moves the tolerance to the loosest that does.
  s.params.solver.force_error = sim::kDefaultForceError;
  return s;
}

dv::HandScript default_hand_script(const DeviceConfig& cfg) {
  const sim::Scenario paper = sim::builtin_scenario("paper-sweep");
  const auto& reg = cfg.hand.registration;
  const auto keys = paper.fingers.at(0).linear_keys(kScriptKeyStep);
  // Hand layout relative to the index fingertip (world frame, m): the other fingers
  // hover just above the dome (top at 6.5 cm), spread along y like a hand.
  const std::array<Eigen::Vector3d, dv::kMaxFingers> offset{
      Eigen::Vector3d(-0.035, -0.045, 0.0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.0, 0.022, 0.0),
      Eigen::Vector3d(-0.004, 0.042, 0.0), Eigen::Vector3d(-0.012, 0.060, 0.0)};
  dv::HandScript script;
  for (int f = 0; f < dv::kMaxFingers; ++f) {
    std::vector<dv::PathKey> path;
    path.reserve(keys.size());
    for (const auto& k : keys) {
      Eigen::Vector3d p(k[1], k[2], k[3]);
      if (f != dv::kIndex) p = Eigen::Vector3d(k[1], 0, 0.082) + offset[f];
      path.push_back({k[0], reg.to_device(to_dev(p))});
    }
    script.set_path(f, std::move(path));
  }
  return script;
}

// ---------------------------------------------------------------------------------------
// Workstation

namespace {
/// The fingertip radius of a patient's scenario (m): its first finger's, else 8 mm.
double finger_radius(const sim::Scenario& s) { return s.fingers.empty() ? 0.008 : s.fingers[0].radius; }
}  // namespace

std::shared_ptr<PatientGeometry> make_patient_geometry(sim::Simulation& simulation, std::uint64_t generation) {
  auto g = std::make_shared<PatientGeometry>();
  const sim::Model& m = simulation.model();
  g->generation = generation;
  g->rest = m.rest;
  g->tets = m.tets;
  g->surface = m.surface;
  g->young = simulation.materials().young;
  g->centroid.resize(m.tets.size());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) c += m.rest[std::size_t(m.tets[e][a])];
    g->centroid[e] = c / 4.0;
  }
  g->tissue_young = simulation.scenario().young_modulus;
  g->base_young = m.tissue_young;
  g->tissue_poisson = simulation.scenario().poisson_ratio;
  g->skin = std::make_shared<const train::SkinMap>(train::build_skin_map(m));
  auto& be = simulation.backend();
  g->backend = be.name();
  g->device_name = be.device_name();
  return g;
}

struct Workstation::Threads {
  HapticThread haptic;
  PeriodicThread emulator;  // the robot side, "emulator" only
  explicit Threads(dv::HapticLoop& l) : haptic(l) {}
};

Workstation::Workstation(WorkstationOptions opt) : opt_(std::move(opt)) {
  if (opt_.device != "simulated" && opt_.device != "emulator" && opt_.device != "handhiro")
    throw std::runtime_error("device: must be simulated, emulator or handhiro, got \"" + opt_.device + "\"");
  DeviceRequest req;
  req.kind = opt_.device;
  req.config = opt_.config;
  req.script = default_hand_script(opt_.config);
  req.looped = true;  // the emulated operator palpates until stopped, as the simulated hand does
  req.robot_address = opt_.robot_address;
  req.robot_port = opt_.robot_port;
  wiring_ = std::make_unique<DeviceWiring>(open_device(std::move(req)));
  // The simulated hand exists with every device: the mouse palpates through it.
  if (wiring_->hand) device_ = wiring_->hand;
  else {
    own_hand_ = std::make_unique<dv::SimulatedHand>(default_hand_script(opt_.config), opt_.config.hand.capabilities);
    device_ = own_hand_.get();
  }
  dv::HapticDevice& dev = *wiring_->device;
  loop_ = std::make_unique<dv::HapticLoop>(dev, poses_, contacts_, &ticks_, opt_.config.loop);
  threads_ = std::make_unique<Threads>(*loop_);
  // Every device finger is simulated, with the patient's fingertip radius.
  SimulationLoopOptions lo;
  for (int d = 0; d < dv::kMaxFingers; ++d) lo.finger_map.push_back(d);
  lo.radius.assign(dv::kMaxFingers, finger_radius(opt_.scenario));
  lo.registration = opt_.config.hand.registration;
  lo.dt = opt_.scenario.params.solver.dt;
  lo.realtime = true;
  lo.max_dt = opt_.sim_max_dt;
  lo.coupling_stiffness = loop_->params().virtual_coupling ? loop_->params().coupling_stiffness : 0.0;
  lo.spike_guard = opt_.spike_guard;
  // Until the first patient's deep press is measured: the configured scale, else 1.
  force_mapping_ = force_mapping_for(0.0, loop_->params().safety.max_force, opt_.config.force_mapping);
  lo.force_scale = force_mapping_.scale;
  lo.recover_hold_s = opt_.recover_hold_s;
  lo.recover_hold_max_s = opt_.recover_hold_max_s;
  lo.recover_blend_s = opt_.recover_blend_s;
  sim_loop_ = std::make_unique<SimulationLoop>(poses_, contacts_, std::move(lo));
}

std::string Workstation::device_description() const {
  if (wiring_->hand) return device_->mode() == HandMode::Mouse ? "mouse" : wiring_->description;
  return wiring_->description;
}

bool Workstation::simulated_device() const { return wiring_->link == nullptr; }

Workstation::~Workstation() { stop(); }

double Workstation::now_s() const { return t0_ns_ ? double(dv::monotonic_ns() - t0_ns_) * 1e-9 : 0.0; }

void Workstation::start() {
  if (running()) return;
  t0_ns_ = dv::monotonic_ns();
  rate_window_ns_ = t0_ns_;
  stop_.store(false);
  sim_state_.store(SimState::Loading);
  sim_thread_ = std::thread([this] { sim_main(); });
  if (wiring_->emulator) {
    dv::HandHiroEmulator* em = wiring_->emulator.get();
    threads_->emulator.start(std::int64_t(1e6), opt_.haptic_priority > 0 ? std::max(1, opt_.haptic_priority - 10) : 0,
                             [em](std::int64_t now, std::int64_t) { em->tick(now); });
  }
  threads_->haptic.start(opt_.haptic_priority);
}

void Workstation::stop() {
  if (!running()) return;
  threads_->haptic.stop();
  threads_->emulator.stop();
  stop_.store(true, std::memory_order_release);
  sim_thread_.join();
  sim_state_.store(SimState::Stopped);
}

void Workstation::post(Command c) {
  std::lock_guard<std::mutex> lk(mu_);
  queue_.push_back(std::move(c));
  posted_.fetch_add(1);
}

const char* command_kind_name(CommandKind k) {
  switch (k) {
    case CommandKind::Young: return "young";
    case CommandKind::Params: return "params";
    case CommandKind::Patient: return "patient";
  }
  return "";
}

const char* sim_state_name(SimState s) {
  switch (s) {
    case SimState::Stopped: return "stopped";
    case SimState::Loading: return "loading";
    case SimState::Running: return "running";
    case SimState::Swapping: return "swapping";
    case SimState::Error: return "error";
  }
  return "";
}

void Workstation::log_event(Event e) {
  std::lock_guard<std::mutex> lk(mu_);
  e.t = now_s();
  events_.push_back(e);
  new_events_.push_back(std::move(e));
}

std::vector<Event> Workstation::events() const {
  std::lock_guard<std::mutex> lk(mu_);
  return events_;
}

std::shared_ptr<const PatientGeometry> Workstation::geometry() const {
  std::lock_guard<std::mutex> lk(mu_);
  return geometry_;
}

ForceMapping Workstation::force_mapping() const {
  std::lock_guard<std::mutex> lk(mu_);
  return force_mapping_;
}

std::vector<double> Workstation::applied_young(std::uint64_t* applied) const {
  std::lock_guard<std::mutex> lk(mu_);
  if (applied) *applied = applied_.load();
  return applied_young_;
}

void apply_element_young(sim::Simulation& s, const std::vector<std::pair<int, double>>& changes) {
  s.set_element_young(changes);
}

void apply_params(sim::Simulation& s, const sim::SimParams& p) {
  sim::SimParams q = p;
  q.solver.dt = s.backend().params().solver.dt;  // the real-time dt stays the thread's
  q.solver.threads = s.backend().params().solver.threads;
  s.backend().set_params(q);
}

void Workstation::notify_command(CommandRecord r) {
  r.index = posted_.load();  // the index post() is about to give it
  for (auto& l : command_listeners_) l(r);
}

void Workstation::set_element_young(std::vector<std::pair<int, double>> changes, const std::optional<MaterialEdit>& edit) {
  tumours_.set_young(changes);
  std::optional<Event> e;
  if (edit) {
    e = Event::material(*edit);
    log_event(*e);
  }
  if (!command_listeners_.empty()) notify_command({0, CommandKind::Young, changes, {}, {}, e});
  post([changes = std::move(changes)](sim::Simulation& s) { apply_element_young(s, changes); });
}

void Workstation::set_params(const sim::SimParams& p) {
  log_event(Event::params());
  if (!command_listeners_.empty()) notify_command({0, CommandKind::Params, {}, p, {}, Event::params()});
  post([p](sim::Simulation& s) { apply_params(s, p); });
}

void Workstation::load_patient(const sim::Scenario& s) {
  log_event(Event::patient_loading(s.source));
  if (!command_listeners_.empty()) notify_command({0, CommandKind::Patient, {}, {}, s, Event::patient_loading(s.source)});
  post([this, s](sim::Simulation&) {
    std::lock_guard<std::mutex> lk(mu_);
    opt_.scenario = s;
    swap_pending_ = true;  // sim_main fades the forces out, then rebuilds
  });
}

void Workstation::set_mouse_finger(const Eigen::Vector3d& world, bool present) {
  dv::SimulatedHand::Targets t;
  t.present[dv::kIndex] = present;
  t.position[dv::kIndex] = opt_.config.hand.registration.to_device(to_dev(world));
  device_->set_targets(t);
}

void Workstation::build(const sim::Scenario& s) {
  sim_state_.store(sim_ ? SimState::Swapping : SimState::Loading);
  // A patient that cannot be built leaves the current one running.
  auto simulation = std::make_unique<sim::Simulation>(s);
  simulation->reset();
  configure_realtime_threads(*simulation);
  const sim::Model& m = simulation->model();
  // The force scale of this patient on this device: its deep press into the device's
  // range (live/force_mapping.h), before the first step, on the patient's backend (on the
  // CPU 0.16-0.27 s on the coarse breast, about 1 s on the paper mesh; on the GPU 0.16 s on
  // the paper mesh, 2 s on xfine), while the forces are faded out. A probe that fails leaves
  // the configured scale, else 1: the safety filter's clamp still bounds the forces.
  ForceMapping fm = force_mapping_for(0.0, loop_->params().safety.max_force, opt_.config.force_mapping);
  try {
    fm = measure_force_mapping(*simulation, finger_radius(s), loop_->params().safety.max_force, opt_.config.force_mapping);
  } catch (const std::exception&) {
  }
  sim_loop_->set_force_scale(fm.scale);
  const std::uint64_t generation = generation_.load() + 1;
  generation_.store(generation);
  auto g = make_patient_geometry(*simulation, generation);
  {
    std::lock_guard<std::mutex> lk(mu_);
    geometry_ = g;
    applied_young_ = simulation->materials().young;
    backend_name_ = g->backend;
    force_mapping_ = fm;
  }
  sim_ = std::move(simulation);
  // The scripted hand starts its palpation now: while the patient was built (meshing, the
  // model cache, the deep-press probe) it kept moving, and a first step that finds a
  // fingertip already deep below the skin pulls it in (the contact normals point inward;
  // measured: 10-11 N per push instead of 5-6 N for the rest of the sweep).
  device_->restart_script();
  log_event(Event::patient_loaded(m.num_nodes(), m.num_tets(), g->backend));
  sim_state_.store(SimState::Running);
}

void Workstation::sim_main() {
  try {
    build(opt_.scenario);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lk(mu_);
    load_error_ = e.what();
    sim_state_.store(SimState::Error);
    return;
  }
  const auto& reg = opt_.config.hand.registration;
  constexpr int nf = dv::kMaxFingers;
  std::int64_t last_snapshot = 0;
  const auto snapshot_period = std::int64_t(1e9 / std::max(1.0, opt_.snapshot_hz));
  std::vector<double> xyz;
  sim::StressScratch stress_scratch;
  std::vector<Command> cmds;
  SimulationLoop& loop = *sim_loop_;
  ForceMapping step_mapping = force_mapping();  // the one the steps' models were sent with
  SimulationLoop::Hooks hooks;
  hooks.between_steps = [&] {
    // Queued commands, between steps.
    {
      std::lock_guard<std::mutex> lk(mu_);
      cmds.swap(queue_);
    }
    if (cmds.empty()) return;
    for (auto& c : cmds) {
      try {
        c(*sim_);
      } catch (const std::exception& e) {
        log_event(Event::with_detail(EventKind::Error, e.what()));
      }
    }
    const std::uint64_t n = cmds.size();
    cmds.clear();
    if (swap_pending_) {
      swap_pending_ = false;
      // Patient swap: fade the forces to zero (empty contact models, blended out by the
      // haptic loop over its blend window), then rebuild. The haptic loop keeps running.
      sim_state_.store(SimState::Swapping);
      const std::int64_t fade_end = dv::monotonic_ns() + 100000000;  // 100 ms
      while (dv::monotonic_ns() < fade_end) {
        loop.publish_empty();
        dv::sleep_until_ns(dv::monotonic_ns() + 2000000);
      }
      sim::Scenario s;
      {
        std::lock_guard<std::mutex> lk(mu_);
        s = opt_.scenario;
      }
      try {
        build(s);
      } catch (const std::exception& e) {
        log_event(Event::with_detail(EventKind::PatientNotLoaded, e.what()));
        sim_state_.store(SimState::Running);
      }
      loop.restart(*sim_, std::vector<double>(nf, finger_radius(s)));
      step_mapping = force_mapping();
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      applied_young_ = sim_->materials().young;
    }
    applied_.fetch_add(n);
  };
  hooks.on_fault = [this](const sim::Simulation::Outcome& r) {
    if (r.fell_back) {
      fallbacks_.fetch_add(1);
      {
        std::lock_guard<std::mutex> lk(mu_);
        backend_name_ = sim_->backend().name();
        safety_note_ = sim_->backend_reason();
      }
      log_event(Event::with_detail(EventKind::Fallback, r.error));
    }
    if (!r.ok) {
      divergences_.fetch_add(1);
      const std::string& reason = sim_->last_check().reason;
      const std::string why = reason.empty() ? std::string("non-finite contact output") : reason;
      {
        std::lock_guard<std::mutex> lk(mu_);
        safety_note_ = "divergence reset: " + why;
      }
      log_event(Event::with_detail(EventKind::Reset, why));
    }
  };
  hooks.after_step = [&](const LoopStep& ls) {
    const sim::StepStats& st = ls.outcome->stats;
    StepSample ss{double(ls.start_ns - t0_ns_) * 1e-9, ls.sim_time, float(ls.step_ms), st.cg_iterations, st.contacts, ls.h,
                  applied_.load(), {}, {}, step_mapping};
    for (int d = 0; d < nf; ++d) {
      ss.in[d] = ls.in[std::size_t(d)];
      ss.force[d] = ls.out[std::size_t(d)].force;
    }
    steps_.push(ss);
    if (ls.start_ns - last_snapshot < snapshot_period) return;
    last_snapshot = ls.start_ns;
    sim::Backend& be = sim_->backend();
    be.positions(xyz);
    RenderSnapshot& rs = snapshots_.write_slot();
    rs.model_generation = generation_.load();
    rs.sequence = ls.sequence;
    rs.sim_time = ls.sim_time;
    rs.positions.resize(xyz.size());
    for (std::size_t i = 0; i < xyz.size(); ++i) rs.positions[i] = float(xyz[i]);
    for (int d = 0; d < nf; ++d) {
      rs.finger_position[d] = to_eigen(reg.to_world(ls.poses->fingers[d].position));
      rs.finger_force[d] = ls.in[std::size_t(d)].active ? Eigen::Vector3d(ls.out[std::size_t(d)].force) : Eigen::Vector3d::Zero();
      rs.finger_active[d] = ls.poses->fingers[d].present;
    }
    rs.finger_radius = ls.in[0].radius;
    if (stress_enabled_.load(std::memory_order_acquire)) sim::nodal_von_mises(sim_->model(), sim_->materials(), xyz.data(), rs.von_mises, stress_scratch);
    else rs.von_mises.clear();
    snapshots_.publish();
  };
  try {
    loop.run(*sim_, stop_, hooks);
  } catch (const std::exception& e) {
    // The CPU backend itself failed: nothing left to step. Fade the forces out.
    const std::string why = e.what();
    log_event(Event::with_detail(EventKind::Stopped, why));
    {
      std::lock_guard<std::mutex> lk(mu_);
      load_error_ = "simulation stopped: " + why;
    }
    sim_state_.store(SimState::Error);
    loop.publish_empty();
  }
}

bool Workstation::poll() {
  const auto& reg = opt_.config.hand.registration;
  dv::TickRecord r;
  bool any_tick = false, any_attached = false;
  while (ticks_.pop(r)) {
    any_tick = true;
    any_attached = any_attached || r.attached != 0;
    ++window_ticks_;
    if (prev_tick_ns_ > 0) {
      const double j = std::fabs(double(r.time_ns - prev_tick_ns_) * 1e-3 - opt_.config.loop.period * 1e6);
      window_jitter_ = std::max(window_jitter_, j);
    }
    prev_tick_ns_ = r.time_ns;
    const double t = double(r.time_ns - t0_ns_) * 1e-9;
    for (int f = 0; f < dv::kMaxFingers; ++f) {
      const bool att = (r.attached >> f) & 1;
      stats_.attached[f] = att;
      stats_.force_n[f] = dv::norm(r.force[f]);
      if (tick_listeners_.empty() || !att) continue;
      TickSample s{t, f, to_eigen(reg.to_world(r.position[f])), to_eigen(reg.vector_to_world(r.force[f])), att};
      for (auto& l : tick_listeners_) l(s);
    }
  }
  StepSample ss;
  while (steps_.pop(ss)) {
    ++window_steps_;
    window_sim_s_ += ss.h;
    stats_.step_ms = ss.step_ms;
    stats_.cg_iterations = ss.cg_iterations;
    for (auto& l : step_listeners_) l(ss);
  }
  std::vector<Event> evs;
  {
    std::lock_guard<std::mutex> lk(mu_);
    evs.swap(new_events_);
  }
  for (const auto& e : evs)
    for (auto& l : event_listeners_) l(e);
  const std::int64_t now = dv::monotonic_ns();
  if (now - rate_window_ns_ >= 500000000) {
    const double w = double(now - rate_window_ns_) * 1e-9;
    stats_.haptic_rate_hz = double(window_ticks_) / w;
    stats_.step_rate_hz = double(window_steps_) / w;
    stats_.pace = window_sim_s_ / w;
    stats_.dt_ms = window_steps_ > 0 ? 1e3 * window_sim_s_ / double(window_steps_) : 0.0;
    stats_.jitter_us = window_jitter_;
    window_ticks_ = window_steps_ = 0;
    window_sim_s_ = 0;
    window_jitter_ = 0;
    rate_window_ns_ = now;
  }
  stats_.dropped = ticks_.dropped();
  stats_.fallbacks = fallbacks_.load();
  stats_.divergences = divergences_.load();
  stats_.recovering = sim_loop_->recovering();
  {
    std::lock_guard<std::mutex> lk(mu_);
    stats_.backend = backend_name_;
    stats_.safety_note = safety_note_;
    stats_.force_mapping = force_mapping_;
  }
  if (any_tick) stats_.connected = running() && any_attached;
  if (!running()) stats_.connected = false;
  stats_.state = sim_state_.load();
  std::shared_ptr<const PatientGeometry> g;
  {
    std::lock_guard<std::mutex> lk(mu_);
    stats_.error = stats_.state == SimState::Error ? load_error_ : std::string();
    g = geometry_;
  }
  // The tumour document follows a new patient.
  if (g && g->generation != tumours_.generation()) tumours_.set_patient(std::move(g));
  return snapshots_.update();
}

}  // namespace palpation::app::live
