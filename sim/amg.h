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

/// The smoothing on one side of a coarse correction: `steps()` steps of
///   r_k = r_{k-1} - A d_{k-1} (k > 0),  d_k = a_k d_{k-1} + c_k D^-1 r_k,  x += d_k,
/// D the block diagonal of A; a polynomial of degree steps() in D^-1 A applied to the
/// residual. Damped block-Jacobi sweeps: a_k = 0, c_k = omega. Chebyshev: the recurrence
/// of the Chebyshev polynomial on an interval [lo, hi] of D^-1 A's spectrum (Saad,
/// Iterative Methods, alg. 12.1), which damps every error component with an eigenvalue in
/// it by the most a polynomial of that degree can. The same polynomial before and after
/// the correction keeps the V-cycle symmetric; it stays positive definite while the
/// smoothing converges on all of D^-1 A's spectrum.
struct Smoothing {
  std::vector<double> a, c;
  int steps() const { return int(c.size()); }
};

enum class Smoother { Jacobi, Chebyshev };

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
  // The smoothing before and after each coarse correction: `degree` damped block-Jacobi
  // sweeps (damping 4 / (3 rho), rho the largest eigenvalue of D^-1 A) or a Chebyshev
  // polynomial of that degree over [1.1 rho / chebyshev_ratio, 1.1 rho], on the finest
  // level; `coarse_smoother` of `coarse_degree` on the coarser ones. Each costs `degree`
  // products with the level's operator on each side. Chebyshev of degree 2 on the finest
  // level is the one for near-incompressible and stiffness-dominated systems: on the Hertz
  // scene (20 across, nodal pressure, CG 1e-8) 61 / 93 / 286 iterations at Poisson's ratio
  // 0.40 / 0.49 / 0.499 against one Jacobi sweep's 103 / 219 / 607 (1.5x from 0.40 to 0.49
  // against 2.1x), 25-30 % less time a step at 0.49. Not the default: on the paper sweep (1 ms
  // steps, mass-heavy, 0.45) it saves one iteration in seven and each costs 5 products with
  // the system instead of 3, 15-40 % more time a step (docs/simulation.md); chebyshev_share
  // picks it by the system instead.
  Smoother smoother = Smoother::Jacobi;
  int degree = 1;
  // With `sparser` given to build(): when the rest of A (A less sparser: the nodal-pressure
  // term, where the callers split it off) holds at least this share of A's trace, the
  // finest level is smoothed by Chebyshev of degree 2 instead of `smoother` / `degree`.
  // The share orders the cases of one scene and mesh, not all of them (docs/simulation.md,
  // "The smoother"): Chebyshev was the faster step from 0.32 up on the Hertz scene, from
  // about 0.4 on the paper breast at 1 ms steps, nowhere up to 0.69 on the xfine breast.
  // More than 1: never (the smoother named is used).
  double chebyshev_share = 2;
  Smoother coarse_smoother = Smoother::Jacobi;
  int coarse_degree = 1;
  double chebyshev_ratio = 30;
  // Keep the finest operator, so that full_cycle can smooth on it (a solver that has no
  // operator of its own: Eigen's CG in static_solve.cpp).
  bool keep_finest = false;
};

/// The levels' sizes, for reports and tests.
struct Stats {
  std::vector<int> unknowns;       // per level, the finest first
  std::vector<long> nonzeros;      // per level
  double operator_complexity = 0;  // sum of the levels' nonzeros over the finest's
  double sparser_share = 0;        // the share of A's trace outside build()'s `sparser` (0 without one)
  bool finest_chebyshev = false;   // the finest level is smoothed by a Chebyshev polynomial
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
  /// The finest level's smoothing (Options::smoother).
  const Smoothing& fine_smoothing() const { return levels_.front().smoothing; }

