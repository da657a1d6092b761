#include "haptic_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace palpation::device {

HapticLoop::HapticLoop(HapticDevice& device, TripleBuffer<PoseFrame>& poses, TripleBuffer<ContactFrame>& contacts,
                       SpscRing<TickRecord>* telemetry, const HapticLoopParams& params)
    : device_(device), poses_(poses), contacts_(contacts), telemetry_(telemetry), p_(params) {
  const DeviceCapabilities caps = device_.capabilities();
  p_.safety.max_force = std::min(p_.safety.max_force, caps.max_force);
  p_.safety.max_damping = std::min(p_.safety.max_damping, caps.max_damping);
  p_.max_stiffness = std::min(p_.max_stiffness, caps.max_stiffness);
  if (!(p_.coupling_stiffness > 0) || p_.coupling_stiffness > p_.max_stiffness) p_.coupling_stiffness = p_.max_stiffness;
  safety_.set_params(p_.safety);
  safety_.reset();
}

Coupled HapticLoop::render(const FingerContactModel& m, const Vec3& x) const {
  if (p_.virtual_coupling) return couple(m, x, p_.coupling_stiffness);
  return {evaluate(m, x, p_.max_stiffness), x};
}

void HapticLoop::tick(std::int64_t now_ns, std::int64_t deadline_ns) {
  // Statistics of the timing.
  if (stats_.ticks == 0) {
    stats_.first_ns = now_ns;
  } else {
    const double period_us = double(now_ns - prev_ns_) * 1e-3;
    stats_.period_us.add(period_us);
    stats_.jitter_us.add(std::fabs(period_us - p_.period * 1e6));
  }
  stats_.latency_us.add(double(now_ns - deadline_ns) * 1e-3);
  prev_ns_ = now_ns;
  stats_.last_ns = now_ns;
  ++stats_.ticks;

  // 1. Read the fingertips.
  if (device_.read(now_ns, state_)) ++stats_.device_updates;

  // 2. The newest contact model; 3. evaluate it at the current positions.
  const ContactFrame& before = contacts_.read();
  std::array<Vec3, kMaxFingers> prev_force{};
  for (int f = 0; f < kMaxFingers; ++f) {
    const double w = blend_left_ > 0 ? double(blend_left_) / double(blend_len_) : 0.0;
    prev_force[f] = render(before.fingers[f], state_.fingers[f].position).force + offset_[f] * w;
  }
  if (contacts_.update()) {
    ++stats_.model_updates;
    const double interval = double(stats_.ticks - last_update_tick_);
    if (last_update_tick_ > 0) update_interval_ticks_ += 0.2 * (interval - update_interval_ticks_);
    last_update_tick_ = stats_.ticks;
    blend_len_ = std::clamp(int(std::lround(update_interval_ticks_)), 1, std::max(1, p_.blend_max_ticks));
    const ContactFrame& now_frame = contacts_.read();
    for (int f = 0; f < kMaxFingers; ++f) {
      // Fade from what was rendered to the new model (a non-finite old force fades nothing).
      const Vec3 fresh = render(now_frame.fingers[f], state_.fingers[f].position).force;
      const Vec3 d = prev_force[f] - fresh;
      offset_[f] = finite(d) ? d : Vec3{};
    }
    blend_left_ = blend_len_;
  }
  const ContactFrame& frame = contacts_.read();
  const double w = blend_left_ > 0 ? double(blend_left_) / double(blend_len_) : 0.0;
  for (int f = 0; f < kMaxFingers; ++f) {
    const Coupled c = render(frame.fingers[f], state_.fingers[f].position);
    proxy_[f] = c.proxy;
    Vec3 fnew = c.force + offset_[f] * w;
    // The fade must not turn the force adhesive either: drop a component into the surface.
    const Vec3& n = frame.fingers[f].normal;
    const double fn = dot(fnew, n);
    if (frame.fingers[f].valid && frame.fingers[f].contacts > 0 && fn < 0) fnew -= n * (fn / std::max(dot(n, n), 1e-300));
    if (stats_.ticks > 1 && finite(fnew) && finite(desired_[f]))
      stats_.max_model_step = std::max(stats_.max_model_step, norm(fnew - desired_[f]));
    desired_[f] = fnew;
  }
  if (blend_left_ > 0) --blend_left_;
  if (blend_left_ == 0) offset_ = {};

  // 4. Publish the fingertips and the proxies for the simulation.
  PoseFrame& pf = poses_.write_slot();
  pf.fingers = state_.fingers;
  pf.proxy = proxy_;
  pf.time_ns = now_ns;
  pf.tick = stats_.ticks;
  pf.connected = state_.connected;
  poses_.publish();

  // 5. Safety filter, 6. send.
  const double sim_age = frame.sequence == 0 ? std::numeric_limits<double>::infinity()
                                             : double(now_ns - frame.published_ns) * 1e-9;
  safety_.apply(now_ns, state_, sim_age, desired_, command_);
  device_.write(now_ns, command_);

  // 7. Record.
  if (telemetry_) {
    TickRecord r;
    r.time_ns = now_ns;
    for (int f = 0; f < kMaxFingers; ++f) {
      r.position[f] = state_.fingers[f].position;
      r.force[f] = command_.force[f];
      if (state_.fingers[f].attached) r.attached |= std::uint8_t(1u << f);
    }
    r.gain = float(safety_.gain());
    if (!telemetry_->push(r)) ++stats_.telemetry_dropped;
  }
}

void HapticLoop::stop(std::int64_t now_ns) {
  ForceCommand zero;
  device_.write(now_ns, zero);
}

}  // namespace palpation::device
