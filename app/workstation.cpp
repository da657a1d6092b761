#include "workstation.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "device_bridge.h"
#include "fem_stress.h"
#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "haptic_thread.h"
#include "phantom.h"
#include "rt_clock.h"
#include "sim_fingers.h"
#include "simulation.h"

namespace palpation::app {

// ---------------------------------------------------------------------------------------
// WorkstationDevice

WorkstationDevice::WorkstationDevice(dv::HandScript script, dv::DeviceCapabilities caps)
    : script_(std::move(script)), duration_(script_.duration()), caps_(caps) {}

bool WorkstationDevice::read(std::int64_t now_ns, dv::DeviceState& state) {
  if (t0_ < 0) t0_ = now_ns;
  const double dt = prev_ns_ > 0 ? double(now_ns - prev_ns_) * 1e-9 : 0.0;
  prev_ns_ = now_ns;
  const Mode mode = this->mode();
  targets_.update();
  const Targets& tg = targets_.read();
  double t = double(now_ns - t0_) * 1e-9;
  if (duration_ > 0) t = std::fmod(t, duration_);  // the scripted hand palpates in a loop
  for (int f = 0; f < dv::kMaxFingers; ++f) {
    dv::FingerState& fs = state.fingers[f];
    dv::Vec3 p, v;
    if (mode == Mode::Script) {
      fs.present = script_.sample(t, f, p, v);
    } else {
      fs.present = tg.present[f];
      p = tg.position[f];
      v = dt > 0 ? (p - last_pos_[f]) * (1.0 / dt) : dv::Vec3{};
    }
    if (fs.present) {
      fs.position = p;
      fs.velocity = v;
      last_pos_[f] = p;
    }
    fs.attached = fs.present;
    fs.torque_limited = false;
  }
  state.device_time_ns = now_ns;
  state.received_ns = now_ns;
  state.sequence = ++seq_;
  state.connected = true;
  state.device_watchdog = false;
  return true;
}

void WorkstationDevice::write(std::int64_t, const dv::ForceCommand&) {}

// ---------------------------------------------------------------------------------------
// Defaults

sim::Scenario default_workstation_scenario() {
  sim::Scenario s = sim::builtin_scenario("paper-sweep");
  s.source = "default patient (paper breast, coarse)";
  s.patient.resolution = "coarse";
  s.patient.edge = *sim::resolution_edge("breast", "coarse");
  s.backend = "auto";
  // Real time on a CPU (docs/benchmarks.md, session 5): on the coarse breast float and CG
  // 1e-2 give the same force error as double and CG 1e-6 (1.2e-4: the kept rotations'
  // error dominates) at 0.6-0.8 ms a step on this project's 2-core VM, against 1.3 ms at
  // the scenario defaults (double, 1e-3). The Simulation panel changes them.
  s.params.solver.precision = sim::Precision::Float;
  s.params.solver.cg_tolerance = 1e-2;
  return s;
}

dv::HandScript default_hand_script(const DeviceConfig& cfg) {
  const sim::Scenario paper = sim::builtin_scenario("paper-sweep");
  const auto& reg = cfg.hand.registration;
  const auto& keys = paper.fingers.at(0).keys;
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
/// The linear blend (1 - g) a + g b of two local contact models (F(x) = F0 + K (x - x0)),
/// exact at every x: expressed about b's x0 (or a's when b has none). g in [0, 1].
dv::FingerContactModel blended(const dv::FingerContactModel& a, const dv::FingerContactModel& b, double g) {
  if (!a.valid && !b.valid) return b;
  dv::FingerContactModel m = b.valid ? b : a;
  const double wa = a.valid ? 1.0 - g : 0.0, wb = b.valid ? g : 0.0;
  const dv::Vec3 fa = a.valid ? a.force + a.stiffness * (m.position - a.position) : dv::Vec3{};
  m.force = fa * wa + (b.valid ? b.force : dv::Vec3{}) * wb;
  m.stiffness = (a.valid ? a.stiffness : dv::Mat3{}) * wa + (b.valid ? b.stiffness : dv::Mat3{}) * wb;
  m.contacts = std::max(a.valid ? a.contacts : 0, b.valid ? b.contacts : 0);
  if (!b.valid || b.contacts == 0) {
    m.normal = a.normal;
    m.contact_point = a.contact_point;
  }
  m.valid = true;
  return m;
}
}  // namespace

std::shared_ptr<PatientGeometry> make_patient_geometry(sim::Simulation& simulation, std::uint64_t generation) {
  auto g = std::make_shared<PatientGeometry>();
  const sim::Model& m = simulation.model();
  g->generation = generation;
  g->rest = m.rest;
  g->tets = m.tets;
  g->surface = m.surface;
  g->young = m.young;
  g->centroid.resize(m.tets.size());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) c += m.rest[std::size_t(m.tets[e][a])];
    g->centroid[e] = c / 4.0;
  }
  g->tissue_young = simulation.scenario().young_modulus;
  g->tissue_poisson = simulation.scenario().poisson_ratio;
  auto& be = simulation.backend();
  g->backend = be.name();
  g->device_name = be.device_name();
  return g;
}

