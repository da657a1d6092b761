#include "live/simulation_loop.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "live/device_bridge.h"
#include "rt_clock.h"
#include "live/sim_fingers.h"

namespace palpation::app::live {

namespace dv = palpation::device;

void configure_realtime_threads(sim::Simulation& s) {
  sim::SimParams params = s.backend().params();
  if (params.solver.threads == 0 && std::thread::hardware_concurrency() <= 3) {
    params.solver.threads = 1;
    s.backend().set_params(params);
  }
}

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

SimulationLoop::SimulationLoop(dv::TripleBuffer<dv::PoseFrame>& poses, dv::TripleBuffer<dv::ContactFrame>& contacts,
                               SimulationLoopOptions opt)
    : poses_(poses), contacts_(contacts), opt_(std::move(opt)), pacer_(opt_.dt, opt_.max_dt) {
  const std::size_t nf = opt_.finger_map.size();
  in_.resize(nf);
  out_.resize(nf);
  prev_force_.assign(nf, Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < nf; ++k) in_[k].radius = k < opt_.radius.size() ? opt_.radius[k] : 0.008;
}

void SimulationLoop::restart(sim::Simulation& simulation, const std::vector<double>& radius) {
  sim_ = &simulation;
  levels_.forget();
  sim_->set_deferred_levels(opt_.deferred_levels);
  for (std::size_t k = 0; k < in_.size() && k < radius.size(); ++k) in_[k].radius = radius[k];
  last_ = {};
  std::fill(prev_force_.begin(), prev_force_.end(), Eigen::Vector3d::Zero());
  good_ = held_ = {};
  recovering_.store(false);
  prev_start_ = 0;
  pacer_.restart();
  for (auto& f : in_) f.active = false;
}

void SimulationLoop::publish_empty() {
  dv::ContactFrame& cf = contacts_.write_slot();
  cf.fingers = {};
  cf.sequence = ++seq_;
  cf.sim_time = sim_time_;
  cf.published_ns = dv::monotonic_ns();
  contacts_.publish();
}

void SimulationLoop::run(sim::Simulation& simulation, const std::atomic<bool>& stop, const Hooks& hooks) {
  sim_ = &simulation;
  sim_->set_deferred_levels(opt_.deferred_levels);
  const int nf = int(in_.size());
  const double dt = opt_.dt;
  while (!stop.load(std::memory_order_acquire)) {
    if (hooks.between_steps) hooks.between_steps();
    poses_.update();
    const dv::PoseFrame& pf = poses_.read();
    if (pf.tick == 0) {
      dv::sleep_until_ns(dv::monotonic_ns() + 1000000);
      continue;
    }
    const std::int64_t now = dv::monotonic_ns();
    double h = dt;
    if (opt_.realtime) {
      const StepPacer::Slot slot = pacer_.next(now);
      if (slot.wait) {
        dv::sleep_until_ns(slot.until_ns);
        continue;
      }
      h = slot.h;
    } else if (prev_start_ != 0) {
      const std::int64_t due = first_step_ns_ + std::int64_t(sim_time_ * 1e9);
      if (now < due) {
        dv::sleep_until_ns(due);
        continue;
      }
    }
    if (prev_start_ == 0) first_step_ns_ = now;
    const double since = prev_start_ == 0 ? 0.0 : double(now - prev_start_) * 1e-9;
    prev_start_ = now;
    for (int k = 0; k < nf; ++k) {
      // With the virtual coupling, the proxy balanced against this thread's newest contact
      // model at the newest device position (computed here, not taken from the haptic
      // loop, whose proxy may still be one model behind); with direct coupling, the
      // device's fingertip.
      const int d = opt_.finger_map[std::size_t(k)];
      finger_from_pose(pf, d, last_[std::size_t(d)], opt_.coupling_stiffness, opt_.registration, since, in_[std::size_t(k)]);
    }
    const auto a = std::chrono::steady_clock::now();
    const sim::Simulation::Outcome r = sim_->advance(in_, out_, h);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
    sim_time_ += h;
    if (!r.ok || r.fell_back) {
      if (hooks.on_fault) hooks.on_fault(r);
      // The body restarted at rest, so its first forces (a fingertip deep in an undeformed
      // body) are not the ones the hand felt: hold the last good models while the new body
      // settles around the fingers, then blend over to the new ones.
      recover_start_ = now;
      blend_start_ = 0;
      settled_for_ = 0;
      if (!recovering_.load()) held_ = good_;
      recovering_.store(true);
    }
    publish(r, now, h);
    if (hooks.after_step) {
      LoopStep ls;
      ls.start_ns = now;
      ls.published_ns = published_ns_;
      ls.h = h;
      ls.sim_time = sim_time_;
      ls.step_ms = ms;
      ls.sequence = seq_;
      ls.outcome = &r;
      ls.in = in_;
      ls.out = out_;
      ls.poses = &pf;
      hooks.after_step(ls);
    }
    // Between steps: new multigrid levels built meanwhile go in use; a rebuild that fell due
    // in this step starts on the builder's thread.
    if (opt_.deferred_levels) levels_.poll(sim_->backend());
  }
}

void SimulationLoop::publish(const sim::Simulation::Outcome& r, std::int64_t now, double h) {
  const bool ok = r.ok;
  const bool fault = !r.ok || r.fell_back;
  dv::ContactFrame& cf = contacts_.write_slot();
  cf.fingers = {};
  bool steady = ok;
  for (std::size_t k = 0; k < in_.size(); ++k) {
    const std::size_t d = std::size_t(opt_.finger_map[k]);
    if (ok && in_[k].active)
      cf.fingers[d] = contact_model(opt_.spike_guard ? guard_force_spike(out_[k], prev_force_[k]) : out_[k], in_[k].position,
                                    opt_.registration, opt_.force_scale);
    const Eigen::Vector3d now_f =
        ok && in_[k].active && out_[k].contacts > 0 ? Eigen::Vector3d(out_[k].force) : Eigen::Vector3d::Zero();
    // Steady: changing by less than 100 % of itself + 0.5 N per second (at the 10 ms
    // real-time dt, 1 % + 5 mN per step); judged per second so a small dt does not pass a
    // body that is still moving.
    steady = steady && (now_f - prev_force_[k]).norm() <= h * (prev_force_[k].norm() + 0.5);
    prev_force_[k] = now_f;
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
      for (int d = 0; d < dv::kMaxFingers; ++d) cf.fingers[std::size_t(d)] = blended(held_[std::size_t(d)], cf.fingers[std::size_t(d)], g);
    } else {
      recovering_.store(false);
    }
  }
  if (!recovering_.load()) good_ = cf.fingers;
  last_ = cf.fingers;
  cf.sequence = ++seq_;
  cf.sim_time = sim_time_;
  cf.published_ns = dv::monotonic_ns();
  published_ns_ = cf.published_ns;
  contacts_.publish();
}

}  // namespace palpation::app::live