  /// e ~ A_1^{-1} r on the first coarse level: one V-cycle over the coarse levels (the
  /// levels' smoothing before and after each coarse correction, Cholesky on the
  /// coarsest), a symmetric positive definite linear map of r.
  void coarse_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const;
  /// e ~ A^{-1} r: one V-cycle from the finest level, on the operator kept by
  /// Options::keep_finest (std::logic_error without it).
  void full_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const;

  Stats stats() const;

  /// One level, as the cycles use it (for a copy elsewhere: the GPU's, sim/cuda/multigrid.cuh).
  struct Level {
    SpMat A;     // this level's operator (empty on the finest: the solver applies its own)
    SpMat Dinv;  // inverse of A's diagonal blocks (block diagonal)
    SpMat P;     // prolongation from the next coarser level
    SpMat R;     // P^T
    Smoothing smoothing;
    bool chebyshev = false;  // `smoothing` is a Chebyshev polynomial (else damped Jacobi sweeps)
    long fine_nonzeros = 0;  // the finest level's A (for stats)
  };
  /// The levels, the finest first; the last is the coarsest (its operator alone).
  const std::vector<Level>& levels() const { return levels_; }
  /// The coarsest level's operator inverted, dense (what its Cholesky solve applies).
  Eigen::MatrixXd coarsest_inverse() const;

 private:
  void cycle(std::size_t k, const Eigen::VectorXd& r, Eigen::VectorXd& e) const;

  std::vector<Level> levels_;  // levels_[0] the finest; the last one coarsest (A only)
  double sparser_share_ = 0;   // Stats::sparser_share of the last build
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

/// x += S (b - A x) for the smoothing S: A and D^-1 are applied by mul_a(in, out) and
/// mul_dinv(in, out), on n unknowns; r, d and t are scratch (r, d must not alias b or x).
/// `from_zero`: x is zero on entry (the first step needs no product). `residual`: r holds
/// b - A x on return (one product more). steps() products with A (less one from zero).
template <class T, class MulA, class MulDinv>
void smooth(const Smoothing& s, int n, MulA&& mul_a, MulDinv&& mul_dinv, const T* b, T* x, T* r, T* d, T* t,
            bool from_zero, bool residual) {
  if (from_zero) {
    for (int i = 0; i < n; ++i) r[i] = b[i];
  } else {
    mul_a(x, t);
    for (int i = 0; i < n; ++i) r[i] = b[i] - t[i];
  }
  for (int k = 0; k < s.steps(); ++k) {
    if (k > 0) {
      mul_a(d, t);
      for (int i = 0; i < n; ++i) r[i] -= t[i];
    }
    mul_dinv(r, t);
    const T a = T(s.a[std::size_t(k)]), c = T(s.c[std::size_t(k)]);
    if (k == 0) {
      for (int i = 0; i < n; ++i) d[i] = c * t[i];
    } else {
      for (int i = 0; i < n; ++i) d[i] = a * d[i] + c * t[i];
    }
    if (k == 0 && from_zero) {
      for (int i = 0; i < n; ++i) x[i] = d[i];
    } else {
      for (int i = 0; i < n; ++i) x[i] += d[i];
    }
  }
  if (residual && s.steps() > 0) {
    mul_a(d, t);
    for (int i = 0; i < n; ++i) r[i] -= t[i];
  }
}

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

/// Largest eigenvalue of Dinv A (Dinv the inverse of A's diagonal blocks, A symmetric
/// positive definite), by `steps` Lanczos steps: from below, what the Chebyshev smoother's
/// interval is sized by. Exposed for tests.
double largest_eigenvalue(const SpMat& Dinv, const SpMat& A, int steps = 20);

/// EIGEN_MAX_ALIGN_BYTES as this library was compiled: the Eigen objects it hands out are
/// freed by Eigen's matching aligned free only where the caller was compiled alike (the CUDA
/// sources, by nvcc, check it against their own).
int eigen_max_align_bytes();

}  // namespace palpation::sim::amg