void Workstation::publish_empty(std::uint64_t& seq, double sim_time) {
  dv::ContactFrame& cf = contacts_.write_slot();
  cf.fingers = {};
  cf.sequence = ++seq;
  cf.sim_time = sim_time;
  cf.published_ns = dv::monotonic_ns();
  contacts_.publish();
}

struct Workstation::Threads {
  HapticThread haptic;
  PeriodicThread emulator;  // the robot side, "emulator" only
  explicit Threads(dv::HapticLoop& l) : haptic(l) {}
};

Workstation::Workstation(WorkstationOptions opt) : opt_(std::move(opt)) {
  const auto& caps = opt_.config.hand.capabilities;
  device_ = std::make_unique<WorkstationDevice>(default_hand_script(opt_.config), caps);
  std::string err;
  if (opt_.device == "emulator") {
    // As in session.cpp: the emulator on a free loopback port, the link to it.
    dv::EmulatorOptions eo;
    eo.bind_address = "127.0.0.1";
    eo.port = 0;
    auto em = std::make_unique<dv::HandHiroEmulator>(opt_.config.hand, default_hand_script(opt_.config), eo);
    if (!em->open(&err)) throw std::runtime_error("emulator: " + err);
    dv::LinkConfig lc = opt_.config.link;
    lc.robot_address = "127.0.0.1";
    lc.robot_port = em->port();
    lc.bind_address = "127.0.0.1";
    lc.bind_port = 0;
    auto link = std::make_unique<dv::HandHiroLink>(caps, lc);
    if (!link->open(&err)) throw std::runtime_error("link: " + err);
    emulator_ = std::move(em);
    link_ = std::move(link);
  } else if (opt_.device == "handhiro") {
    dv::LinkConfig lc = opt_.config.link;
    if (!opt_.robot_address.empty()) lc.robot_address = opt_.robot_address;
    if (opt_.robot_port > 0) lc.robot_port = std::uint16_t(opt_.robot_port);
    auto link = std::make_unique<dv::HandHiroLink>(caps, lc);
    if (!link->open(&err)) throw std::runtime_error("link: " + err);
    link_ = std::move(link);
  } else if (opt_.device != "simulated") {
    throw std::runtime_error("device: must be simulated, emulator or handhiro, got \"" + opt_.device + "\"");
  }
  dv::HapticDevice& dev = link_ ? *link_ : static_cast<dv::HapticDevice&>(*device_);
  loop_ = std::make_unique<dv::HapticLoop>(dev, poses_, contacts_, &ticks_, opt_.config.loop);
  threads_ = std::make_unique<Threads>(*loop_);
}

