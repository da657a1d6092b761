// Penalty contact between rigid fingertip spheres and the surface vertices (paper 3.3).
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "params.h"

namespace palpation::sim::contact {

/// One vertex in contact with one finger during a step.
struct VertexContact {
  int node;            // node index
  int finger;          // finger index
  Eigen::Vector3d n;   // unit, from the sphere centre to the vertex
  double depth;        // penetration d = r - |x - c| > 0, m
};

/// Penalty force magnitude on a vertex, F = k_s d + k_e d_dot, never adhesive (>= 0).
inline double penalty(double ks, double ke, double depth, double depth_rate) {
  const double f = ks * depth + ke * depth_rate;
  return f > 0 ? f : 0.0;
}

/// Axis-aligned box of the current surface, for skipping fingers out of reach.
struct Bounds {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  bool touches(const Eigen::Vector3d& c, double r) const {
    return (c.array() + r >= lo.array()).all() && (c.array() - r <= hi.array()).all();
  }
};

/// Finds surface vertices inside the finger spheres. `x` is (nnode x 3) positions in any
/// scalar type. Fingers whose sphere misses `bounds` cost nothing.
template <class T>
void detect(std::span<const FingerInput> fingers, const std::vector<int>& surface_nodes, const T* x,
            const Bounds& bounds, std::vector<VertexContact>& out) {
  out.clear();
  for (int f = 0; f < static_cast<int>(fingers.size()); ++f) {
    const FingerInput& fi = fingers[f];
    if (!fi.active || !(fi.radius > 0) || !bounds.touches(fi.position, fi.radius)) continue;
    const double r2 = fi.radius * fi.radius;
    for (int node : surface_nodes) {
      const Eigen::Vector3d p(double(x[3 * node]), double(x[3 * node + 1]), double(x[3 * node + 2]));
      const Eigen::Vector3d d = p - fi.position;
      const double dist2 = d.squaredNorm();
      if (dist2 >= r2) continue;
      const double dist = std::sqrt(dist2);
      // A vertex exactly at the centre has no direction: push it straight up (+z).
      const Eigen::Vector3d n = dist > 1e-12 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d::UnitZ();
      out.push_back({node, f, n, fi.radius - dist});
    }
  }
}

}  // namespace palpation::sim::contact
