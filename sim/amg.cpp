// Smoothed-aggregation multigrid: aggregation, tentative and smoothed prolongators, the
// Galerkin coarse operators and the V-cycle over the coarse levels (amg.h says why).
#include "amg.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace palpation::sim::amg {
namespace {

constexpr int kModes = 6;  // rigid motions: three translations, three rotations

/// Block-diagonal inverse of A's b x b diagonal blocks (a singular block: zero, which
/// leaves that node to the coarse levels).
SpMat block_diagonal_inverse(const SpMat& A, int b) {
  const int n = int(A.rows()) / b;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(n) * b * b);
  Eigen::MatrixXd D(b, b);
  for (int i = 0; i < n; ++i) {
    D.setZero();
    for (int r = 0; r < b; ++r)
      for (SpMat::InnerIterator it(A, i * b + r); it; ++it) {
        const int c = int(it.col()) - i * b;
        if (c >= 0 && c < b) D(r, c) = it.value();
      }
    Eigen::MatrixXd Dinv = D.ldlt().solve(Eigen::MatrixXd::Identity(b, b));
    if (!Dinv.allFinite()) Dinv.setZero();
    for (int r = 0; r < b; ++r)
      for (int c = 0; c < b; ++c)
        if (Dinv(r, c) != 0) t.emplace_back(i * b + r, i * b + c, Dinv(r, c));
  }
  SpMat M(A.rows(), A.cols());
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

/// Largest eigenvalue of D^-1 A (real and positive: similar to D^-1/2 A D^-1/2), by power
/// iteration from a fixed start; within a few percent after 20 steps (from below), which
/// is all the smoothers need: Jacobi's damping 4 / (3 rho) converges for eigenvalues up to
/// 1.5 times this, the Chebyshev polynomial over [1.1 rho / ratio, 1.1 rho] up to
/// 1.1 (1 + 1 / ratio) times.
double spectral_radius(const SpMat& Dinv, const SpMat& A) {
  Eigen::VectorXd v(A.rows());
  for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = 1.0 + 0.5 * std::sin(0.7 * double(i));
  double rho = 0;
  for (int it = 0; it < 20; ++it) {
    const Eigen::VectorXd y = Dinv * (A * v);
    const double nv = v.norm(), ny = y.norm();
    if (!(nv > 0) || !(ny > 0)) break;
    rho = ny / nv;
    v = y / ny;
  }
  return rho > 0 ? rho : 1.0;
}

/// `sweeps` damped block-Jacobi sweeps, damping 4 / (3 rho).
Smoothing jacobi(double rho, int sweeps) {
  Smoothing s;
  s.a.assign(std::size_t(sweeps), 0.0);
  s.c.assign(std::size_t(sweeps), 4.0 / (3.0 * rho));
  return s;
}

/// The Chebyshev polynomial of degree `degree` over [hi / ratio, hi], hi = 1.1 rho (the
/// power iteration's estimate is from below): theta the interval's centre, delta its
/// half-width, sigma = theta / delta; d_0 = r / theta, then
/// d_k = rho_k rho_{k-1} d_{k-1} + 2 rho_k / delta D^-1 r_k, rho_0 = 1 / sigma,
/// rho_k = 1 / (2 sigma - rho_{k-1}).
Smoothing chebyshev(double rho, int degree, double ratio) {
  const double hi = 1.1 * rho, lo = hi / ratio;
  const double theta = 0.5 * (hi + lo), delta = 0.5 * (hi - lo), sigma = theta / delta;
  Smoothing s;
  s.a.push_back(0.0);
  s.c.push_back(1.0 / theta);
  double rho_old = 1.0 / sigma;
  for (int k = 1; k < degree; ++k) {
    const double rho_new = 1.0 / (2.0 * sigma - rho_old);
    s.a.push_back(rho_new * rho_old);
    s.c.push_back(2.0 * rho_new / delta);
    rho_old = rho_new;
  }
  return s;
}

/// Drops the entries of each row of P below `fraction` of the row's largest (not
/// rescaled: with six coarse unknowns per aggregate no one row sum is to be kept). The
/// smoothed prolongator's small entries come from the rings of neighbours that its
/// smoothing reaches; they cost more in the cycle and in the coarse operator's fill than
/// they add to its convergence.
void truncate_rows(SpMat& P, double fraction) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(P.nonZeros()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    double big = 0;
    for (SpMat::InnerIterator it(P, i); it; ++it) big = std::max(big, std::abs(it.value()));
    for (SpMat::InnerIterator it(P, i); it; ++it)
      // The margin keeps an entry at the threshold to rounding: two builds from the same
      // system assembled in another summation order (the CPU's and the GPU's) keep the same.
      if (it.value() != 0 && std::abs(it.value()) >= fraction * big * (1 - 1e-9)) t.emplace_back(int(i), int(it.col()), it.value());
  }
  SpMat Q(P.rows(), P.cols());
  Q.setFromTriplets(t.begin(), t.end());
  P = std::move(Q);
}

