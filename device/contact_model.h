// The local contact model the simulation publishes for the 1 kHz haptic loop (multirate
// haptics, Courtecuisse et al. 2015; style.md "Haptic loops"): per finger, the force the
// FEM computed, its derivative with respect to the finger position, and the position it
// was computed at. The haptic loop re-evaluates it at the current position every tick:
//
//   F(x) = F0 + K (x - x0),   K = dF/dx (clamped to the device's renderable stiffness),
//
// and keeps it unilateral: the tissue pushes, never pulls (F . n >= 0, else zero).
// All in the device frame (app/ converts from the simulation's world frame).
#pragma once

#include <array>
#include <cstdint>

#include "haptic_device.h"
#include "vec3.h"

namespace palpation::device {

struct FingerContactModel {
  bool valid = false;          // false: no model for this finger (no force)
  int contacts = 0;            // vertices in contact when computed (0: no contact)
  Vec3 force;                  // F0, N, on the finger
  Mat3 stiffness;              // K = dF/dx, N/m (negative semi-definite for a contact)
  Vec3 position;               // x0, finger position the model was computed at, m
  Vec3 contact_point;          // mean contact vertex, m
  Vec3 normal;                 // unit, from the surface toward the finger
};

struct ContactFrame {
  std::array<FingerContactModel, kMaxFingers> fingers{};
  std::uint64_t sequence = 0;  // +1 per simulation step published (0: none yet)
  std::int64_t published_ns = 0;  // host monotonic clock when published
  double sim_time = 0;         // simulation time of the step, s
};

/// Scales K so that its Frobenius norm (an upper bound of its spectral norm) stays at or
/// below `max_stiffness`: the stiffest the device renders stably at 1 kHz.
inline Mat3 clamp_stiffness(const Mat3& k, double max_stiffness) {
  const double n = frobenius(k);
  if (!(n > max_stiffness)) return k;
  return k * (max_stiffness / n);
}

/// F(x) for one finger; zero without a valid contact or when the extrapolation turns
/// adhesive. Non-finite inputs give non-finite outputs (the safety filter catches them).
inline Vec3 evaluate(const FingerContactModel& m, const Vec3& x, double max_stiffness) {
  if (!m.valid || m.contacts <= 0) return {};
  const Vec3 f = m.force + clamp_stiffness(m.stiffness, max_stiffness) * (x - m.position);
  const double fn = dot(f, m.normal);
  if (dot(m.normal, m.normal) > 0 && fn <= 0) return {};
  return f;
}

}  // namespace palpation::device
