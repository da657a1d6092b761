// Corotational linear tetrahedra: rotation extraction, element force and stiffness.
//
// References: Mueller & Gross 2004 (interactive virtual materials), Nesme et al. 2005
// (corotational FEM), Mueller, Bender, Chentanez & Macklin 2016 ("A robust method to
// extract the rotational part of deformations", MIG '16) for the rotation, which always
// returns a proper rotation, also for inverted elements (det F < 0), unlike a polar
// decomposition through F^T F. Header-only and templated so that tests and both
// precisions share one implementation; the CUDA kernels mirror it line for line.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lanes4.h"

namespace palpation::sim::fem {

template <class T>
using Mat3 = Eigen::Matrix<T, 3, 3>;
template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

/// Number of fixed-point iterations of the rotation extraction. Warm-started from the
/// previous step's rotation, 1-2 suffice at haptic rates; a fixed count keeps the CPU and
/// GPU backends bit-comparable in their control flow.
inline constexpr int kRotationIterations = 4;

/// Deformation gradient F = sum_a x_a g_a^T of a linear tetrahedron.
template <class T>
Mat3<T> deformation_gradient(const Vec3<T> x[4], const Vec3<T> g[4]) {
  Mat3<T> F = x[0] * g[0].transpose();
  for (int a = 1; a < 4; ++a) F.noalias() += x[a] * g[a].transpose();
  return F;
}

/// Stopping threshold of the rotation iteration (radians of the last update).
template <class T>
constexpr T rotation_tolerance() {
  return sizeof(T) == sizeof(double) ? T(1e-9) : T(1e-6);
}

/// Rotational part of A (Mueller et al. 2016), refining the unit quaternion q in place.
/// Always returns a rotation (det = +1), continuous under inversion. The quaternion
/// update exp(omega/2) uses its Taylor series for small angles (no trigonometry in the
/// common warm-started case; series error below 1e-12 for |omega| < 1e-2).
template <class T>
void extract_rotation(const Mat3<T>& A, Eigen::Quaternion<T>& q, int iterations = kRotationIterations) {
  for (int it = 0; it < iterations; ++it) {
    const Mat3<T> R = q.toRotationMatrix();
    const Vec3<T> omega_num = R.col(0).cross(A.col(0)) + R.col(1).cross(A.col(1)) + R.col(2).cross(A.col(2));
    const T denom = std::abs(R.col(0).dot(A.col(0)) + R.col(1).dot(A.col(1)) + R.col(2).dot(A.col(2))) + T(1e-9);
    const Vec3<T> omega = omega_num / denom;
    const T w2 = omega.squaredNorm();
    const T w = std::sqrt(w2);
    if (w < rotation_tolerance<T>()) break;
    T c, s;  // cos(w/2), sin(w/2)/w
    if (w < T(1e-2)) {
      c = T(1) - w2 / T(8) + w2 * w2 / T(384);
      s = T(0.5) - w2 / T(48);
    } else {
      c = std::cos(T(0.5) * w);
      s = std::sin(T(0.5) * w) / w;
    }
    const Eigen::Quaternion<T> dq(c, s * omega.x(), s * omega.y(), s * omega.z());
    q = dq * q;
    q.normalize();
  }
}

/// extract_rotation for four matrices at once, one per lane (the same arithmetic per
/// lane; a lane stops updating where the scalar loop would break). A[3 j + i] holds entry
/// (i, j) of the four matrices, q[0..3] the quaternions' w, x, y, z, refined in place.
/// The scalar loop is a chain of dependent divisions and square roots (latency-bound:
/// most warm-started extractions run all four iterations); four independent chains side
/// by side take about the time of one.
template <class T>
void extract_rotation4(const lanes::V4<T> A[9], lanes::V4<T> q[4], int iterations = kRotationIterations) {
  using V4 = lanes::V4<T>;
  using Mask = typename lanes::Lanes4<T>::Mask;
  auto sqrt4 = [](V4 v) {
    for (int k = 0; k < 4; ++k) v[k] = std::sqrt(v[k]);
    return v;
  };
  Mask active = {-1, -1, -1, -1};
  for (int it = 0; it < iterations; ++it) {
    const V4 w = q[0], x = q[1], y = q[2], z = q[3];
    // q.toRotationMatrix() (Eigen's formula), by columns.
    const V4 tx = T(2) * x, ty = T(2) * y, tz = T(2) * z;
    const V4 twx = tx * w, twy = ty * w, twz = tz * w, txx = tx * x, txy = ty * x, txz = tz * x, tyy = ty * y,
             tyz = tz * y, tzz = tz * z;
    const V4 R[9] = {T(1) - (tyy + tzz), txy + twz, txz - twy,   // column 0
                     txy - twz, T(1) - (txx + tzz), tyz + twx,   // column 1
                     txz + twy, tyz - twx, T(1) - (txx + tyy)};  // column 2
    // omega = sum_c R.col(c) x A.col(c) / (|sum_c R.col(c) . A.col(c)| + 1e-9)
    V4 ox = {}, oy = {}, oz = {}, dot = {};
    for (int c = 0; c < 3; ++c) {
      const V4 *r = R + 3 * c, *a = A + 3 * c;
      ox += r[1] * a[2] - r[2] * a[1];
      oy += r[2] * a[0] - r[0] * a[2];
      oz += r[0] * a[1] - r[1] * a[0];
      dot += r[0] * a[0] + r[1] * a[1] + r[2] * a[2];
    }
    const V4 denom = (dot < T(0) ? -dot : dot) + T(1e-9);
    ox /= denom;
    oy /= denom;
    oz /= denom;
    const V4 w2 = ox * ox + oy * oy + oz * oz;
    const V4 wn = sqrt4(w2);
    active &= ~(wn < rotation_tolerance<T>());  // the scalar loop's break (NaN goes on)
    if (!(active[0] | active[1] | active[2] | active[3])) break;
    // cos(w/2), sin(w/2)/w: the series below 1e-2, the functions lane by lane above.
    V4 c = T(1) - w2 / T(8) + w2 * w2 / T(384);
    V4 s = T(0.5) - w2 / T(48);
    for (int k = 0; k < 4; ++k)
      if (!(wn[k] < T(1e-2))) {
        c[k] = std::cos(T(0.5) * wn[k]);
        s[k] = std::sin(T(0.5) * wn[k]) / wn[k];
      }
    const V4 sx = s * ox, sy = s * oy, sz = s * oz;
    // dq * q, dq = (c, s omega), then normalised.
    V4 nw = c * w - (sx * x + sy * y + sz * z);
    V4 nx = c * x + w * sx + (sy * z - sz * y);
    V4 ny = c * y + w * sy + (sz * x - sx * z);
    V4 nz = c * z + w * sz + (sx * y - sy * x);
    const V4 norm = sqrt4(nw * nw + nx * nx + ny * ny + nz * nz);
    nw /= norm;
    nx /= norm;
    ny /= norm;
    nz /= norm;
    q[0] = active ? nw : w;
    q[1] = active ? nx : x;
    q[2] = active ? ny : y;
    q[3] = active ? nz : z;
  }
}

/// Cauchy-like stress of small strain: sigma = 2 mu eps + lambda tr(eps) I, eps = sym(H).
template <class T>
Mat3<T> linear_stress(const Mat3<T>& H, T lambda, T mu) {
  const Mat3<T> eps = T(0.5) * (H + H.transpose());
  return T(2) * mu * eps + lambda * eps.trace() * Mat3<T>::Identity();
}

/// Elastic forces on the four nodes (world frame, N):
///   f_a = -V R sigma(R^T F - I) g_a.
/// Zero for any rigid motion when R is the rotation of that motion.
template <class T>
void element_forces(const Mat3<T>& F, const Mat3<T>& R, const Vec3<T> g[4], T volume, T lambda, T mu,
                    Vec3<T> f[4]) {
  const Mat3<T> H = R.transpose() * F - Mat3<T>::Identity();
  const Mat3<T> S = linear_stress(H, lambda, mu);
  for (int a = 0; a < 4; ++a) f[a] = -volume * (R * (S * g[a]));
}

/// Stiffness block K_ab = V (lambda r_a r_b^T + mu r_b r_a^T + mu (g_a . g_b) I), r = R g.
template <class T>
Mat3<T> stiffness_block(const Vec3<T>& ra, const Vec3<T>& rb, T gab, T volume, T lambda, T mu) {
  Mat3<T> K = lambda * ra * rb.transpose() + mu * rb * ra.transpose();
  K.diagonal().array() += mu * gab;
  return volume * K;
}

/// Matrix-free product of the rotated element stiffness with nodal vectors p:
///   (K p)_a = V sigma(P) r_a,  P = sum_b p_b r_b^T.
template <class T>
void stiffness_apply(const Vec3<T> r[4], T volume, T lambda, T mu, const Vec3<T> p[4], Vec3<T> y[4]) {
  Mat3<T> P = p[0] * r[0].transpose();
  for (int b = 1; b < 4; ++b) P.noalias() += p[b] * r[b].transpose();
  const Mat3<T> S = linear_stress(P, lambda, mu);
  for (int a = 0; a < 4; ++a) y[a] = volume * (S * r[a]);
}

}  // namespace palpation::sim::fem