/// Dense Cholesky of a coarsest level, refused beyond a size that a dense matrix should
/// take (a stalled coarsening would otherwise allocate without bound).
void factor_coarsest(const SpMat& A, int limit, Eigen::LLT<Eigen::MatrixXd>& llt) {
  if (A.rows() > limit)
    throw std::runtime_error("amg: the coarsening stalled at " + std::to_string(A.rows()) +
                             " unknowns, more than a direct solve of the coarsest level takes (" + std::to_string(limit) + ")");
  llt.compute(Eigen::MatrixXd(A));
  if (llt.info() != Eigen::Success || !llt.matrixLLT().allFinite())
    throw std::runtime_error("amg: the coarsest level (" + std::to_string(A.rows()) + " unknowns) is not positive definite");
}

}  // namespace

/// Largest eigenvalue of D^-1 A by Lanczos in the A inner product (D^-1 A is self-adjoint
/// in it), `steps` steps from the power iteration's start: the largest eigenvalue of the
/// tridiagonal matrix, from below like the power iteration's, but converging much faster.
/// The Chebyshev smoother needs it: its polynomial grows fast past the interval's end, and
/// 20 power steps came out 16-20 % low on the 28-across Hertz block at Poisson's ratio 0.40
/// (2.34 against 2.80; the 1.1 margin did not cover it and CG took 150-357 iterations a step
/// instead of 33-81). One product with A and one with D^-1 a step, as the power iteration.
double largest_eigenvalue(const SpMat& Dinv, const SpMat& A, int steps) {
  const Eigen::Index n = A.rows();
  if (n == 0) return 1.0;
  Eigen::VectorXd q(n);
  for (Eigen::Index i = 0; i < n; ++i) q[i] = 1.0 + 0.5 * std::sin(0.7 * double(i));
  Eigen::VectorXd Aq = A * q;
  double nq = q.dot(Aq);
  if (!(nq > 0)) return spectral_radius(Dinv, A);
  nq = std::sqrt(nq);
  q /= nq;
  Aq /= nq;
  Eigen::VectorXd q_old = Eigen::VectorXd::Zero(n), Aq_old = Eigen::VectorXd::Zero(n);
  std::vector<double> alpha, beta;
  double beta_old = 0;
  for (int j = 0; j < steps; ++j) {
    Eigen::VectorXd w = Dinv * Aq;  // D^-1 A q
    Eigen::VectorXd Aw = A * w;
    const double a = w.dot(Aq);     // <D^-1 A q, q>_A
    w -= a * q + beta_old * q_old;
    Aw -= a * Aq + beta_old * Aq_old;
    alpha.push_back(a);
    const double b2 = w.dot(Aw);
    if (!std::isfinite(a) || !(b2 > 1e-28 * a * a)) break;  // an invariant subspace: the Ritz values are exact
    const double b = std::sqrt(b2);
    beta.push_back(b);
    q_old.swap(q);
    Aq_old.swap(Aq);
    q = w / b;
    Aq = Aw / b;
    beta_old = b;
  }
  const Eigen::Index k = Eigen::Index(alpha.size());
  if (k == 0 || !std::isfinite(alpha[0])) return spectral_radius(Dinv, A);
  Eigen::VectorXd diag = Eigen::Map<const Eigen::VectorXd>(alpha.data(), k);
  Eigen::VectorXd sub = k > 1 ? Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(beta.data(), k - 1)) : Eigen::VectorXd();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  eig.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
  const double top = eig.eigenvalues().maxCoeff();
  return top > 0 && std::isfinite(top) ? top : spectral_radius(Dinv, A);
}

