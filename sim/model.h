// The immutable tissue model (MuJoCo's mjModel idea): everything that does not change
// while a session runs. The mutable state lives in the backends.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem_membrane.h"
#include "mesh.h"
#include "params.h"

namespace palpation::sim {

/// Isotropic linear-elastic material.
/// @param young_modulus  Pa, > 0
/// @param poisson_ratio  -1 < nu < 0.5
/// @param density        kg/m^3, > 0
struct Material {
  double young_modulus = 19000.0;
  double poisson_ratio = 0.45;
  double density = 1000.0;
};

/// Lame parameters of a material: lambda = E nu / ((1+nu)(1-2nu)), mu = E / (2(1+nu)).
inline void lame(double E, double nu, double& lambda, double& mu) {
  lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  mu = E / (2.0 * (1.0 + nu));
}

/// Precomputed rest-state data of a corotational linear-tetrahedron model.
///
/// Element stiffness in the rest frame, for the linear tetrahedron with shape-function
/// gradients g_a (a = 0..3), volume V and Lame parameters lambda, mu:
///   K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I)
/// so the four gradients, V, lambda and mu are all the element needs (12 numbers + 3)
/// instead of a 12 x 12 matrix. Corotation replaces g_a by R g_a.
/// Per-element materials: what painting a tumour changes. A Model holds those it was built
/// with; a running Simulation holds the current ones and hands them to its backend.
/// The tumour rule: an element is tumour tissue when its Young's modulus is above 1.2 x
/// its tissue's (Model::tissue_young: the bulk tissue's, or its layer's; a patient's
/// inclusions are 2x to 25x stiffer than fat; the factor keeps a tissue modulus edited by
/// a few percent from reading as a tumour). The tumour
/// editor, the 3-D view and the exam scorer all read it here.
inline constexpr double kTumourFactor = 1.2;
inline bool is_tumour_modulus(double young, double tissue_young) { return young > kTumourFactor * tissue_young; }

struct Materials {
  std::vector<double> young;                // (ntet) Pa
  std::vector<double> poisson;              // (ntet)
  std::vector<double> lambda, mu;           // (ntet) Lame parameters, Pa
  int size() const { return static_cast<int>(young.size()); }
  /// Element e gets Young's modulus E (Pa) and Poisson's ratio nu (its Lame parameters follow).
  void set(int e, double E, double nu);
};

/// The skin membrane of a model (fem_membrane.h, tissue_layers.h apply_skin): one
/// triangle per skin face (the boundary off the chest wall). Empty: no skin.
struct SkinMembrane {
  SkinSpec spec;
  double poisson_ratio = 0.45;
  std::vector<std::array<int, 3>> triangles;        // (ntri) nodes
  std::vector<membrane::Rest<double>> rest;         // (ntri) rest gradients, normal, A t
  std::vector<std::array<int, 9>> block;            // (ntri x 3 x 3) block of (a, b), -1 if fixed
  bool empty() const { return triangles.empty(); }
  int size() const { return static_cast<int>(triangles.size()); }
  /// Plane-stress Lame parameters: lambda' = E nu / (1 - nu^2), mu = E / (2 (1 + nu)).
  double lambda_plane() const {
    const double nu = poisson_ratio;
    return spec.young_modulus * nu / (1.0 - nu * nu);
  }
  double mu() const { return spec.young_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

struct Model {
  // Geometry ------------------------------------------------------------------
  std::vector<Eigen::Vector3d> rest;        // (nnode) rest positions, m
  std::vector<std::array<int, 4>> tets;     // (ntet) positively oriented
  std::vector<int> region;                  // (ntet) region tag from the mesh
  /// (ntet) each element's index in the mesh the model was built from (its file's or
  /// Gmsh's order: build_model renumbers for locality, TetMesh::order_for_locality). A
  /// workstation recording made before the renumbering names elements by this index.
  std::vector<int> mesh_tet;
  std::vector<std::array<int, 3>> surface;  // (nsurf) boundary triangles, outward
  std::vector<int> surface_nodes;           // (nsurfnode) nodes on the boundary
  // Elements ------------------------------------------------------------------
  Materials materials;                      // (ntet) as built: tissue and inclusions
  /// (ntet) Pa: each element's tissue without tumours, the tissue's modulus or its
  /// layer's (tissue_layers.h). The tumour rule compares with it; erasing restores it.
  std::vector<double> tissue_young;
  std::vector<double> volume;               // (ntet) m^3
  std::vector<std::array<Eigen::Vector3d, 4>> grad;  // (ntet x 4) shape gradients, 1/m
  std::vector<Eigen::Matrix3d> dm_inv;      // (ntet) inverse rest edge matrix
  // Nodes ---------------------------------------------------------------------
  std::vector<double> mass;                 // (nnode) lumped, kg
  std::vector<unsigned char> fixed;         // (nnode) 1 = Dirichlet (chest wall)
  std::vector<int> dof;                     // (nnode) free index, -1 when fixed
  std::vector<int> free_nodes;              // (nfree) node of each free index
  // Sparsity of the free-free system in 3x3 blocks (block CSR, full symmetric storage).
  std::vector<int> row_ptr;                 // (nfree + 1)
  std::vector<int> col;                     // (nblock) free column index
  std::vector<int> diag_block;              // (nfree) block index of the diagonal
  std::vector<std::array<int, 16>> tet_block;  // (ntet x 4 x 4) block of (a,b), -1 if fixed
  // Element colouring: elements of one colour share no free node (race-free scatter).
  std::vector<std::vector<int>> colours;
  SkinMembrane skin;                        // the skin on the surface; empty: none
  Material tissue;                          // bulk material (for reporting)
  double density = 1000.0;

  int num_nodes() const { return static_cast<int>(rest.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
  int num_free() const { return static_cast<int>(free_nodes.size()); }
  int num_blocks() const { return static_cast<int>(col.size()); }
  /// Index of the block (ia, ib) of free indices in col/the block arrays; -1 when either is
  /// -1 (a fixed node). The pair must share an element.
  int block_of(int ia, int ib) const;

  /// Sets one element's material while the model is built (inclusions). A running body's
  /// materials change through Simulation::set_element_young (the model stays as built).
  void set_element_material(int e, double young_modulus, double poisson_ratio) {
    materials.set(e, young_modulus, poisson_ratio);
  }
};

/// Which nodes are fixed: by default the chest-wall base (z <= base_tolerance).
using FixedPredicate = std::function<bool(const Eigen::Vector3d&)>;

/// Builds a model from a mesh. Every element gets `tissue`; inclusions are applied
/// afterwards with set_element_material. Throws std::invalid_argument on a bad mesh.
Model build_model(TetMesh mesh, const Material& tissue, const FixedPredicate& is_fixed);

/// Parameters as a backend of this model runs them: Element::Auto resolved from the
/// tissue's Poisson's ratio, Preconditioner::Auto from the mesh's size and whether the
/// backend is the GPU's persistent solver (`gpu`), the corotation tolerance from the
/// force-error target (params.h), WarmStart::Auto. Both backends apply it to what they are
/// given, so params() names what runs.
inline SimParams resolved_for(const Model& m, SimParams p, bool gpu = false) {
  p.element = resolve_element(p.element, m.tissue.poisson_ratio);
  p.solver.warm_start = resolve_warm_start(p.solver.warm_start);
  p.solver.preconditioner = resolve_preconditioner(p.solver.preconditioner, gpu, m.num_nodes());
  p.solver.corotation_tolerance = resolve_corotation_tolerance(p.solver);
  return p;
}

/// Fixed predicate for the chest wall: z below `height` (m).
FixedPredicate fix_base(double height = 1e-9);

}  // namespace palpation::sim
