// Tetrahedral meshes: the geometry a model is built from.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace palpation::sim {

/// A linear tetrahedral mesh in metres. Tetrahedra are positively oriented
/// (det[x1-x0, x2-x0, x3-x0] > 0) after `orient()`.
struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;         // (nnode)
  std::vector<std::array<int, 4>> tets;       // (ntet) node indices
  std::vector<int> region;                    // (ntet) geometric region tag, 0 = bulk tissue

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }

  /// Flips negatively oriented tetrahedra; returns how many were flipped.
  int orient();
  /// Checks indices, finiteness and non-degenerate volumes. Empty string when valid,
  /// else a one-line reason.
  std::string validate() const;
  /// Boundary triangles (faces that belong to exactly one tetrahedron), outward facing.
  std::vector<std::array<int, 3>> boundary_faces() const;
  /// Renumbers the nodes by reverse Cuthill-McKee over the tetrahedra's edges and sorts
  /// the tetrahedra by their lowest node (stable; each keeps its own node order, so its
  /// orientation). The same geometry in an order whose neighbours are near in memory:
  /// a node's matrix row, its elements and their nodes then share cache lines, where the
  /// mesher's order scatters them over the whole mesh. Deterministic for a given mesh.
  /// Returns, for each tetrahedron in the new order, its index before.
  std::vector<int> order_for_locality();
  /// Axis-aligned bounds.
  void bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const;
  /// 64-bit FNV-1a hash of the content (used by the cache and by recordings).
  std::uint64_t hash() const;
};

/// Distance along the ray o + t d to triangle (a, b, c) (Moller-Trumbore; t in units of
/// |d|), or a negative number when the ray misses it. Hits on an edge (within 1e-9 of the
/// barycentric range) count, so a ray through a shared edge finds one of its triangles.
double ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Signed volume of a tetrahedron (positive when positively oriented).
double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d);

/// Structured box mesh: base on z = 0, centred on x = y = 0, size (sx, sy, sz), divided
/// into nx x ny x nz cubes of 6 tetrahedra each (Kuhn subdivision: conforming, no Gmsh
/// needed, deterministic; used for analytic checks and on machines without Gmsh).
TetMesh make_box_mesh(const Eigen::Vector3d& size, int nx, int ny, int nz);

/// Box mesh whose cells are about `edge` metres on a side. With grading g > 1 the node
/// coordinates are mapped x = (s/2) sign(u)|u|^g (u uniform in [-1, 1]) and
/// z = sz (1 - (1 - w)^g) (w uniform in [0, 1]), concentrating cells toward the top centre
/// where a finger presses (same cell count, smaller cells under the contact).
TetMesh make_box_mesh(const Eigen::Vector3d& size, double edge, double grading = 1.0);
/// Applies that grading to an existing structured box mesh in place.
void grade_box_mesh(TetMesh& mesh, const Eigen::Vector3d& size, double grading);

}  // namespace palpation::sim
