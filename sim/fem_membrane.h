// Corotational membrane triangles: the skin as a sheet on the surface triangles, with its
// in-plane stiffness E t and no thickness to mesh (a tetrahedral band of the skin's 1.5 mm
// would need elements a tenth of the paper mesh's edge; docs/simulation.md, "The skin").
//
// A linear (constant-strain) triangle in plane stress, in a frame that turns with it:
//   F = sum_a x_a g_a^T, g_a the rest in-plane shape gradients (g_a . n0 = 0);
//   R = R1 R2: R1 the least rotation taking the rest normal n0 to the current one n, R2 the
//       rotation about n0 by the polar angle of R1^T F in the rest plane (closed form, no
//       iteration and no state: both backends get the same R from the same positions);
//   eps = sym(R^T F) - P0, P0 = I - n0 n0^T (R^T F has no normal row or column);
//   sigma = 2 mu eps + lambda' tr(eps) P0, lambda' = E nu / (1 - nu^2) (plane stress);
//   f_a = -A t R sigma g_a;
//   K_ab = A t (lambda' r_a r_b^T + mu r_b r_a^T + mu (g_a . g_b) P), r = R g, P = I - n n^T,
// the tetrahedron's blocks (fem_corotational.h) with the in-plane identity P in place of I:
// a membrane resists stretch in its plane and not a transverse move of a node (the shear
// that a tetrahedron would resist there is a rotation of the sheet); plus, under tension,
//   A t (g_a . S+ g_b) I, S+ the tensile part of sigma (the geometric stiffness),
// with which a taut sheet resists a node pushed across it. The backends linearise about
// the present positions, f(x + dx) = f - K dx (b0 = f + K u on the CPU), for any K.
//
// Plain arrays and PALPATION_HD so that the CPU backend and the CUDA kernel run this one
// code (row-major 3x3 matrices, vectors of 3).
#pragma once

#include <cmath>

#ifdef __CUDACC__
#define PALPATION_HD __host__ __device__
#else
#define PALPATION_HD
#endif

