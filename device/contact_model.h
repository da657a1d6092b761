// The local contact model the simulation publishes for the 1 kHz haptic loop (multirate
// haptics, Courtecuisse et al. 2015; style.md "Haptic loops"): per finger, the force the
// FEM computed, its derivative with respect to the finger position, and the position it
// was computed at. The haptic loop re-evaluates it at the current position every tick:
//
//   F(x) = F0 + K (x - x0),   K = dF/dx (clamped to the device's renderable stiffness),
//
// and keeps it unilateral: the tissue pushes, never pulls (F . n >= 0, else zero).
// All in the device frame and device units (app/ converts from the simulation's world
// frame and scales the simulated force into the device's range, app/live/force_mapping.h).
//
// Rendering it directly at the device position ("direct") hands the device the
// simulation's penalty stiffness (tens of kN/m per contact point), sampled every few ms:
// a delayed stiff spring that chatters. The default is a virtual coupling instead
// (Colgate, Stanley & Brown 1995; the proxy / god-object of CHAI3D): the simulated
// fingertip (the proxy) is tied to the device's by a spring k_c no stiffer than the
// device renders at 1 kHz, the simulation steps with the proxy, and the user feels the
// coupling force. See couple().
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

/// Inverse of a 3 x 3 matrix; false when it is singular (|det| <= tiny * scale^3).
inline bool invert(const Mat3& a, Mat3& inv, double scale) {
  const double c00 = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), c01 = a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2),
               c02 = a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0);
  const double det = a(0, 0) * c00 + a(0, 1) * c01 + a(0, 2) * c02;
  if (!(std::fabs(det) > 1e-12 * scale * scale * scale)) return false;
  const double r = 1.0 / det;
  inv = Mat3{{c00 * r, (a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2)) * r, (a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1)) * r,
              c01 * r, (a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0)) * r, (a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2)) * r,
              c02 * r, (a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1)) * r, (a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)) * r}};
  return true;
}

struct Coupled {
  Vec3 force;   // on the user's fingertip, N
  Vec3 proxy;   // where the simulated fingertip should be, m
};

/// Virtual coupling with a quasi-static proxy. With the local model of the tissue force
/// on the proxy, F(x) = F0 + K (x - x0), the proxy sits where the coupling spring and the
/// tissue balance:
///   k_c (x_p - x_d) = F0 + K (x_p - x0)   ->   (k_c I - K) x_p = F0 - K x0 + k_c x_d
/// and the user feels F = k_c (x_p - x_d). With K = -S (S >= 0 for a contact), the
/// stiffness the user feels is k_c (k_c + S)^-1 S: the series combination, never above
/// k_c however stiff the penalty inside the simulation. Unilateral: when the balance
/// would pull (F . n <= 0) the finger is free, F = 0 and the proxy follows the device.
/// Iterated across simulation steps (the simulation steps with x_p and returns F0, K at
/// it) the proxy converges when the true contact stiffness is below 2 S + k_c.
inline Coupled couple(const FingerContactModel& m, const Vec3& xd, double kc) {
  if (!m.valid || m.contacts <= 0) return {{}, xd};
  Mat3 ks = (m.stiffness + m.stiffness.transposed()) * 0.5;  // symmetric part
  Mat3 a = Mat3::identity() * kc + ks * -1.0;
  Mat3 inv;
  if (!invert(a, inv, kc + frobenius(ks))) return {evaluate(m, xd, kc), xd};
  const Vec3 xp = inv * (m.force - ks * m.position + xd * kc);
  const Vec3 f = (xp - xd) * kc;
  if (dot(m.normal, m.normal) > 0 && !(dot(f, m.normal) > 0)) {
    if (finite(f)) return {{}, xd};
  }
  return {f, xp};
}

}  // namespace palpation::device