std::vector<int> aggregate(const SpMat& A, int block, double strength, int& count) {
  const int n = int(A.rows()) / block;
  // The node graph with the Frobenius norms of the blocks.
  std::vector<int> ptr(n + 1, 0), adj;
  std::vector<double> norm, diag(n, 0.0), acc(n, 0.0);
  std::vector<int> mark(n, -1), list;
  for (int i = 0; i < n; ++i) {
    list.clear();
    for (int r = 0; r < block; ++r)
      for (SpMat::InnerIterator it(A, i * block + r); it; ++it) {
        const int j = int(it.col()) / block;
        if (mark[j] != i) {
          mark[j] = i;
          acc[j] = 0;
          list.push_back(j);
        }
        acc[j] += it.value() * it.value();
      }
    for (int j : list) {
      if (j == i) {
        diag[i] = std::sqrt(acc[j]);
      } else {
        adj.push_back(j);
        norm.push_back(std::sqrt(acc[j]));
      }
    }
    ptr[i + 1] = int(adj.size());
  }
  // Strong couplings only.
  std::vector<int> sptr(n + 1, 0), sadj;
  std::vector<double> sw;
  for (int i = 0; i < n; ++i) {
    for (int k = ptr[i]; k < ptr[i + 1]; ++k) {
      const int j = adj[k];
      if (norm[k] >= strength * std::sqrt(diag[i] * diag[j])) {
        sadj.push_back(j);
        sw.push_back(norm[k] / std::sqrt(diag[i] * diag[j]));
      }
    }
    sptr[i + 1] = int(sadj.size());
  }
  std::vector<int> agg(n, -1);
  count = 0;
  // 1: a node whose strong neighbours are all free roots an aggregate of them all.
  for (int i = 0; i < n; ++i) {
    if (agg[i] >= 0) continue;
    bool free = true;
    for (int k = sptr[i]; k < sptr[i + 1] && free; ++k) free = agg[sadj[k]] < 0;
    if (!free) continue;
    agg[i] = count;
    for (int k = sptr[i]; k < sptr[i + 1]; ++k) agg[sadj[k]] = count;
    ++count;
  }
  // 2: the rest join the aggregate they are most strongly coupled to (of couplings equal
  // to rounding, the first: a symmetric mesh has exact ties, and a system assembled in
  // another summation order must choose as this one does).
  std::vector<int> joined = agg;
  for (int i = 0; i < n; ++i) {
    if (agg[i] >= 0) continue;
    double best = -1;
    for (int k = sptr[i]; k < sptr[i + 1]; ++k)
      if (agg[sadj[k]] >= 0 && sw[k] > best * (1 + 1e-9)) {
        best = sw[k];
        joined[i] = agg[sadj[k]];
      }
  }
  agg = joined;
  // 3: what is left (no strong neighbour in an aggregate) forms aggregates of its own.
  for (int i = 0; i < n; ++i) {
    if (agg[i] >= 0) continue;
    agg[i] = count;
    for (int k = sptr[i]; k < sptr[i + 1]; ++k)
      if (agg[sadj[k]] < 0) agg[sadj[k]] = count;
    ++count;
  }
  return agg;
}