namespace palpation::sim::membrane {

/// Rest data of one triangle, in T: in-plane shape gradients (3 x 3), unit normal n0, unit
/// in-plane axis e1 (along the first edge), A t (m^3).
template <class T>
struct Rest {
  T g[9];
  T n0[3];
  T e1[3];
  T at;
};

/// The rest data in another precision (the model keeps double; a float backend runs float).
template <class T, class U>
Rest<T> rest_cast(const Rest<U>& r) {
  Rest<T> d{};
  for (int k = 0; k < 9; ++k) d.g[k] = T(r.g[k]);
  for (int k = 0; k < 3; ++k) {
    d.n0[k] = T(r.n0[k]);
    d.e1[k] = T(r.e1[k]);
  }
  d.at = T(r.at);
  return d;
}

template <class T>
PALPATION_HD inline void cross(const T a[3], const T b[3], T c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

template <class T>
PALPATION_HD inline T dot(const T a[3], const T b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Rotation about the unit axis k by the angle with cosine c and sine s (Rodrigues).
template <class T>
PALPATION_HD inline void axis_rotation(const T k[3], T c, T s, T R[9]) {
  const T t = T(1) - c;
  R[0] = c + t * k[0] * k[0];
  R[1] = t * k[0] * k[1] - s * k[2];
  R[2] = t * k[0] * k[2] + s * k[1];
  R[3] = t * k[1] * k[0] + s * k[2];
  R[4] = c + t * k[1] * k[1];
  R[5] = t * k[1] * k[2] - s * k[0];
  R[6] = t * k[2] * k[0] - s * k[1];
  R[7] = t * k[2] * k[1] + s * k[0];
  R[8] = c + t * k[2] * k[2];
}

/// The triangle's rotation R (row-major) and current unit normal n from its node positions
/// x (3 x 3) and F = sum_a x_a g_a^T (row-major). A degenerate triangle (zero area) keeps
/// the rest normal.
template <class T>
PALPATION_HD inline void rotation(const Rest<T>& r, const T x[9], const T F[9], T R[9], T n[3]) {
  T u[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = x[3 + k] - x[k];
    w[k] = x[6 + k] - x[k];
  }
  cross(u, w, n);
  const T len = std::sqrt(dot(n, n));
  if (len > T(0)) {
    for (int k = 0; k < 3; ++k) n[k] /= len;
  } else {
    for (int k = 0; k < 3; ++k) n[k] = r.n0[k];
  }
  // R1: n0 -> n about n0 x n; a triangle turned over (n = -n0) turns about e1 by pi.
  T R1[9];
  T axis[3];
  cross(r.n0, n, axis);
  const T s1 = std::sqrt(dot(axis, axis)), c1 = dot(r.n0, n);
  if (s1 > T(1e-12)) {
    for (int k = 0; k < 3; ++k) axis[k] /= s1;
    axis_rotation(axis, c1, s1, R1);
  } else if (c1 > T(0)) {
    axis_rotation(r.e1, T(1), T(0), R1);
  } else {
    axis_rotation(r.e1, T(-1), T(0), R1);
  }
  // The in-plane part of R1^T F in (e1, e2 = n0 x e1) and its polar angle.
  T e2[3];
  cross(r.n0, r.e1, e2);
  T Fe1[3], Fe2[3];  // R1^T F e1, R1^T F e2
  for (int i = 0; i < 3; ++i) {
    Fe1[i] = Fe2[i] = T(0);
    for (int k = 0; k < 3; ++k) {
      Fe1[i] += R1[3 * k + i] * dot(F + 3 * k, r.e1);
      Fe2[i] += R1[3 * k + i] * dot(F + 3 * k, e2);
    }
  }
  const T m00 = dot(r.e1, Fe1), m01 = dot(r.e1, Fe2), m10 = dot(e2, Fe1), m11 = dot(e2, Fe2);
  const T ys = m10 - m01, xs = m00 + m11, h = std::sqrt(xs * xs + ys * ys);
  T R2[9];
  if (h > T(0))
    axis_rotation(r.n0, xs / h, ys / h, R2);
  else
    axis_rotation(r.n0, T(1), T(0), R2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = R1[3 * i] * R2[j] + R1[3 * i + 1] * R2[3 + j] + R1[3 * i + 2] * R2[6 + j];
}

/// One triangle from its node positions x (3 x 3): forces f (3 x 3, N, on its nodes) and
/// when K is given its nine stiffness blocks K_ab (row-major 3x3 each, block 3 a + b).
/// lambda_p = E nu / (1 - nu^2), mu = E / (2 (1 + nu)).
template <class T>
PALPATION_HD inline void element(const Rest<T>& r, const T x[9], T lambda_p, T mu, T f[9], T* K) {
  T F[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F[3 * i + j] = x[i] * r.g[j] + x[3 + i] * r.g[3 + j] + x[6 + i] * r.g[6 + j];
  T R[9], n[3];
  rotation(r, x, F, R, n);
  // eps = sym(R^T F) - P0, sigma = 2 mu eps + lambda' tr(eps) P0.
  T H[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[3 * i + j] = R[i] * F[j] + R[3 + i] * F[3 + j] + R[6 + i] * F[6 + j];
  T S[9];
  T tr = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const T p0 = (i == j ? T(1) : T(0)) - r.n0[i] * r.n0[j];
      S[3 * i + j] = T(0.5) * (H[3 * i + j] + H[3 * j + i]) - p0;
      if (i == j) tr += S[3 * i + j];
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const T p0 = (i == j ? T(1) : T(0)) - r.n0[i] * r.n0[j];
      S[3 * i + j] = T(2) * mu * S[3 * i + j] + lambda_p * tr * p0;
    }
  T rg[9];  // r_a = R g_a
  for (int a = 0; a < 3; ++a) {
    T sg[3];
    for (int i = 0; i < 3; ++i) sg[i] = S[3 * i] * r.g[3 * a] + S[3 * i + 1] * r.g[3 * a + 1] + S[3 * i + 2] * r.g[3 * a + 2];
    for (int i = 0; i < 3; ++i) {
      f[3 * a + i] = -r.at * (R[3 * i] * sg[0] + R[3 * i + 1] * sg[1] + R[3 * i + 2] * sg[2]);
      rg[3 * a + i] = R[3 * i] * r.g[3 * a] + R[3 * i + 1] * r.g[3 * a + 1] + R[3 * i + 2] * r.g[3 * a + 2];
    }
  }
  if (!K) return;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const T gab = dot(r.g + 3 * a, r.g + 3 * b);
      T* Kab = K + 9 * (3 * a + b);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const T pij = (i == j ? T(1) : T(0)) - n[i] * n[j];
          Kab[3 * i + j] = r.at * (lambda_p * rg[3 * a + i] * rg[3 * b + j] + mu * rg[3 * b + i] * rg[3 * a + j] + mu * gab * pij);
        }
    }
  // The tension's stiffness (the geometric term): K_ab += A t (g_a . S+ g_b) I, S+ the
  // tensile part of S. A taut sheet resists a node pushed across it to first order (the
  // term above does not: it is the stiffness of the stretch alone), which a long step into
  // a sheet wrapped around a fingertip needs. Compression's part is left out: it would make
  // K indefinite (the sheet wrinkles instead) and the conjugate gradients need K >= 0.
  // S+ from the 2 x 2 in-plane stress in (e1, e2): eigenvalues l1 >= l2, and where they
  // differ in sign l1 times the spectral projector (S - l2 I) / (l1 - l2).
  T e2[3];
  cross(r.n0, r.e1, e2);
  T s11 = 0, s12 = 0, s22 = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      s11 += r.e1[i] * S[3 * i + j] * r.e1[j];
      s12 += r.e1[i] * S[3 * i + j] * e2[j];
      s22 += e2[i] * S[3 * i + j] * e2[j];
    }
  const T mean = T(0.5) * (s11 + s22), half = T(0.5) * (s11 - s22);
  const T dev = std::sqrt(half * half + s12 * s12), l1 = mean + dev, l2 = mean - dev;
  if (l1 <= T(0)) return;
  if (l2 < T(0)) {
    const T c = l1 / (l1 - l2);
    s11 = c * (s11 - l2);
    s12 = c * s12;
    s22 = c * (s22 - l2);
  }
  T gp[6];  // g_a in (e1, e2)
  for (int a = 0; a < 3; ++a) {
    gp[2 * a] = dot(r.g + 3 * a, r.e1);
    gp[2 * a + 1] = dot(r.g + 3 * a, e2);
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const T q = r.at * (gp[2 * a] * (s11 * gp[2 * b] + s12 * gp[2 * b + 1]) + gp[2 * a + 1] * (s12 * gp[2 * b] + s22 * gp[2 * b + 1]));
      T* Kab = K + 9 * (3 * a + b);
      for (int i = 0; i < 3; ++i) Kab[4 * i] += q;
    }
}

}  // namespace palpation::sim::membrane
