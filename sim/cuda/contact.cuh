// Contact stage of the CUDA backends (contact_sphere.h + backend_cpu.cpp add_contacts /
// finger_outputs): the finger spheres against the surface triangles.
//
// The detection itself (detect_nodes) is device code shared by three kernels, so it lives
// here, header-only: k_detect (contact.cu: the stand-alone detection at rest and the
// baseline's end-of-step outputs), k_element (element.cu: the start-of-step detection in
// extra blocks) and k_pcg (pcg.cu: the finger outputs at the end state).
#pragma once

#include <cmath>

#include "cuda/common.cuh"

namespace palpation::sim::cuda {

template <class T>
struct DetectArgs {
  int ntri;
  const int* tri;        // (ntri x 3) surface triangles (outward), node indices
  const int* node_surf;  // (nnode) surface-node index of each node or -1
  const int* dof;        // (nnode) free index or -1
  int nsurf;             // surface nodes (rows of cA, cb)
  const T* x;            // (nnode x 3)
  const T* v;            // (nnode x 3)
  double* cA;            // (nsurf x 6) contact matrix sum_k w_k (h^2 ks + h ke) n n^T; zero at step entry
  double* cb;            // (nsurf x 3) contact rhs; zero at step entry
  DevScratch* scr;
  DevResult* res;        // mapped host memory
};

/// Closest point to p on triangle (a, b, c) and its barycentric weights: Ericson, Real-Time
/// Collision Detection 5.1.5, as contact::closest_on_triangle.
inline __device__ void closest_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                           double q[3], double w[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto set = [&](double w0, double w1, double w2) {
    w[0] = w0;
    w[1] = w1;
    w[2] = w2;
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    set(1, 0, 0);
    for (int k = 0; k < 3; ++k) q[k] = a[k];
    return;
  }
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    set(0, 1, 0);
    for (int k = 0; k < 3; ++k) q[k] = b[k];
    return;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    set(1 - v, v, 0);
    for (int k = 0; k < 3; ++k) q[k] = a[k] + v * ab[k];
    return;
  }
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    set(0, 0, 1);
    for (int k = 0; k < 3; ++k) q[k] = c[k];
    return;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    set(1 - t, 0, t);
    for (int k = 0; k < 3; ++k) q[k] = a[k] + t * ac[k];
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    set(0, 1 - t, t);
    for (int k = 0; k < 3; ++k) q[k] = b[k] + t * (c[k] - b[k]);
    return;
  }
  const double den = 1.0 / (va + vb + vc);
  const double v = vb * den, u = vc * den;
  set(1 - v - u, v, u);
  for (int k = 0; k < 3; ++k) q[k] = a[k] + ab[k] * v + ac[k] * u;
}

