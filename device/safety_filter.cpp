#include "safety_filter.h"

#include <algorithm>
#include <cmath>

namespace palpation::device {

void SafetyFilter::reset() {
  finger_ = {};
  c_ = {};
  gain_ = 0;
  stale_ = true;
  linked_ = false;
  started_ = false;
  last_ns_ = 0;
}

void SafetyFilter::apply(std::int64_t now_ns, const DeviceState& state, double sim_age_s,
                         const std::array<Vec3, kMaxFingers>& desired, ForceCommand& out) {
  constexpr double kNominalDt = 0.001;
  double dt = started_ ? double(now_ns - last_ns_) * 1e-9 : kNominalDt;
  if (!(dt > 0)) dt = 1e-6;
  dt = std::min(dt, 0.02);  // a stalled loop advances ramps and rate limits by at most 20 ms
  started_ = true;
  last_ns_ = now_ns;
  ++c_.ticks;

  // Global gain: simulation fresh and device linked -> 1, else ramp to 0.
  const bool stale = !(sim_age_s <= p_.stale_after);
  if (stale && !stale_) ++c_.stale_events;
  stale_ = stale;
  if (!state.connected && linked_) ++c_.link_events;
  linked_ = state.connected;
  const bool go = !stale && state.connected;
  if (go) gain_ = std::min(1.0, gain_ + (p_.ramp_in > 0 ? dt / p_.ramp_in : 1.0));
  else gain_ = std::max(0.0, gain_ - (p_.ramp_out > 0 ? dt / p_.ramp_out : 1.0));

  const double hp_tau = 1.0 / (2.0 * M_PI * std::max(p_.passivity_highpass_hz, 1e-3));
  const double hp_a = hp_tau / (hp_tau + dt);
  const double leak = p_.passivity_leak > 0 ? std::exp(-dt / p_.passivity_leak) : 1.0;
  const double step_max = p_.max_rate * dt;

  for (int f = 0; f < kMaxFingers; ++f) {
    Finger& s = finger_[f];
    const FingerState& fs = state.fingers[f];
    const bool attached = fs.present && fs.attached;
    if (attached && !s.attached && s.seen) ++c_.reattaches;
    if (!attached && s.attached) ++c_.releases;
    s.attached = attached;
    s.seen = s.seen || attached;
    out.enabled[f] = attached;
    if (!attached) {
      // Released (or absent): the fingertip is free, render nothing, ramp in again later.
      s.gain = 0;
      s.out = {};
      s.have_prev = false;
      s.w = 0;
      out.force[f] = {};
      continue;
    }
    s.gain = std::min(1.0, s.gain + (p_.ramp_in > 0 ? dt / p_.ramp_in : 1.0));

    // 1. Non-finite guard.
    Vec3 f_des = desired[f];
    const bool pos_ok = finite(fs.position) && finite(fs.velocity);
    if (!finite(f_des) || !pos_ok) {
      ++c_.nonfinite;
      f_des = {};
    } else {
      c_.max_desired = std::max(c_.max_desired, norm(f_des));
    }

    // 2. Passivity observer/controller in the vibration band.
    if (pos_ok) {
      if (!s.have_prev) {
        s.x_prev = fs.position;
        s.v_prev = {};
        s.v_hp = {};
        s.f_prev_in = s.out;
        s.f_hp = {};
        s.have_prev = true;
      }
      const Vec3 v = (fs.position - s.x_prev) * (1.0 / dt);
      s.x_prev = fs.position;
      s.v_hp = (s.v_hp + v - s.v_prev) * hp_a;
      s.v_prev = v;
      s.w += dot(s.f_hp, s.v_hp) * dt;
      s.w = std::max(s.w * leak, -p_.passivity_reserve);
      if (p_.passivity && s.w > p_.passivity_threshold) {
        const double v2 = dot(s.v_hp, s.v_hp);
        const double beta = std::min(p_.max_damping, (s.w - p_.passivity_threshold) / (v2 * dt + 1e-30));
        if (beta * v2 > 0) {
          f_des -= s.v_hp * beta;
          c_.dissipated += beta * v2 * dt;
          ++c_.passivity_active;
        }
      }
    }

    // 3. Gains.
    Vec3 f_out = f_des * (gain_ * s.gain);
    // 4. Magnitude clamp.
    const double mag = norm(f_out);
    if (mag > p_.max_force) {
      f_out *= p_.max_force * (1.0 - 1e-12) / mag;  // strictly inside: round-off stays below
      ++c_.clamped;
    }
    // 5. Rate limit.
    const Vec3 step = f_out - s.out;
    const double sn = norm(step);
    if (sn > step_max) {
      f_out = s.out + step * (step_max / sn);
      ++c_.rate_limited;
    }
    // 6. Final guard: whatever happened above, never NaN/Inf, never above the limit.
    if (!finite(f_out)) {
      f_out = {};
      ++c_.final_guard;
    } else if (norm(f_out) > p_.max_force) {
      f_out *= p_.max_force / norm(f_out) * (1.0 - 1e-12);
      ++c_.final_guard;
    }

    // High-passed applied force for the observer's next tick.
    s.f_hp = (s.f_hp + f_out - s.f_prev_in) * hp_a;
    s.f_prev_in = f_out;
    s.out = f_out;
    out.force[f] = f_out;
    c_.max_output = std::max(c_.max_output, norm(f_out));
  }
}

}  // namespace palpation::device
