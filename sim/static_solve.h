// Direct solves with Eigen's sparse Cholesky: the reference the iterative solver is
// checked against, and small-deformation static problems (cantilever) where the
// answer must not depend on a CG tolerance.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "model.h"
#include "params.h"

namespace palpation::sim {

/// Global stiffness over the free degrees of freedom (3 per free node), assembled with
/// per-element rotations R (identity for the rest state). Symmetric. For the nodal-pressure
/// element the volumetric term B^T W B (nodal_pressure.h) is formed here on its own, with
/// Eigen's sparse products, as an independent check of the backends' factored form. Auto:
/// the element the model's tissue gets (resolve_element).
Eigen::SparseMatrix<double> assemble_stiffness(const Model& m, const std::vector<Eigen::Matrix3d>* rotations = nullptr,
                                               Element element = Element::Linear);

/// Linear static displacement under nodal loads (nnode x 3, N) with the fixed nodes held:
/// K u = f solved by SimplicialLDLT. Returns (nnode x 3) displacements, zero at fixed nodes.
/// Throws std::runtime_error when the factorisation fails (a free rigid mode).
std::vector<Eigen::Vector3d> solve_linear_static(const Model& m, const std::vector<Eigen::Vector3d>& loads,
                                                 Element element = Element::Linear);

/// The same solve by conjugate gradients with the multigrid preconditioner (amg.h) to a
/// relative residual `tolerance`: for meshes whose direct factorisation takes minutes (the
/// nodal-pressure term couples two rings of nodes, and the Cholesky factor fills in).
/// `iterations`, when given, receives CG's count. Throws std::runtime_error when CG does
/// not reach the tolerance in 5,000 iterations.
std::vector<Eigen::Vector3d> solve_linear_static_multigrid(const Model& m, const std::vector<Eigen::Vector3d>& loads,
                                                           Element element = Element::Linear, double tolerance = 1e-8,
                                                           int* iterations = nullptr);

/// Nodal loads of a uniform body force b (N/m^3): lumped, rho-free (volume / 4 per node).
std::vector<Eigen::Vector3d> body_force_loads(const Model& m, const Eigen::Vector3d& b);

}  // namespace palpation::sim