/// Tests surface triangles t = first, first + stride, ... against the fingers
/// (contact::detect): each penetrated triangle is one contact at the closest point, its
/// force F = k_s d + k_e d_dot along n shared by the triangle's nodes with the
/// barycentric weights (backend_cpu.cpp add_contacts: lumped on the diagonal blocks).
/// system: add the per-node contact terms of the linear system (atomics: contacts are
/// few) and count contacts (start of step). sacc != nullptr: per-finger sums (shared).
template <class T>
__device__ void detect_nodes(const DetectArgs<T>& a, const FingersArg& F, const StepConsts& k, bool system,
                             double* sacc, int* scount, int first, int stride) {
  const double h = k.h;
  for (int t = first; t < a.ntri; t += stride) {
    const int nd[3] = {a.tri[3 * t], a.tri[3 * t + 1], a.tri[3 * t + 2]};
    double P[3][3];
    for (int m = 0; m < 3; ++m)
      for (int c = 0; c < 3; ++c) P[m][c] = double(a.x[3 * nd[m] + c]);
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = fmin(fmin(P[0][c], P[1][c]), P[2][c]);
      hi[c] = fmax(fmax(P[0][c], P[1][c]), P[2][c]);
    }
    int count = 0;
    for (int f = 0; f < F.n; ++f) {
      const FingerDev& fi = F.f[f];
      if (!fi.active || !(fi.r > 0)) continue;
      const double r = fi.r;
      bool out = false;
      for (int c = 0; c < 3; ++c) out = out || fi.c[c] + r < lo[c] || fi.c[c] - r > hi[c];
      if (out) continue;
      double q[3], w[3];
      closest_on_triangle(fi.c, P[0], P[1], P[2], q, w);
      const double d0 = q[0] - fi.c[0], d1 = q[1] - fi.c[1], d2 = q[2] - fi.c[2];
      const double dist2 = d0 * d0 + d1 * d1 + d2 * d2;
      if (dist2 >= r * r) continue;
      const double dist = sqrt(dist2);
      double n0, n1, n2;
      if (dist > 1e-12) {
        n0 = d0 / dist;
        n1 = d1 / dist;
        n2 = d2 / dist;
      } else {  // the centre on the surface itself: along the inward normal
        const double e1[3] = {P[1][0] - P[0][0], P[1][1] - P[0][1], P[1][2] - P[0][2]};
        const double e2[3] = {P[2][0] - P[0][0], P[2][1] - P[0][1], P[2][2] - P[0][2]};
        const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                     cz = e1[0] * e2[1] - e1[1] * e2[0];
        const double l = sqrt(cx * cx + cy * cy + cz * cz);
        n0 = -cx / l;
        n1 = -cy / l;
        n2 = -cz / l;
      }
      const double depth = r - dist;
      // Area weight of the penalty (contact::area_scale): triangle area / (pi r^2).
      double sc;
      {
        const double e1[3] = {P[1][0] - P[0][0], P[1][1] - P[0][1], P[1][2] - P[0][2]};
        const double e2[3] = {P[2][0] - P[0][0], P[2][1] - P[0][1], P[2][2] - P[0][2]};
        const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                     cz = e1[0] * e2[1] - e1[1] * e2[0];
        sc = 0.5 * sqrt(cx * cx + cy * cy + cz * cz) / (M_PI * r * r);
      }
      const double ks = sc * k.ks, ke = sc * k.ke;
      double vp[3] = {0, 0, 0};
      for (int m = 0; m < 3; ++m)
        for (int c = 0; c < 3; ++c) vp[c] += w[m] * double(a.v[3 * nd[m] + c]);
      const double rate = -(n0 * (vp[0] - fi.v[0]) + n1 * (vp[1] - fi.v[1]) + n2 * (vp[2] - fi.v[2]));
      const double fpen = ks * depth + ke * rate;
      const double mag = fpen > 0 ? fpen : 0.0;
      ++count;
      if (sacc) {
        double* acc = sacc + f * kFingerVals;
        atomicAdd(acc + 0, -mag * n0);
        atomicAdd(acc + 1, -mag * n1);
        atomicAdd(acc + 2, -mag * n2);
        atomicAdd(acc + 3, -ks * n0 * n0);
        atomicAdd(acc + 4, -ks * n0 * n1);
        atomicAdd(acc + 5, -ks * n0 * n2);
        atomicAdd(acc + 6, -ks * n1 * n1);
        atomicAdd(acc + 7, -ks * n1 * n2);
        atomicAdd(acc + 8, -ks * n2 * n2);
        atomicAdd(acc + 9, q[0]);
        atomicAdd(acc + 10, q[1]);
        atomicAdd(acc + 11, q[2]);
        atomicAdd(acc + 12, 1.0);
      }
      if (system && mag > 0) {
        const double cst = h * h * ks + h * ke, hks = h * ks;
        for (int m = 0; m < 3; ++m) {
          const int node = nd[m];
          if (a.dof[node] < 0 || w[m] <= 0) continue;
          const int s = a.node_surf[node];
          const double v0 = double(a.v[3 * node]), v1 = double(a.v[3 * node + 1]), v2 = double(a.v[3 * node + 2]);
          // Linearised: f(x + h v') ~ f - h ks n n^T v', damping ke n n^T on v'; weight w_m.
          const double nv = n0 * v0 + n1 * v1 + n2 * v2;
          const double hw = h * w[m];
          atomicAdd(a.cb + 3 * s, hw * (mag * n0 - hks * n0 * nv));
          atomicAdd(a.cb + 3 * s + 1, hw * (mag * n1 - hks * n1 * nv));
          atomicAdd(a.cb + 3 * s + 2, hw * (mag * n2 - hks * n2 * nv));
          const double cw = w[m] * cst;
          atomicAdd(a.cA + 6 * s, cw * n0 * n0);
          atomicAdd(a.cA + 6 * s + 1, cw * n0 * n1);
          atomicAdd(a.cA + 6 * s + 2, cw * n0 * n2);
          atomicAdd(a.cA + 6 * s + 3, cw * n1 * n1);
          atomicAdd(a.cA + 6 * s + 4, cw * n1 * n2);
          atomicAdd(a.cA + 6 * s + 5, cw * n2 * n2);
        }
      }
    }
    if (system && count) atomicAdd(scount, count);
  }
}

/// Zeroes the contact terms for the next step (after the assembly has read them).
template <class T>
__device__ void zero_contact_terms(const DetectArgs<T>& a, int first, int stride) {
  for (int j = first; j < 9 * a.nsurf; j += stride) {
    if (j < 6 * a.nsurf)
      a.cA[j] = 0.0;
    else
      a.cb[j - 6 * a.nsurf] = 0.0;
  }
}

/// Blocks of the stand-alone detection for ntri surface triangles on sms multiprocessors.
inline int detect_grid(int ntri, int sms) { return std::max(1, std::min((ntri + kBlock - 1) / kBlock, 4 * sms)); }

/// Launches k_detect (grid blocks of kBlock threads) in stream s. start: the start-of-step
/// detection (system terms, contact count, the step scratch zeroed) with the finger sums;
/// else the finger outputs of the end state, the contact terms zeroed for the next step.
template <class T>
void launch_detect(cudaStream_t s, int grid, const DetectArgs<T>& a, const FingersArg& F, const StepConsts& k,
                   bool start);

}  // namespace palpation::sim::cuda
