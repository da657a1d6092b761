// Smoothed-aggregation algebraic multigrid (Vanek, Mandel and Brezina 1996) for the implicit
// step's system, as a preconditioner of the conjugate gradients (solve_cg.h).
//
// Block-Jacobi sees each node alone, so its CG iteration count grows with the mesh (about
// with the number of nodes across the body) and with Poisson's ratio. Multigrid corrects
// the smooth part of the error on coarser levels, where it is no longer smooth. The levels
// are algebraic (aggregates of neighbouring nodes, no second mesh), and the coarse spaces
// carry the body's six rigid motions exactly (the near-null space of elasticity), which is
// what makes the coarse correction work for an elastic body.
//
// Hand-written, not a library: the Debian packages with smoothed aggregation (Trilinos
// ML/MueLu, PETSc's GAMG, hypre's BoomerAMG) each bring an MPI stack and their own matrix
// types; here a few hundred lines on Eigen's sparse matrices do what the solver needs.
//
// Setup takes the system matrix once (scalar CSR, three unknowns per node, in the solver's
// node order) and the nodes' rest positions. The finest level's smoothing runs on the
// solver's own current operator (cg::multiply); the coarse levels keep the Galerkin
// operators R A P of the matrix they were built from. The preconditioner stays a fixed
// symmetric positive definite operator within a solve, so plain CG stays valid; as the
// system drifts from the one the levels were built from (rotations, contact), only the
// quality of the coarse correction changes, and the caller rebuilds when that costs more
// iterations than a setup does.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace palpation::sim::amg {

using SpMat = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

struct Options {
  int coarse_unknowns = 600;  // a level at most this large is solved directly (Cholesky)
  int max_levels = 8;
  // A coupling of nodes i and j is strong when |A_ij| >= strength sqrt(|A_ii| |A_jj|), the
  // norms of the 3x3 (coarser: 6x6) blocks; aggregates grow along strong couplings. 0: every
  // coupling (the paper breast at truncation 0.2: 25 nodes per aggregate, 6.8 CG
  // iterations a step, against 13.7 nodes and 5.8 iterations at 0.08, 30 % less time a
  // step; docs/simulation.md).
  double strength = 0.0;
  // The prolongator keeps, per row, the entries of at least this fraction of the row's
  // largest (0.2 on the paper breast at strength 0.08: 5.7x fewer entries, the coarse
  // operator 1.6x sparser, 5.4 -> 5.8 iterations, 25 % less time a step).
  double truncation = 0.2;
  // Keep the finest operator, so that full_cycle can smooth on it (a solver that has no
  // operator of its own: Eigen's CG in static_solve.cpp).
  bool keep_finest = false;
};

/// The levels' sizes, for reports and tests.
struct Stats {
  std::vector<int> unknowns;       // per level, the finest first
  std::vector<long> nonzeros;      // per level
  double operator_complexity = 0;  // sum of the levels' nonzeros over the finest's
  int levels() const { return int(unknowns.size()); }
};

class Hierarchy {
 public:
  /// Builds the levels below A (symmetric positive definite, 3 unknowns per node, node i's
  /// rest position nodes[i]). `sparser`, when given, is what the finest level aggregates
  /// and smooths the prolongator with: a part of A with fewer neighbours per node (the
  /// stiffness without the nodal-pressure term, whose couplings reach two rings of nodes
  /// where the stiffness reaches one), which keeps the prolongator about three times
  /// sparser; the coarse operators are still R A P of the whole A. Throws
  /// std::runtime_error (and keeps the levels it had) on a matrix whose size does not
  /// match the nodes, an entry that is not finite, a coarsening that stalls above four
  /// times coarse_unknowns, or a coarsest level that is not positive definite.
  void build(const SpMat& A, std::span<const Eigen::Vector3d> nodes, const Options& options = {},
             const SpMat* sparser = nullptr);
  bool built() const { return !levels_.empty(); }

  /// The finest level's prolongation (fine unknowns x first coarse unknowns) and
  /// restriction (its transpose).
  const SpMat& prolongation() const { return levels_.front().P; }
  const SpMat& restriction() const { return levels_.front().R; }
  /// Damping of the finest level's Jacobi smoother: 4 / (3 rho(D^-1 A)), rho estimated.
  double fine_omega() const { return levels_.front().omega; }

  /// e ~ A_1^{-1} r on the first coarse level: one V-cycle over the coarse levels (one
  /// damped block-Jacobi sweep before and after each coarse correction, Cholesky on the
  /// coarsest), a symmetric positive definite linear map of r.
  void coarse_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const;
  /// e ~ A^{-1} r: one V-cycle from the finest level, on the operator kept by
  /// Options::keep_finest (std::logic_error without it).
  void full_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const;

  Stats stats() const;

 private:
  struct Level {
    SpMat A;     // this level's operator (empty on the finest: the solver applies its own)
    SpMat Dinv;  // inverse of A's diagonal blocks (block diagonal)
    SpMat P;     // prolongation from the next coarser level
    SpMat R;     // P^T
    double omega = 0;
    long fine_nonzeros = 0;  // the finest level's A (for stats)
  };
  void cycle(std::size_t k, const Eigen::VectorXd& r, Eigen::VectorXd& e) const;

  std::vector<Level> levels_;  // levels_[0] the finest; the last one coarsest (A only)
  Eigen::LLT<Eigen::MatrixXd> coarsest_;
};

/// Hierarchy as the preconditioner of Eigen's iterative solvers (Eigen::ConjugateGradient's
/// Preconditioner parameter), over levels built beforehand with Options::keep_finest.
class EigenPreconditioner {
 public:
  EigenPreconditioner() = default;
  template <class M>
  explicit EigenPreconditioner(const M&) {}
  void attach(const Hierarchy* levels) { levels_ = levels; }
  template <class M>
  EigenPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  EigenPreconditioner& factorize(const M&) { return *this; }
  template <class M>
  EigenPreconditioner& compute(const M&) { return *this; }
  template <class Rhs>
  Eigen::VectorXd solve(const Rhs& r) const {
    Eigen::VectorXd e;
    levels_->full_cycle(Eigen::VectorXd(r), e);
    return e;
  }
  Eigen::ComputationInfo info() const { return levels_ && levels_->built() ? Eigen::Success : Eigen::InvalidInput; }

 private:
  const Hierarchy* levels_ = nullptr;
};

/// y = M x, serial. Eigen's own row-major product forks an OpenMP team for any matrix of
/// more than 20,000 entries, which on the solver's small levels costs more than the
/// product (a third of the step on the coarse breast); the solver parallelises the fine
/// level itself.
template <class X>
void multiply(const SpMat& M, const X* x, double* y) {
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const double* v = M.valuePtr();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    double s = 0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) s += v[k] * double(x[inner[k]]);
    y[i] = s;
  }
}

/// Aggregates of the nodes of a matrix with `block` unknowns per node: agg[i] is node i's
/// aggregate (0..count-1). Exposed for tests.
std::vector<int> aggregate(const SpMat& A, int block, double strength, int& count);

}  // namespace palpation::sim::amg