void Hierarchy::build(const SpMat& A0, std::span<const Eigen::Vector3d> nodes, const Options& options,
                      const SpMat* sparser) {
  if (A0.rows() != A0.cols() || A0.rows() != 3 * Eigen::Index(nodes.size()) ||
      (sparser && (sparser->rows() != A0.rows() || sparser->cols() != A0.cols())))
    throw std::runtime_error("amg: a matrix of " + std::to_string(A0.rows()) + " rows for " +
                             std::to_string(nodes.size()) + " nodes (3 unknowns each)");
  for (Eigen::Index k = 0; k < A0.outerSize(); ++k)
    for (SpMat::InnerIterator it(A0, k); it; ++it)
      if (!std::isfinite(it.value()))
        throw std::runtime_error("amg: the matrix has an entry that is not finite (row " + std::to_string(it.row()) + ")");
  if (options.degree < 1 || options.coarse_degree < 1 || !(options.chebyshev_ratio > 1))
    throw std::runtime_error("amg: smoothing of degree " + std::to_string(options.degree) + " / " +
                             std::to_string(options.coarse_degree) + ", Chebyshev ratio " + std::to_string(options.chebyshev_ratio) +
                             " (at least 1, 1 and more than 1)");
  // Built aside and swapped in at the end: a build that throws leaves the levels as they were.
  std::vector<Level> levels;
  Eigen::LLT<Eigen::MatrixXd> coarsest;
  const int dense_limit = 4 * options.coarse_unknowns;
  // The finest level's near-null space: translations and rotations about the centroid,
  // the rotations scaled by the body's size so that all six columns are of one order.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& x : nodes) centre += x;
  if (!nodes.empty()) centre /= double(nodes.size());
  double size = 0;
  for (const auto& x : nodes) size = std::max(size, (x - centre).norm());
  if (!(size > 0)) size = 1;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3 * Eigen::Index(nodes.size()), kModes);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d d = (nodes[i] - centre) / size;
    auto b = B.block<3, kModes>(3 * Eigen::Index(i), 0);
    b.leftCols<3>().setIdentity();
    b(1, 3) = -d.z(), b(2, 3) = d.y();  // e_x x d
    b(0, 4) = d.z(), b(2, 4) = -d.x();  // e_y x d
    b(0, 5) = -d.y(), b(1, 5) = d.x();  // e_z x d
  }

  // The share of A's trace outside `sparser` (Options::chebyshev_share).
  double share = 0;
  if (sparser) {
    const double total = A0.diagonal().sum();
    if (total > 0) share = std::clamp(1.0 - sparser->diagonal().sum() / total, 0.0, 1.0);
  }
  Smoother fine_smoother = options.smoother;
  int fine_degree = options.degree;
  if (sparser && share >= options.chebyshev_share && fine_smoother != Smoother::Chebyshev) {
    fine_smoother = Smoother::Chebyshev;
    fine_degree = 2;
  }

  SpMat A = A0;
  int block = 3;
  for (int depth = 0;; ++depth) {
    Level L;
    L.Dinv = block_diagonal_inverse(A, block);
    const double rho = spectral_radius(L.Dinv, A);
    const int degree = depth == 0 ? fine_degree : options.coarse_degree;
    const Smoother smoother = depth == 0 ? fine_smoother : options.coarse_smoother;
    L.chebyshev = smoother == Smoother::Chebyshev;
    // Jacobi's damping converges up to 1.5 times the power estimate; Chebyshev's interval
    // ends at 1.1 times its estimate, so it takes Lanczos's.
    L.smoothing = smoother == Smoother::Chebyshev ? chebyshev(largest_eigenvalue(L.Dinv, A), degree, options.chebyshev_ratio)
                                                  : jacobi(rho, degree);
    if (depth == 0) L.fine_nonzeros = long(A.nonZeros());
    if (depth == 0 && options.keep_finest) L.A = A;
    const bool last = A.rows() <= options.coarse_unknowns || depth + 1 >= options.max_levels;
    // What this level aggregates and smooths the prolongator with, and that damping.
    const SpMat& S = depth == 0 && sparser ? *sparser : A;
    SpMat SDinv;
    double s_omega = 4.0 / (3.0 * rho);
    if (&S != &A && !last) {
      SDinv = block_diagonal_inverse(S, block);
      s_omega = 4.0 / (3.0 * spectral_radius(SDinv, S));
    }
    const SpMat& SD = &S != &A ? SDinv : L.Dinv;
    int count = 0;
    std::vector<int> agg;
    if (!last) agg = aggregate(S, block, options.strength, count);
    if (last || kModes * count >= A.rows()) {  // small enough, or the coarsening stalls
      if (depth == 0) {
        // Nothing to coarsen: the "coarse" level is the system itself, solved directly.
        L.P = SpMat(A.rows(), A.cols());
        L.P.setIdentity();
        L.R = L.P;
        factor_coarsest(A, dense_limit, coarsest);
        levels.push_back(std::move(L));
        Level C;
        C.A = std::move(A);
        levels.push_back(std::move(C));
      } else {
        factor_coarsest(A, dense_limit, coarsest);
        L.A = std::move(A);
        levels.push_back(std::move(L));
      }
      break;
    }
    // Tentative prolongator: per aggregate, an orthonormal basis of the near-null space
    // restricted to it (thin QR); R becomes the coarse level's near-null space.
    const int n = int(A.rows()) / block;
    std::vector<std::vector<int>> members(count);
    for (int i = 0; i < n; ++i) members[agg[i]].push_back(i);
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(std::size_t(A.rows()) * kModes);
    Eigen::MatrixXd Bc = Eigen::MatrixXd::Zero(Eigen::Index(count) * kModes, kModes);
    for (int a = 0; a < count; ++a) {
      const auto& mem = members[a];
      const int rows = block * int(mem.size());
      Eigen::MatrixXd Ba(rows, kModes);
      for (std::size_t m = 0; m < mem.size(); ++m) Ba.middleRows(block * Eigen::Index(m), block) = B.middleRows(block * Eigen::Index(mem[m]), block);
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Ba);
      const int k = std::min(rows, kModes);
      const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(rows, k);
      Bc.block(Eigen::Index(a) * kModes, 0, k, kModes) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
      for (std::size_t m = 0; m < mem.size(); ++m)
        for (int r = 0; r < block; ++r)
          for (int c = 0; c < k; ++c) {
            const double q = Q(block * Eigen::Index(m) + r, c);
            if (q != 0) t.emplace_back(mem[m] * block + r, a * kModes + c, q);
          }
    }
    SpMat Pt(A.rows(), Eigen::Index(count) * kModes);
    Pt.setFromTriplets(t.begin(), t.end());
    // Smoothed: P = (I - omega D^-1 A) Pt, and the Galerkin operator R A P.
    const SpMat SPt = S * Pt;
    const SpMat DSPt = SD * SPt;
    L.P = Pt - s_omega * DSPt;
    truncate_rows(L.P, options.truncation);
    L.R = L.P.transpose();
    SpMat Ac = L.R * (A * L.P);
    SpMat AcT = Ac.transpose();
    Ac = 0.5 * (Ac + AcT);
    // An aggregate smaller than the six modes leaves coarse unknowns with zero rows: give
    // them a unit diagonal (their residual is always zero, so they stay zero).
    double dmax = 0;
    for (Eigen::Index i = 0; i < Ac.rows(); ++i) dmax = std::max(dmax, std::abs(Ac.coeff(i, i)));
    std::vector<Eigen::Triplet<double>> fix;
    for (Eigen::Index i = 0; i < Ac.rows(); ++i)
      if (!(std::abs(Ac.coeff(i, i)) > 1e-12 * dmax)) fix.emplace_back(int(i), int(i), 1.0);
    if (!fix.empty()) {
      SpMat F(Ac.rows(), Ac.cols());
      F.setFromTriplets(fix.begin(), fix.end());
      Ac += F;
    }
    Ac.prune(0.0);
    if (depth > 0) L.A = std::move(A);  // the finest level's operator is the solver's
    levels.push_back(std::move(L));
    A = std::move(Ac);
    B = std::move(Bc);
    block = kModes;
  }
  levels_ = std::move(levels);
  coarsest_ = std::move(coarsest);
  sparser_share_ = share;
}

