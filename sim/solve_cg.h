// Preconditioned conjugate gradients on a symmetric 3x3-block CSR matrix.
// Block-Jacobi preconditioner (inverse of each 3x3 diagonal block), warm start from the
// initial content of x. OpenMP over rows when `parallel` (both cores, large systems).
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Dense>

namespace palpation::sim::cg {

template <class T>
struct BlockSystem {
  int n;                 // block rows (free nodes)
  const int* row_ptr;    // (n + 1)
  const int* col;        // (nblock)
  const T* blocks;       // (nblock x 9) row-major 3x3
  T* precond;            // (n x 9) workspace for the inverse diagonal blocks
};

template <class T>
struct Workspace {
  std::vector<T> r, z, p, q;
  void resize(std::size_t n) {
    r.resize(n);
    z.resize(n);
    p.resize(n);
    q.resize(n);
  }
};

struct Result {
  int iterations = 0;
  double relative_residual = 0.0;
  bool converged = false;
};

/// y = A x
template <class T>
void multiply(const BlockSystem<T>& A, const T* x, T* y, bool parallel) {
#pragma omp parallel for schedule(static) if (parallel)
  for (int i = 0; i < A.n; ++i) {
    T y0 = 0, y1 = 0, y2 = 0;
    for (int k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k) {
      const T* b = A.blocks + 9 * std::size_t(k);
      const T* xx = x + 3 * A.col[k];
      y0 += b[0] * xx[0] + b[1] * xx[1] + b[2] * xx[2];
      y1 += b[3] * xx[0] + b[4] * xx[1] + b[5] * xx[2];
      y2 += b[6] * xx[0] + b[7] * xx[1] + b[8] * xx[2];
    }
    y[3 * i] = y0;
    y[3 * i + 1] = y1;
    y[3 * i + 2] = y2;
  }
}

template <class T>
T dot(const T* a, const T* b, int n, bool parallel) {
  T s = 0;
#pragma omp parallel for reduction(+ : s) schedule(static) if (parallel)
  for (int i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

/// Inverts the diagonal blocks into A.precond. `diag` is each row's diagonal block index.
template <class T>
void build_block_jacobi(const BlockSystem<T>& A) {
  for (int i = 0; i < A.n; ++i) {
    int k = A.row_ptr[i];
    while (A.col[k] != i) ++k;
    Eigen::Matrix<T, 3, 3> D = Eigen::Map<const Eigen::Matrix<T, 3, 3, Eigen::RowMajor>>(A.blocks + 9 * std::size_t(k));
    Eigen::Matrix<T, 3, 3> Dinv = D.inverse();
    if (!Dinv.allFinite()) Dinv.setZero();
    Eigen::Map<Eigen::Matrix<T, 3, 3, Eigen::RowMajor>>(A.precond + 9 * std::size_t(i)) = Dinv;
  }
}

/// Solves A x = b to ||b - A x|| <= tol ||b|| or max_iter iterations.
template <class T>
Result solve(const BlockSystem<T>& A, const T* b, T* x, T tol, int max_iter, Workspace<T>& w, bool parallel) {
  const int n = 3 * A.n;
  w.resize(n);
  build_block_jacobi(A);
  auto precondition = [&A](const T* r, T* z) {
    for (int i = 0; i < A.n; ++i) {
      const T* P = A.precond + 9 * std::size_t(i);
      const T* ri = r + 3 * i;
      z[3 * i] = P[0] * ri[0] + P[1] * ri[1] + P[2] * ri[2];
      z[3 * i + 1] = P[3] * ri[0] + P[4] * ri[1] + P[5] * ri[2];
      z[3 * i + 2] = P[6] * ri[0] + P[7] * ri[1] + P[8] * ri[2];
    }
  };
  Result res;
  const T bnorm = std::sqrt(dot(b, b, n, parallel));
  if (!(bnorm > 0)) {
    for (int i = 0; i < n; ++i) x[i] = 0;
    res.converged = true;
    return res;
  }
  multiply(A, x, w.q.data(), parallel);
  for (int i = 0; i < n; ++i) w.r[i] = b[i] - w.q[i];
  T rnorm = std::sqrt(dot(w.r.data(), w.r.data(), n, parallel));
  if (!std::isfinite(double(rnorm)) || rnorm > T(1e3) * bnorm) {
    // A warm start that is worse than nothing (or broken): restart from zero.
    for (int i = 0; i < n; ++i) {
      x[i] = 0;
      w.r[i] = b[i];
    }
    rnorm = bnorm;
  }
  precondition(w.r.data(), w.z.data());
  for (int i = 0; i < n; ++i) w.p[i] = w.z[i];
  T rz = dot(w.r.data(), w.z.data(), n, parallel);
  int it = 0;
  while (it < max_iter && rnorm > tol * bnorm) {
    multiply(A, w.p.data(), w.q.data(), parallel);
    const T pq = dot(w.p.data(), w.q.data(), n, parallel);
    if (!(pq > 0)) break;  // not positive definite along p (or NaN): stop, report
    const T alpha = rz / pq;
    for (int i = 0; i < n; ++i) {
      x[i] += alpha * w.p[i];
      w.r[i] -= alpha * w.q[i];
    }
    precondition(w.r.data(), w.z.data());
    const T rz_new = dot(w.r.data(), w.z.data(), n, parallel);
    rnorm = std::sqrt(dot(w.r.data(), w.r.data(), n, parallel));
    const T beta = rz_new / rz;
    rz = rz_new;
    for (int i = 0; i < n; ++i) w.p[i] = w.z[i] + beta * w.p[i];
    ++it;
  }
  res.iterations = it;
  res.relative_residual = double(rnorm / bnorm);
  res.converged = rnorm <= tol * bnorm;
  return res;
}

}  // namespace palpation::sim::cg
