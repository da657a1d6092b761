// The safety filter: the last stage before the device (design.md section 7). A haptic
// robot must never receive NaN, Inf or a force above its limit. Per tick and finger:
//
//   1. non-finite guard: a NaN/Inf desired force or finger position renders nothing;
//   2. passivity (energy) controller, see below;
//   3. gains: a global gain ramps to zero within `ramp_out` once the simulation is stale
//      (no update for `stale_after`) or the device link is down, and ramps in over
//      `ramp_in` at session start and after recovery; a per-finger gain is zero while
//      the magnet joint is released and ramps in after re-attachment;
//   4. magnitude clamp to max_force;
//   5. rate limit: |F_k - F_{k-1}| <= max_rate * dt (keeps |F| <= max_force: the ball is
//      convex);
//   6. a final check (finite, <= max_force) that holds whatever the stages above did.
//
// Passivity (time-domain passivity observer/controller, Hannaford & Ryu 2002, in the
// spirit of the energy monitor + adjustable damping of Kim & Lee 2015 for stiff
// inclusions, reference/facts.md): per finger the observer integrates the work the
// rendered force does on the user's fingertip in the vibration band (force and velocity
// both high-passed at `passivity_highpass_hz`, so slow pressing and releasing, which move
// stored elastic energy in and out, are left alone):
//   W_k = W_{k-1} + F_hp,{k-1} . v_hp,k dt      (W > 0: the loop generated energy)
// W is bounded below by -passivity_reserve (a small credit of dissipated energy) and
// leaks toward zero. While W exceeds a small dead band W0 (the sampled-data generation of
// a zero-order-held spring is of that order, and acting on it would make the controller
// impulsive) it adds damping -beta v_hp with
//   beta = min(max_damping, (W - W0) / (|v_hp|^2 dt))
// which dissipates the excess (the observer sees the damping next tick).
#pragma once

#include <array>
#include <cstdint>

#include "haptic_device.h"
#include "vec3.h"

namespace palpation::device {

struct SafetyParams {
  double max_force = 4.0;          // N per finger (device capability)
  double max_rate = 1000.0;        // N/s per finger
  double stale_after = 0.1;        // s without a simulation update before ramping out
  double ramp_out = 0.05;          // s from full force to zero
  double ramp_in = 0.5;            // s from zero to full force
  bool passivity = true;
  double passivity_highpass_hz = 10.0;
  double max_damping = 10.0;       // N s/m the controller may add (device capability)
  double passivity_reserve = 2e-4; // J
  double passivity_threshold = 1e-5;  // J generated before the controller acts (dead band)
  double passivity_leak = 0.5;     // s, time constant of W toward zero
};

struct SafetyCounters {
  std::uint64_t ticks = 0;
  std::uint64_t clamped = 0;           // finger-ticks where the magnitude clamp acted
  std::uint64_t rate_limited = 0;      // finger-ticks where the rate limit acted
  std::uint64_t nonfinite = 0;         // finger-ticks with NaN/Inf input (rendered as 0)
  std::uint64_t passivity_active = 0;  // finger-ticks with added damping
  std::uint64_t stale_events = 0;      // simulation fresh -> stale transitions
  std::uint64_t link_events = 0;       // device connected -> lost transitions
  std::uint64_t releases = 0;          // attached -> released transitions
  std::uint64_t reattaches = 0;        // released -> attached transitions
  std::uint64_t final_guard = 0;       // stage 6 had to act (should stay 0)
  double max_desired = 0;              // N, largest finite desired force
  double max_output = 0;               // N, largest force sent
  double dissipated = 0;               // J removed by the passivity controller
};

class SafetyFilter {
 public:
  explicit SafetyFilter(const SafetyParams& p = {}) : p_(p) { reset(); }
  void reset();
  const SafetyParams& params() const { return p_; }
  void set_params(const SafetyParams& p) { p_ = p; }

  /// One tick. `sim_age_s`: seconds since the simulation's newest update (infinity when
  /// none yet). `desired`: forces from the contact models, device frame, N.
  void apply(std::int64_t now_ns, const DeviceState& state, double sim_age_s,
             const std::array<Vec3, kMaxFingers>& desired, ForceCommand& out);

  double gain() const { return gain_; }
  double finger_gain(int f) const { return finger_[f].gain; }
  double energy(int f) const { return finger_[f].w; }
  const SafetyCounters& counters() const { return c_; }

 private:
  struct Finger {
    bool attached = false, have_prev = false, seen = false;
    double gain = 1;          // per-finger ramp: restarts from 0 after a re-attachment
    Vec3 out;                 // last force sent
    Vec3 x_prev, v_prev, v_hp, f_prev_in, f_hp;
    double w = 0;             // observed generated energy, J
  };
  SafetyParams p_;
  SafetyCounters c_;
  std::array<Finger, kMaxFingers> finger_{};
  double gain_ = 0;
  bool stale_ = true, linked_ = false, started_ = false;
  std::int64_t last_ns_ = 0;
};

}  // namespace palpation::device
