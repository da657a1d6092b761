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
