// Penalty contact between rigid fingertip spheres and the body surface (paper 3.3).
//
// The paper tests each surface vertex against the sphere. With vertices alone a sphere
// pressed deeper than the surface spacing slips between them and falls through the
// faces (seen on the paper-size breast at 1.2 cm depth: the force collapses from 2 N to
// 0.2 N). So the contact points are the closest points of the sphere centre on the
// surface triangles: each triangle that the sphere penetrates is one contact, with the
// paper's law F = k_s d + k_e d_dot along n, distributed to the triangle's three vertices
// by the barycentric weights of the contact point. A sphere on a vertex is then caught
// by every triangle around it, and one inside a face by that face.
//
// Each triangle's penalty is weighted by its area relative to the finger's cross-section,
// s = A / (pi r^2): k_s is the stiffness of a contact patch as large as the fingertip's
// cross-section (a pressure stiffness k_s / (pi r^2)). Per contact point, as in the paper,
// the total stiffness grows with the number of points in contact, i.e. with mesh
// refinement: measured on the GPU, the same 1.8 cm push gave 5 N on the coarse breast,
// 40 N on the paper mesh and 110 N on the fine one, with the contact chattering because
// a light node entering contact met a spring far beyond what one step can resolve
// (omega dt = 7.7 on the fine mesh, 0.95-1.1 with the area weight).
#pragma once

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "params.h"

namespace palpation::sim::contact {

/// One surface triangle in contact with one finger during a step.
struct SurfaceContact {
  int finger;                 // finger index
  std::array<int, 3> node;    // the triangle's nodes
  std::array<double, 3> w;    // barycentric weights of the contact point
  Eigen::Vector3d n;          // unit, from the sphere centre to the contact point
  Eigen::Vector3d p;          // contact point on the surface, m
  double depth;               // penetration d = r - |p - c| > 0, m
  double scale;               // area weight of the penalty, A_triangle / (pi r^2)
};

/// Area weight of one triangle's penalty: its area over the finger's cross-section.
inline double area_scale(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double r) {
  return 0.5 * (b - a).cross(c - a).norm() / (M_PI * r * r);
}

/// Penalty force magnitude, F = k_s d + k_e d_dot, never adhesive (>= 0).
inline double penalty(double ks, double ke, double depth, double depth_rate) {
  const double f = ks * depth + ke * depth_rate;
  return f > 0 ? f : 0.0;
}

/// Closest point to p on triangle (a, b, c), with its barycentric weights (Ericson,
/// Real-Time Collision Detection, 5.1.5).
inline Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c, std::array<double, 3>& w) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) { w = {1, 0, 0}; return a; }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) { w = {0, 1, 0}; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    w = {1 - v, v, 0};
    return a + v * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) { w = {0, 0, 1}; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    w = {1 - t, 0, t};
    return a + t * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w = {0, 1 - t, t};
    return b + t * (c - b);
  }
  const double den = 1.0 / (va + vb + vc);
  const double v = vb * den, u = vc * den;
  w = {1 - v - u, v, u};
  return a + ab * v + ac * u;
}

/// Axis-aligned box of the current surface, for skipping fingers out of reach.
struct Bounds {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  bool touches(const Eigen::Vector3d& c, double r) const {
    return (c.array() + r >= lo.array()).all() && (c.array() - r <= hi.array()).all();
  }
};

/// Finds the surface triangles the finger spheres penetrate. `x` is (nnode x 3)
/// positions in any scalar type. Fingers whose sphere misses `bounds` cost nothing; a
/// triangle is tested only when its bounding box overlaps the sphere's.
template <class T>
void detect(std::span<const FingerInput> fingers, const std::vector<std::array<int, 3>>& surface, const T* x,
            const Bounds& bounds, std::vector<SurfaceContact>& out) {
  out.clear();
  auto pos = [x](int i) { return Eigen::Vector3d(double(x[3 * i]), double(x[3 * i + 1]), double(x[3 * i + 2])); };
  for (int f = 0; f < static_cast<int>(fingers.size()); ++f) {
    const FingerInput& fi = fingers[f];
    if (!fi.active || !(fi.radius > 0) || !bounds.touches(fi.position, fi.radius)) continue;
    const Eigen::Vector3d c = fi.position;
    const double r = fi.radius;
    for (const auto& tri : surface) {
      const Eigen::Vector3d a = pos(tri[0]), b = pos(tri[1]), cc = pos(tri[2]);
      const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(cc), hi = a.cwiseMax(b).cwiseMax(cc);
      if ((c.array() + r < lo.array()).any() || (c.array() - r > hi.array()).any()) continue;
      std::array<double, 3> w;
      const Eigen::Vector3d p = closest_on_triangle(c, a, b, cc, w);
      const Eigen::Vector3d d = p - c;
      const double dist2 = d.squaredNorm();
      if (dist2 >= r * r) continue;
      const double dist = std::sqrt(dist2);
      // The centre on the surface itself: push along the inward normal.
      const Eigen::Vector3d n = dist > 1e-12 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d(-(b - a).cross(cc - a).normalized());
      out.push_back({f, tri, w, n, p, r - dist, area_scale(a, b, cc, r)});
    }
  }
}

}  // namespace palpation::sim::contact