std::string Workstation::device_description() const {
  if (opt_.device == "emulator") return "HandHIRO emulator (UDP loopback)";
  if (opt_.device == "handhiro") {
    const std::string a = opt_.robot_address.empty() ? opt_.config.link.robot_address : opt_.robot_address;
    const int p = opt_.robot_port > 0 ? opt_.robot_port : opt_.config.link.robot_port;
    return "HandHIRO at " + a + ":" + std::to_string(p);
  }
  return device_->mode() == WorkstationDevice::Mode::Mouse ? "mouse" : "simulated HandHIRO";
}

Workstation::~Workstation() { stop(); }

double Workstation::now_s() const { return t0_ns_ ? double(dv::monotonic_ns() - t0_ns_) * 1e-9 : 0.0; }

void Workstation::start() {
  if (running()) return;
  t0_ns_ = dv::monotonic_ns();
  rate_window_ns_ = t0_ns_;
  stop_.store(false);
  sim_state_.store(1);
  sim_thread_ = std::thread([this] { sim_main(); });
  if (emulator_) {
    dv::HandHiroEmulator* em = emulator_.get();
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
  sim_state_.store(0);
}

void Workstation::post(Command c) {
  std::lock_guard<std::mutex> lk(mu_);
  queue_.push_back(std::move(c));
  posted_.fetch_add(1);
}

void Workstation::log_event(const std::string& kind, const std::string& text) {
  std::lock_guard<std::mutex> lk(mu_);
  Event e{now_s(), kind, text};
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

std::vector<double> Workstation::applied_young(std::uint64_t* applied) const {
  std::lock_guard<std::mutex> lk(mu_);
  if (applied) *applied = applied_.load();
  return applied_young_;
}

void apply_element_young(sim::Simulation& s, const std::vector<std::pair<int, double>>& changes) {
  sim::Model& m = s.model();
  for (const auto& [e, E] : changes)
    if (e >= 0 && e < m.num_tets() && E > 0) m.set_element_material(e, E, m.poisson[e]);
  s.backend().update_materials();
}

void apply_params(sim::Simulation& s, const sim::SimParams& p) {
  sim::SimParams q = p;
  q.solver.dt = s.backend().params().solver.dt;  // the real-time dt stays the thread's
  q.solver.threads = s.backend().params().solver.threads;
  s.backend().set_params(q);
}

void configure_workstation_threads(sim::Simulation& s) {
  sim::SimParams params = s.backend().params();
  // On a small machine the haptic thread needs a core of its own (see session.cpp).
  if (params.solver.threads == 0 && std::thread::hardware_concurrency() <= 3) {
    params.solver.threads = 1;
    s.backend().set_params(params);
  }
}

void Workstation::notify_command(CommandRecord r) {
  r.index = posted_.load();  // the index post() is about to give it
  for (auto& l : command_listeners_) l(r);
}

void Workstation::set_element_young(std::vector<std::pair<int, double>> changes, const std::string& event_text) {
  if (!event_text.empty()) log_event("material", event_text);
  if (!command_listeners_.empty()) notify_command({0, "young", changes, {}, {}, event_text});
  post([changes = std::move(changes)](sim::Simulation& s) { apply_element_young(s, changes); });
}

void Workstation::set_params(const sim::SimParams& p) {
  log_event("params", "solver/contact parameters changed");
  if (!command_listeners_.empty()) notify_command({0, "params", {}, p, {}, "solver/contact parameters changed"});
  post([p](sim::Simulation& s) { apply_params(s, p); });
}

void Workstation::load_patient(const sim::Scenario& s) {
  log_event("patient", "loading patient: " + s.source);
  if (!command_listeners_.empty()) notify_command({0, "patient", {}, {}, s, "loading patient: " + s.source});
  post([this, s](sim::Simulation&) {
    std::lock_guard<std::mutex> lk(mu_);
    opt_.scenario = s;
    swap_pending_ = true;  // sim_main fades the forces out, then rebuilds
  });
}

void Workstation::set_mouse_finger(const Eigen::Vector3d& world, bool present) {
  WorkstationDevice::Targets t;
  t.present[dv::kIndex] = present;
  t.position[dv::kIndex] = opt_.config.hand.registration.to_device(to_dev(world));
  device_->set_targets(t);
}

void Workstation::build(const sim::Scenario& s) {
  sim_state_.store(sim_ ? 3 : 1);
  sim_.reset();
  auto simulation = std::make_unique<sim::Simulation>(s);
  simulation->reset();
  configure_workstation_threads(*simulation);
  const sim::Model& m = simulation->model();
  const std::uint64_t generation = generation_.load() + 1;
  generation_.store(generation);
  auto g = make_patient_geometry(*simulation, generation);
  {
    std::lock_guard<std::mutex> lk(mu_);
    geometry_ = g;
    applied_young_ = m.young;
    backend_name_ = g->backend;
  }
  sim_ = std::move(simulation);
  log_event("patient", "patient loaded: " + std::to_string(m.num_nodes()) + " nodes, " + std::to_string(m.num_tets()) +
                           " tetrahedra, backend " + g->backend);
  sim_state_.store(2);
}

void Workstation::sim_main() {
  try {
    build(opt_.scenario);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lk(mu_);
    load_error_ = e.what();
    sim_state_.store(4);
    return;
  }
  const auto& reg = opt_.config.hand.registration;
  const double kc = loop_->params().virtual_coupling ? loop_->params().coupling_stiffness : 0.0;
  constexpr int nf = dv::kMaxFingers;
  std::vector<sim::FingerInput> in(nf);
  std::vector<sim::FingerOutput> out(nf);
  std::array<dv::FingerContactModel, nf> last{};
  // Previous step's simulated force (spike guard). Eigen does not zero-initialise, and
  // `{}` value-initialises the array but not the vectors in it: fill explicitly.
  std::array<Eigen::Vector3d, nf> prev_force;
  prev_force.fill(Eigen::Vector3d::Zero());
  const double dt = opt_.scenario.params.solver.dt;
  std::int64_t prev_start = 0, last_snapshot = 0;
  const auto snapshot_period = std::int64_t(1e9 / std::max(1.0, opt_.snapshot_hz));
  std::uint64_t seq = 0;
  double sim_time = 0;
  std::vector<double> xyz;
  sim::StressScratch stress_scratch;
  std::vector<Command> cmds;
  while (!stop_.load(std::memory_order_acquire)) {
    // Queued commands, between steps.
    {
      std::lock_guard<std::mutex> lk(mu_);
      cmds.swap(queue_);
    }
    if (!cmds.empty()) {
      for (auto& c : cmds) {
        try {
          c(*sim_);
        } catch (const std::exception& e) {
          log_event("error", e.what());
        }
      }
      const std::uint64_t n = cmds.size();
      cmds.clear();
      if (swap_pending_) {
        swap_pending_ = false;
        // Patient swap: fade the forces to zero (empty contact models, blended out by the
        // haptic loop over its blend window), then rebuild. The haptic loop keeps running.
        sim_state_.store(3);
        const std::int64_t fade_end = dv::monotonic_ns() + 100000000;  // 100 ms
        while (dv::monotonic_ns() < fade_end) {
          publish_empty(seq, sim_time);
          dv::sleep_until_ns(dv::monotonic_ns() + 2000000);
        }
        last = {};
        prev_force.fill(Eigen::Vector3d::Zero());
        good_ = held_ = {};
        recovering_.store(false);
        sim::Scenario s;
        {
          std::lock_guard<std::mutex> lk(mu_);
          s = opt_.scenario;
        }
        try {
          build(s);
        } catch (const std::exception& e) {
          log_event("error", std::string("patient not loaded: ") + e.what());
          sim_state_.store(2);
        }
        prev_start = 0;
        for (auto& f : in) f.active = false;
      }
      {
        std::lock_guard<std::mutex> lk(mu_);
        applied_young_ = sim_->model().young;
      }
      applied_.fetch_add(n);
    }

    poses_.update();
    const dv::PoseFrame& pf = poses_.read();
    if (pf.tick == 0) {
      dv::sleep_until_ns(dv::monotonic_ns() + 1000000);
      continue;
    }
    const std::int64_t now = dv::monotonic_ns();
    double h = dt;
    if (prev_start != 0) {
      // Real-time dt as in the session (session.cpp): never faster than the scenario's dt,
      // at most sim_max_dt.
      const std::int64_t due = prev_start + std::int64_t(dt * 1e9);
      if (now < due) {
        dv::sleep_until_ns(due);
        continue;
      }
      h = std::min(double(now - prev_start) * 1e-9, opt_.sim_max_dt);
    }
    const double since = prev_start == 0 ? 0.0 : double(now - prev_start) * 1e-9;
    prev_start = now;
    for (int d = 0; d < nf; ++d) {
      in[d].radius = opt_.scenario.fingers.empty() ? 0.008 : opt_.scenario.fingers[0].radius;
      finger_from_pose(pf, d, last[d], kc, reg, since, in[d]);
    }
    if (sim_->backend().params().solver.dt != h) {
      sim::SimParams p = sim_->backend().params();
      p.solver.dt = h;
      sim_->backend().set_params(p);
    }
    const auto a = std::chrono::steady_clock::now();
    sim::StepStats st;
    bool fault = false;
    try {
      st = sim_->backend().step(in, out);
    } catch (const std::exception& e) {
      // A backend error mid-session (a CUDA error, design.md section 7): continue on the
      // CPU from rest; the forces are held, then blended below (no spike).
      const std::string why = e.what();
      if (!sim_->fall_back_to_cpu(why)) {
        // The CPU backend itself failed: nothing left to step. Fade the forces out.
        log_event("error", "simulation stopped: " + why);
        {
          std::lock_guard<std::mutex> lk(mu_);
          load_error_ = "simulation stopped: " + why;
        }
        sim_state_.store(4);
        publish_empty(seq, sim_time);
        return;
      }
      fault = true;
      fallbacks_.fetch_add(1);
      {
        std::lock_guard<std::mutex> lk(mu_);
        backend_name_ = sim_->backend().name();
        safety_note_ = sim_->backend_reason();
      }
      log_event("fallback", "backend error: " + why + "; continuing on the CPU from rest (forces held, then blended)");
      st = sim_->backend().step(in, out);
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
    sim_time += h;
    // Divergence guard (design.md section 7, sim::Simulation::check_divergence): NaN/Inf
    // or an energy blow-up puts the body back to rest, logged.
    const sim::DivergenceCheck& chk = sim_->check_divergence(st, out);
    bool ok = !chk.diverged;
    for (const auto& o : out) ok = ok && o.force.allFinite() && o.stiffness.allFinite();
    if (!ok) {
      if (!chk.diverged) sim_->backend().reset();
      divergences_.fetch_add(1);
      const std::string why = chk.reason.empty() ? std::string("non-finite contact output") : chk.reason;
      {
        std::lock_guard<std::mutex> lk(mu_);
        safety_note_ = "divergence reset: " + why;
      }
      log_event("reset", "simulation diverged (" + why + "): body reset to rest (forces held, then blended)");
      fault = true;
    }
    if (fault) {
      // Recovery: the body restarted at rest, so its first forces (a fingertip deep in an
      // undeformed body) are not the ones the hand felt. Hold the last good models while
      // the new body settles around the fingers, then blend over to the new ones.
      recover_start_ = now;
      blend_start_ = 0;
      settled_for_ = 0;
      if (!recovering_.load()) held_ = good_;
      recovering_.store(true);
    }
    dv::ContactFrame& cf = contacts_.write_slot();
    cf.fingers = {};
    bool steady = ok;
    for (int d = 0; d < nf; ++d) {
      if (ok && in[d].active)
        cf.fingers[d] = contact_model(opt_.spike_guard ? guard_force_spike(out[d], prev_force[d]) : out[d], in[d].position, reg);
      const Eigen::Vector3d now_f = ok && in[d].active && out[d].contacts > 0 ? Eigen::Vector3d(out[d].force) : Eigen::Vector3d::Zero();
      // Steady: changing by less than 100 % of itself + 0.5 N per second (at the 10 ms
      // real-time dt, 1 % + 5 mN per step); judged per second so a small dt does not pass a
      // body that is still moving.
      steady = steady && (now_f - prev_force[d]).norm() <= h * (prev_force[d].norm() + 0.5);
      prev_force[d] = now_f;
    }
    if (recovering_.load()) {
      settled_for_ = steady && !fault ? settled_for_ + h : 0.0;
      const double t = double(now - recover_start_) * 1e-9;
      const double hold = std::max(opt_.recover_hold_s, 0.0), blend = std::max(opt_.recover_blend_s, 0.0);
      const double hold_max = std::max(opt_.recover_hold_max_s, hold);
      if (blend_start_ == 0 && t >= hold && (settled_for_ >= 0.1 || t >= hold_max || hold_max == 0)) blend_start_ = now;
      const double tb = blend_start_ == 0 ? -1.0 : double(now - blend_start_) * 1e-9;
      if (tb < 0) {
        cf.fingers = held_;
      } else if (tb < blend) {
        const double g = tb / blend;
        for (int d = 0; d < nf; ++d) cf.fingers[d] = blended(held_[d], cf.fingers[d], g);
      } else {
        recovering_.store(false);
      }
    }
    if (!recovering_.load()) good_ = cf.fingers;
    last = cf.fingers;
    cf.sequence = ++seq;
    cf.sim_time = sim_time;
    cf.published_ns = dv::monotonic_ns();
    contacts_.publish();
    StepSample ss{double(now - t0_ns_) * 1e-9, sim_time, float(ms), st.cg_iterations, st.contacts, h, applied_.load(), {}, {}};
    for (int d = 0; d < nf; ++d) {
      ss.in[d] = in[d];
      ss.force[d] = ok ? Eigen::Vector3d(out[d].force) : Eigen::Vector3d::Zero();
    }
    steps_.push(ss);

    if (now - last_snapshot >= snapshot_period) {
      last_snapshot = now;
      sim::Backend& be = sim_->backend();
      be.positions(xyz);
      RenderSnapshot& rs = snapshots_.write_slot();
      rs.model_generation = generation_.load();
      rs.sequence = seq;
      rs.sim_time = sim_time;
      rs.positions.resize(xyz.size());
      for (std::size_t i = 0; i < xyz.size(); ++i) rs.positions[i] = float(xyz[i]);
      for (int d = 0; d < nf; ++d) {
        rs.finger_position[d] = to_eigen(reg.to_world(pf.fingers[d].position));
        rs.finger_force[d] = ok && in[d].active ? Eigen::Vector3d(out[d].force) : Eigen::Vector3d::Zero();
        rs.finger_active[d] = pf.fingers[d].present;
      }
      rs.finger_radius = in[0].radius;
      if (stress_enabled_.load(std::memory_order_acquire)) sim::nodal_von_mises(sim_->model(), xyz.data(), rs.von_mises, stress_scratch);
      else rs.von_mises.clear();
      snapshots_.publish();
    }
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
    stats_.jitter_us = window_jitter_;
    window_ticks_ = window_steps_ = 0;
    window_jitter_ = 0;
    rate_window_ns_ = now;
  }
  stats_.dropped = ticks_.dropped();
  stats_.fallbacks = fallbacks_.load();
  stats_.divergences = divergences_.load();
  stats_.recovering = recovering_.load();
  {
    std::lock_guard<std::mutex> lk(mu_);
    stats_.backend = backend_name_;
    stats_.safety_note = safety_note_;
  }
  if (any_tick) stats_.connected = running() && any_attached;
  if (!running()) stats_.connected = false;
  switch (sim_state_.load()) {
    case 0: stats_.state = "stopped"; break;
    case 1: stats_.state = "loading"; break;
    case 2: stats_.state = "running"; break;
    case 3: stats_.state = "swapping"; break;
    default: {
      std::lock_guard<std::mutex> lk(mu_);
      stats_.state = "error: " + load_error_;
    }
  }
  return snapshots_.update();
}

}  // namespace palpation::app
