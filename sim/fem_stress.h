// Stress for display: von Mises stress per element from a deformed state, and its
// average at the nodes (for a colour map on the surface). Header-only, no state.
//
// Per element: deformation gradient F = sum_a x_a g_a^T (g_a: rest shape-function
// gradients, Model::grad), Green-Lagrange strain E = (F^T F - I) / 2 (invariant under
// rotation, so no polar decomposition is needed), stress S = lambda tr(E) I + 2 mu E, and
// von Mises sigma_v = sqrt(3/2 s:s) with s = S - tr(S) I / 3. For the small strains of
// the corotational model (design.md section 4) S equals its rotated-back stress
// R^T sigma R to first order in the strain; sigma_v is rotation invariant, so the two
// agree to that order (tests/tst_fem_stress.cpp: uniaxial strain, rigid rotation).
// Cost (measured, nodal_von_mises, this 2-core machine under load): 0.36 ms for the coarse
// breast (1,014 nodes, 4,286 elements), 3.7 ms for the paper mesh (43,406 elements).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "model.h"

namespace palpation::sim {

/// Von Mises stress (Pa) of one element with nodes at x0..x3 (m).
inline double element_von_mises(const Model& m, const Materials& mat, int e, const Eigen::Vector3d* x) {
  const auto& g = m.grad[e];
  Eigen::Matrix3d F = x[0] * g[0].transpose() + x[1] * g[1].transpose() + x[2] * g[2].transpose() +
                      x[3] * g[3].transpose();
  const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
  const double tr = E.trace();
  Eigen::Matrix3d S = 2.0 * mat.mu[e] * E;
  S.diagonal().array() += mat.lambda[e] * tr;
  Eigen::Matrix3d s = S;
  s.diagonal().array() -= S.trace() / 3.0;
  return std::sqrt(1.5 * s.cwiseAbs2().sum());
}

/// Von Mises stress of every element (ntet, Pa) for node positions `xyz` (nnode x 3, m;
/// float or double) and the elements' current materials.
template <class Real>
void element_von_mises(const Model& m, const Materials& mat, const Real* xyz, std::vector<double>& out) {
  out.resize(m.tets.size());
  Eigen::Vector3d x[4];
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    for (int a = 0; a < 4; ++a) x[a] = Eigen::Vector3d(double(xyz[3 * t[a]]), double(xyz[3 * t[a] + 1]), double(xyz[3 * t[a] + 2]));
    out[e] = element_von_mises(m, mat, e, x);
  }
}

/// Reusable buffers of nodal_von_mises (no allocation after the first call).
struct StressScratch {
  std::vector<double> element, acc, weight;
};

/// Von Mises stress at the nodes (nnode, Pa): the volume-weighted mean of the incident
/// elements' values. `xyz`: node positions (nnode x 3, m; float or double).
template <class Real, class Out>
void nodal_von_mises(const Model& m, const Materials& mat, const Real* xyz, std::vector<Out>& out, StressScratch& s) {
  element_von_mises(m, mat, xyz, s.element);
  const std::size_t n = m.rest.size();
  s.acc.assign(n, 0.0);
  s.weight.assign(n, 0.0);
  for (int e = 0; e < m.num_tets(); ++e) {
    const double w = m.volume[e];
    for (int a = 0; a < 4; ++a) {
      s.acc[m.tets[e][a]] += w * s.element[e];
      s.weight[m.tets[e][a]] += w;
    }
  }
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = s.weight[i] > 0 ? Out(s.acc[i] / s.weight[i]) : Out(0);
}

}  // namespace palpation::sim