void Hierarchy::cycle(std::size_t k, const Eigen::VectorXd& r, Eigen::VectorXd& e) const {
  if (k + 1 == levels_.size()) {
    e = coarsest_.solve(r);
    return;
  }
  const Level& L = levels_[k];
  const int n = int(r.size());
  Eigen::VectorXd res(n), d(n), t(n), rc(L.R.rows()), ec;
  e.resize(n);
  auto mul_a = [&](const double* x, double* y) { multiply(L.A, x, y); };
  auto mul_dinv = [&](const double* x, double* y) { multiply(L.Dinv, x, y); };
  smooth(L.smoothing, n, mul_a, mul_dinv, r.data(), e.data(), res.data(), d.data(), t.data(), true, true);
  multiply(L.R, res.data(), rc.data());
  cycle(k + 1, rc, ec);
  multiply(L.P, ec.data(), t.data());
  e += t;
  smooth(L.smoothing, n, mul_a, mul_dinv, r.data(), e.data(), res.data(), d.data(), t.data(), false, false);
}

void Hierarchy::coarse_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const { cycle(1, r, e); }

void Hierarchy::full_cycle(const Eigen::VectorXd& r, Eigen::VectorXd& e) const {
  if (levels_.empty() || levels_.front().A.rows() != r.size())
    throw std::logic_error("amg: full_cycle needs the levels built with Options::keep_finest");
  cycle(0, r, e);
}

Eigen::MatrixXd Hierarchy::coarsest_inverse() const {
  if (levels_.empty()) return {};
  const Eigen::Index n = levels_.back().A.rows();
  return coarsest_.solve(Eigen::MatrixXd::Identity(n, n));
}

Stats Hierarchy::stats() const {
  Stats s;
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    const Level& L = levels_[k];
    s.unknowns.push_back(k == 0 ? int(L.P.rows()) : int(L.A.rows()));
    s.nonzeros.push_back(k == 0 ? L.fine_nonzeros : long(L.A.nonZeros()));
  }
  long total = 0;
  for (long z : s.nonzeros) total += z;
  s.operator_complexity = s.nonzeros.empty() || s.nonzeros[0] == 0 ? 0 : double(total) / double(s.nonzeros[0]);
  s.sparser_share = sparser_share_;
  s.finest_chebyshev = !levels_.empty() && levels_[0].chebyshev;
  return s;
}

int eigen_max_align_bytes() { return EIGEN_MAX_ALIGN_BYTES; }

}  // namespace palpation::sim::amg
