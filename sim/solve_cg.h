// Preconditioned conjugate gradients on a symmetric 3x3-block CSR matrix
//   A = scale * B + D,
// B the stored blocks, D an optional block diagonal kept apart (the CPU backend keeps the
// rotated stiffness B from step to step and rebuilds only the mass and contact terms D
// and the time-step factor). Block-Jacobi preconditioner (inverse of each 3x3 diagonal
// block of A), or one multigrid V-cycle (amg.h) whose finest-level smoothing is a
// polynomial in that block-Jacobi times A; warm start from the initial content of x.
// OpenMP over rows when `parallel` (both cores, large systems).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "amg.h"
#include "lanes4.h"

namespace palpation::sim::cg {

/// The average-nodal-pressure volumetric term B^T W B (nodal_pressure.h), kept factored:
/// (B x)_n = sum_j b_nj . x_j over the pressure rows n (every node), then
/// (B^T pi)_j = sum_n b_nj pi_n over the free rows j.
template <class T>
struct PressureTerm {
  int nnode = 0;
  const int* row_ptr = nullptr;    // (nnode + 1)
  const int* col = nullptr;        // (npair) free index
  const int* t_row_ptr = nullptr;  // (nfree + 1)
  const int* t_node = nullptr;     // (npair)
  const int* t_pair = nullptr;     // (npair)
  const T* b = nullptr;            // (npair x 3) coupling vectors b_nj
  const T* w = nullptr;            // (nnode) lambda_n / V_n
  T* pi = nullptr;                 // (nnode) scratch: the nodal pressures of the last product
  // Optional: the free rows' couplings in the block matrix's order, for a product by block
  // rows (pressure_rows_by_blocks): at block (i, c), bb = b_{n(i) c} and bt = b_{n(c) i}
  // (3 T each and one T of padding past the last), n(i) = free_node[i]; the fixed nodes'
  // rows and each free row's pairs with them (NodalPressurePattern::fixed_rows, ft_*).
  const T* bb = nullptr;
  const T* bt = nullptr;
  const int* free_node = nullptr;   // (nfree)
  T* pif = nullptr;                 // (nfree) scratch: the free nodes' pressures of the last product
  int nfixed = 0;
  const int* fixed_rows = nullptr;  // (nfixed) nodes; their pressures go to pi
  const int* ft_row_ptr = nullptr;  // (nfree + 1)
  const int* ft_node = nullptr;     // a fixed node n of free row j's pair (n, j)
  const int* ft_pair = nullptr;     // that pair's index
};

/// Gives P the block layout: the couplings bb and bt in the block order, each free row's
/// node, the scratch pif, and the fixed rows of `pattern` (a NodalPressurePattern:
/// fixed_rows, ft_row_ptr, ft_node, ft_pair).
template <class T, class Pattern>
void set_block_layout(PressureTerm<T>& P, const Pattern& pattern, const int* free_node, const T* bb, const T* bt,
                      T* pif) {
  P.bb = bb;
  P.bt = bt;
  P.free_node = free_node;
  P.pif = pif;
  P.nfixed = static_cast<int>(pattern.fixed_rows.size());
  P.fixed_rows = pattern.fixed_rows.data();
  P.ft_row_ptr = pattern.ft_row_ptr.data();
  P.ft_node = pattern.ft_node.data();
  P.ft_pair = pattern.ft_pair.data();
}

/// sum_k b_k . x_{col_k} over [k0, k1), in two chains of sums. Inlined by force here and
/// below: GCC left these row bodies as calls from the OpenMP-outlined loops, a third of
/// the product's time on the coarse breast.
template <class T>
[[gnu::always_inline]] inline T coupling_sum(const T* __restrict b3, const int* __restrict col, int k0, int k1, const T* __restrict x) {
  T s0 = 0, s1 = 0;
  int k = k0;
  for (; k + 2 <= k1; k += 2) {
    const T* b = b3 + 3 * std::size_t(k);
    const T* x0 = x + 3 * std::size_t(col[k]);
    const T* x1 = x + 3 * std::size_t(col[k + 1]);
    s0 += b[0] * x0[0] + b[1] * x0[1] + b[2] * x0[2];
    s1 += b[3] * x1[0] + b[4] * x1[1] + b[5] * x1[2];
  }
  if (k < k1) {
    const T* b = b3 + 3 * std::size_t(k);
    const T* x0 = x + 3 * std::size_t(col[k]);
    s0 += b[0] * x0[0] + b[1] * x0[1] + b[2] * x0[2];
  }
  return s0 + s1;
}

/// pi_n = w_n (sum_j b_nj . x_j + c_n) for every pressure row (c: none, or per node).
template <class T>
void pressure_rows(const PressureTerm<T>& P, const T* __restrict x, const T* __restrict c, bool parallel) {
#pragma omp parallel for schedule(static) if (parallel)
  for (int n = 0; n < P.nnode; ++n)
    P.pi[n] = P.w[n] * ((c ? c[n] : T(0)) + coupling_sum(P.b, P.col, P.row_ptr[n], P.row_ptr[n + 1], x));
}

/// (B^T pi)_j for free row j, from the pressures of the last pressure_rows.
template <class T>
[[gnu::always_inline]] inline lanes::V4<T> pressure_gather(const PressureTerm<T>& P, int j) {
  lanes::V4<T> y = {0, 0, 0, 0};
  for (int k = P.t_row_ptr[j]; k < P.t_row_ptr[j + 1]; ++k) y += lanes::load3(P.b + 3 * std::size_t(P.t_pair[k])) * P.pi[P.t_node[k]];
  return y;
}

/// A symmetric block matrix's upper triangle beside its full rows, for a one-thread product
/// (upper_rows) that reads each off-diagonal block once for both (i, c) and (c, i). Row i
/// holds the columns c >= i, its diagonal first; at entry (i, c) the block A_ci (= A_ic^T),
/// column-major, and with a pressure term bb = b_{n(i) c} and bt = b_{n(c) i} (the full
/// layout's couplings at block (i, c)). A product through it reads x (and the pressure
/// pass's x) four values at a time, so x must hold one readable value past its 3 n.
template <class T>
struct UpperBlocks {
  const int* row_ptr = nullptr;  // (n + 1)
  const int* col = nullptr;      // (nupper)
  const T* blocks = nullptr;     // (nupper x 9) + 1 T of padding
  const T* bb = nullptr;         // (nupper x 3) + 1, with a pressure term
  const T* bt = nullptr;
  T* scatter = nullptr;  // (n x 4) zero between products: rows c's sums from the rows above
};

template <class T>
struct BlockSystem {
  int n;                 // block rows (free nodes)
  const int* row_ptr;    // (n + 1)
  const int* col;        // (nblock)
  const T* blocks;       // (nblock x 9) column-major 3x3, plus one T of padding at the end
  T scale = 1;           // A = scale * blocks + diag
  const T* diag = nullptr;       // (n x 9) column-major extra diagonal blocks + 1 T padding, or none
  const int* diag_index = nullptr;  // (n) block index of each row's diagonal, or none (searched)
  // Optional: B^T W B added to the stored blocks (A = scale * (blocks + B^T W B) + diag),
  // and its 3x3 diagonal blocks (n x 9, column-major) for the preconditioner.
  const PressureTerm<T>* pressure = nullptr;
  const T* pressure_diag = nullptr;
  // Optional: the upper triangle, used by a product on one thread (multiply).
  const UpperBlocks<T>* upper = nullptr;
};

template <class T>
struct Workspace {
  std::vector<T> r, z, p, q;
  std::vector<T> precond;  // (n / 3 x 12) inverse diagonal blocks, columns of four lanes
  // The caller keeps `precond` for the system it solves (invert_diagonal of the rows whose
  // diagonal changed): solve() does not build it.
  bool precond_kept = false;
  // Multigrid levels below this system (none: block-Jacobi alone), and its scratch.
  const amg::Hierarchy* multigrid = nullptr;
  std::vector<T> t, s, d;
  Eigen::VectorXd coarse_r, coarse_e, fine_e;
  // Each vector one value longer than the system (zero, never written): a product through
  // UpperBlocks reads one past its input.
  void resize(std::size_t n) {
    if (multigrid) {
      t.resize(n + 1);
      s.resize(n + 1);
      d.resize(n + 1);
    }
    precond.resize(4 * n);
    r.resize(n + 1);
    z.resize(n + 1);
    p.resize(n + 1);
    q.resize(n + 1);
  }
};

struct Result {
  int iterations = 0;
  double relative_residual = 0.0;
  bool converged = false;
  bool rescued = false;  // went past max_iter towards rescue_tol
};

/// The nodal pressures of a product by block rows (A's pressure term has the block
/// layout), w_n (sum_j b_nj . x_j + c_n) (c: none, or per node): the free rows' from bb
/// along A's own rows into pif, the fixed rows' into pi.
///
/// `Padded`: x holds one readable value past its 3 n (UpperBlocks), so each x_c is one
/// four-lane load (its fourth lane, the next node's first value, meets bb's fourth and is
/// not summed): the pass 1.3-1.4x quicker than with three-value loads (this VM, a box of
/// 135k blocks, float: 124 -> 84-92 us).
template <class T, bool Padded = false>
void pressure_rows_by_blocks(const BlockSystem<T>& A, const T* __restrict x, const T* __restrict c, bool parallel) {
  const PressureTerm<T>& P = *A.pressure;
  using V4 = lanes::V4<T>;
  const auto xload = [x](int col) { return Padded ? lanes::load4(x + 3 * std::size_t(col)) : lanes::load3(x + 3 * std::size_t(col)); };
#pragma omp parallel for schedule(static) if (parallel)
  for (int i = 0; i < A.n; ++i) {
    // Four lanes a pair (bb's fourth is the next pair's first, x's a zero or not summed):
    // half the loads and a third of the multiplies of coupling_sum's scalar form, which
    // bb's padding allows and the pair order's unpadded b does not.
    V4 s0 = {0, 0, 0, 0}, s1 = {0, 0, 0, 0};
    int k = A.row_ptr[i];
    const int end = A.row_ptr[i + 1];
    for (; k + 2 <= end; k += 2) {
      s0 += lanes::load4(P.bb + 3 * std::size_t(k)) * xload(A.col[k]);
      s1 += lanes::load4(P.bb + 3 * std::size_t(k) + 3) * xload(A.col[k + 1]);
    }
    if (k < end) s0 += lanes::load4(P.bb + 3 * std::size_t(k)) * xload(A.col[k]);
    s0 += s1;
    const int n = P.free_node[i];
    P.pif[i] = P.w[n] * ((c ? c[n] : T(0)) + (s0[0] + s0[1] + s0[2]));
  }
  for (int f = 0; f < P.nfixed; ++f) {
    const int n = P.fixed_rows[f];
    P.pi[n] = P.w[n] * ((c ? c[n] : T(0)) + coupling_sum(P.b, P.col, P.row_ptr[n], P.row_ptr[n + 1], x));
  }
}

/// (B^T pi)_i for free row i after pressure_rows_by_blocks: bt along the row, streamed as
/// the blocks are (block k's part here, added by block_rows beside the block), and the
/// row's few pairs with fixed nodes.
template <class T>
[[gnu::always_inline]] inline lanes::V4<T> pressure_at_block(const BlockSystem<T>& A, int k) {
  return lanes::load4(A.pressure->bt + 3 * std::size_t(k)) * A.pressure->pif[A.col[k]];
}
template <class T>
[[gnu::always_inline]] inline lanes::V4<T> pressure_fixed_pairs(const BlockSystem<T>& A, int i) {
  const PressureTerm<T>& P = *A.pressure;
  lanes::V4<T> y = {0, 0, 0, 0};
  for (int q = P.ft_row_ptr[i]; q < P.ft_row_ptr[i + 1]; ++q)
    y += lanes::load3(P.b + 3 * std::size_t(P.ft_pair[q])) * P.pi[P.ft_node[q]];
  return y;
}
template <class T>
lanes::V4<T> pressure_by_blocks(const BlockSystem<T>& A, int i) {
  lanes::V4<T> y = pressure_fixed_pairs(A, i);
  for (int k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k) y += pressure_at_block(A, k);
  return y;
}

/// b x for the 3x3 block b (column-major; four-lane columns, the fourth lane not used).
template <class T>
[[gnu::always_inline]] inline lanes::V4<T> block_times(const T* __restrict b, T x0, T x1, T x2) {
  return lanes::load4(b) * x0 + lanes::load4(b + 3) * x1 + lanes::load4(b + 6) * x2;
}

/// The end of block row i of a product, acc holding the row's sum over the stored blocks:
/// y_i = scale acc + D_i x_i; returns x_i . y_i.
template <class T>
[[gnu::always_inline]] inline T finish_row(const BlockSystem<T>& A, int i, lanes::V4<T> acc, const T* __restrict x,
                                           T* __restrict y) {
  const T x0 = x[3 * i], x1 = x[3 * i + 1], x2 = x[3 * i + 2];
  if (A.diag) {
    acc = A.scale * acc + block_times(A.diag + 9 * std::size_t(i), x0, x1, x2);
  } else if (A.scale != T(1)) {
    acc *= A.scale;
  }
  y[3 * i] = acc[0];
  y[3 * i + 1] = acc[1];
  y[3 * i + 2] = acc[2];
  return x0 * acc[0] + x1 * acc[1] + x2 * acc[2];
}

/// y_i = scale (sum_k (B_ik x_k + at_block(k)) + at_row(i)) + D_i x_i over the block rows;
/// returns x . y.
///
/// Blocks are stored column-major, so B_ij x_j is three contiguous columns times three
/// broadcast scalars, which the compiler turns into 4-wide vector loads and FMAs
/// (GCC/Clang vector extensions, no intrinsics; any target). The fourth lane reads one
/// value past each block (the array carries one value of padding) and is ignored.
template <class T, class AtBlock, class AtRow>
T block_rows(const BlockSystem<T>& A, const T* __restrict x, T* __restrict y, bool parallel, AtBlock at_block,
             AtRow at_row) {
  using V4 = lanes::V4<T>;
  using lanes::load4;
  // One block: three columns times x's three entries broadcast.
  auto block = [](const T* __restrict b, const T* __restrict xx) { return block_times(b, xx[0], xx[1], xx[2]); };
  T xy = 0;
#pragma omp parallel for schedule(static) reduction(+ : xy) if (parallel)
  for (int i = 0; i < A.n; ++i) {
    // Two blocks per turn into two sums (half the loop overhead, two independent chains).
    V4 acc = {0, 0, 0, 0}, acc2 = {0, 0, 0, 0};
    const int* __restrict c = A.col;
    int k = A.row_ptr[i];
    const int end = A.row_ptr[i + 1];
    const T* __restrict b = A.blocks + 9 * std::size_t(k);
    for (; k + 2 <= end; k += 2, b += 18) {
      acc += block(b, x + 3 * c[k]) + at_block(k);
      acc2 += block(b + 9, x + 3 * c[k + 1]) + at_block(k + 1);
    }
    if (k < end) acc += block(b, x + 3 * c[k]) + at_block(k);
    acc += acc2 + at_row(i);
    xy += finish_row(A, i, acc, x, y);
  }
  return xy;
}

/// block_rows through A.upper on one thread (`Pressure`: with the term's B^T pi, after
/// pressure_rows_by_blocks): each stored block A_ci of entry (i, c) gives row i's A_ic x_c
/// = A_ci^T x_c (three four-lane sums against x_c, added across the row and reduced once)
/// and row c's A_ci x_i (x_i's entries broadcast once a row), into c's four-value slot of
/// U.scatter, which row c adds and clears. Four values a slot: a three-value stride lets a
/// four-lane store and the next row's load overlap two stores, which the CPU cannot
/// forward (measured 1.1x; with the slots 1.35x over block_rows, a box of 135k blocks,
/// this VM, float, with the pressure term).
template <class T, bool Pressure>
T upper_rows(const BlockSystem<T>& A, const T* __restrict x, T* __restrict y) {
  using V4 = lanes::V4<T>;
  using lanes::load4;
  const UpperBlocks<T>& U = *A.upper;
  const int* __restrict col = U.col;
  const T* __restrict blocks = U.blocks;
  const T* __restrict bb = U.bb;
  const T* __restrict bt = U.bt;
  const T* __restrict pif = Pressure ? A.pressure->pif : nullptr;
  T* __restrict ty = U.scatter;
  T xy = 0;
  for (int i = 0; i < A.n; ++i) {
    const int k0 = U.row_ptr[i], end = U.row_ptr[i + 1];
    const T x0 = x[3 * i], x1 = x[3 * i + 1], x2 = x[3 * i + 2];
    const T* b = blocks + 9 * std::size_t(k0);
    V4 acc = block_times(b, x0, x1, x2);  // the diagonal block
    T pi = 0;
    if constexpr (Pressure) {
      pi = pif[i];
      acc += load4(bt + 3 * std::size_t(k0)) * pi;
    }
    V4 a0 = {0, 0, 0, 0}, a1 = a0, a2 = a0;
    for (int k = k0 + 1; k < end; ++k) {
      const int c = col[k];
      b = blocks + 9 * std::size_t(k);
      const V4 c0 = load4(b), c1 = load4(b + 3), c2 = load4(b + 6);
      const V4 xc = load4(x + 3 * std::size_t(c));  // lane 3 not summed
      a0 += c0 * xc;
      a1 += c1 * xc;
      a2 += c2 * xc;
      V4 t = c0 * x0 + c1 * x1 + c2 * x2;
      if constexpr (Pressure) {
        acc += load4(bt + 3 * std::size_t(k)) * pif[c];
        t += load4(bb + 3 * std::size_t(k)) * pi;
      }
      T* slot = ty + 4 * std::size_t(c);
      lanes::store4(slot, load4(slot) + t);
    }
    acc[0] += a0[0] + a0[1] + a0[2];
    acc[1] += a1[0] + a1[1] + a1[2];
    acc[2] += a2[0] + a2[1] + a2[2];
    T* own = ty + 4 * std::size_t(i);
    acc += load4(own);
    lanes::store4(own, V4{0, 0, 0, 0});
    if constexpr (Pressure) acc += pressure_fixed_pairs(A, i);
    xy += finish_row(A, i, acc, x, y);
  }
  return xy;
}

/// y = A x; returns x . y when `dot_out` is set (fused: one pass over the matrix).
///
/// The nodal-pressure term, where A has one, in two passes: its pressures, then B^T pi
/// added in each block row. With the block layout both read the couplings in the blocks'
/// order beside the rows' own indices, with no scatter and no out-of-order gather. The
/// product against the one this replaced (a one-thread pass scattering b_nj pi_n into y by
/// pressure row, the gather by free row on threads), this VM, fastest of 8,000: coarse
/// breast, one thread, 52.3 -> 41.1 us (1.27x); paper mesh 716 -> 572 us (1.25x), on two
/// threads 449 -> 308-357 us. Without the layout, that gather (a term built elsewhere).
template <class T>
void multiply(const BlockSystem<T>& A, const T* __restrict x, T* __restrict y, bool parallel, T* dot_out = nullptr) {
  using V4 = lanes::V4<T>;
  const auto none = [](int) { return V4{0, 0, 0, 0}; };
  T xy;
  if (A.upper && !parallel) {
    if (A.pressure) {
      pressure_rows_by_blocks<T, true>(A, x, static_cast<const T*>(nullptr), false);
      xy = upper_rows<T, true>(A, x, y);
    } else {
      xy = upper_rows<T, false>(A, x, y);
    }
  } else if (!A.pressure) {
    xy = block_rows(A, x, y, parallel, none, none);
  } else if (A.pressure->bb) {
    pressure_rows_by_blocks(A, x, static_cast<const T*>(nullptr), parallel);
    xy = block_rows(
        A, x, y, parallel, [&](int k) { return pressure_at_block(A, k); }, [&](int i) { return pressure_fixed_pairs(A, i); });
  } else {
    pressure_rows(*A.pressure, x, static_cast<const T*>(nullptr), parallel);
    xy = block_rows(A, x, y, parallel, none, [&](int i) { return pressure_gather(*A.pressure, i); });
  }
  if (dot_out) *dot_out = xy;
}

template <class T>
T dot(const T* a, const T* b, int n, bool parallel) {
  T s = 0;
#pragma omp parallel for reduction(+ : s) schedule(static) if (parallel)
  for (int i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

/// Inverts row i's diagonal block of A into P's 12 values at 12 i (by columns of four
/// lanes, lane 3 zero); a singular or non-finite block gives zero. By its cofactors, written
/// out: Eigen's Map-and-inverse form of the same formula took 1.5x as long (this VM, float,
/// 9.8k rows: 400 against 240-270 us), a product's worth of every step on the paper mesh.
template <class T>
void invert_diagonal(const BlockSystem<T>& A, int i, T* P) {
  int k;
  if (A.diag_index) {
    k = A.diag_index[i];
  } else {
    k = A.row_ptr[i];
    while (A.col[k] != i) ++k;
  }
  const T* b = A.blocks + 9 * std::size_t(k);
  const T* pd = A.pressure_diag ? A.pressure_diag + 9 * std::size_t(i) : nullptr;
  const T* dd = A.diag ? A.diag + 9 * std::size_t(i) : nullptr;
  T m[9];  // column-major: m[r + 3 c]
  for (int q = 0; q < 9; ++q) m[q] = A.scale * (b[q] + (pd ? pd[q] : T(0))) + (dd ? dd[q] : T(0));
  // The inverse's (r, c) is the cofactor of (c, r) over the determinant; cRC below is the
  // inverse's column C, row R before the division.
  const T c00 = m[4] * m[8] - m[7] * m[5], c01 = m[7] * m[2] - m[1] * m[8], c02 = m[1] * m[5] - m[4] * m[2];
  const T c10 = m[6] * m[5] - m[3] * m[8], c11 = m[0] * m[8] - m[6] * m[2], c12 = m[3] * m[2] - m[0] * m[5];
  const T c20 = m[3] * m[7] - m[6] * m[4], c21 = m[6] * m[1] - m[0] * m[7], c22 = m[0] * m[4] - m[3] * m[1];
  const T det = m[0] * c00 + m[3] * c01 + m[6] * c02;
  const T id = T(1) / det;
  const T inv[9] = {c00 * id, c01 * id, c02 * id, c10 * id, c11 * id, c12 * id, c20 * id, c21 * id, c22 * id};
  bool finite = std::isfinite(id);
  for (T v : inv) finite = finite && std::isfinite(v);
  T* Pi = P + 12 * std::size_t(i);
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) Pi[4 * c + r] = finite ? inv[3 * c + r] : T(0);
    Pi[4 * c + 3] = 0;
  }
}

/// Inverts the diagonal blocks of A into P (n x 12).
template <class T>
void build_block_jacobi(const BlockSystem<T>& A, T* P) {
  for (int i = 0; i < A.n; ++i) invert_diagonal(A, i, P);
}

/// Over block rows [lo, hi): z = P r (block-Jacobi); returns r . z.
template <class T>
T precondition(const T* __restrict P, const T* __restrict r, T* __restrict z, int lo, int hi) {
  using V4 = lanes::V4<T>;
  V4 rz = {};
  for (int i = lo; i < hi; ++i) {
    const T* Pi = P + 12 * std::size_t(i);
    const T* ri = r + 3 * std::size_t(i);
    const V4 zi = lanes::load4(Pi) * ri[0] + lanes::load4(Pi + 4) * ri[1] + lanes::load4(Pi + 8) * ri[2];
    z[3 * i] = zi[0];
    z[3 * i + 1] = zi[1];
    z[3 * i + 2] = zi[2];
    rz += zi * lanes::load3(ri);
  }
  return rz[0] + rz[1] + rz[2];
}

/// Over entries [lo, hi): x += alpha p, r -= alpha q; returns r . r (four lanes at a time,
/// the reduction in four partial sums, which scalar code cannot vectorise).
template <class T>
T update_x_r(T* __restrict x, T* __restrict r, const T* __restrict p, const T* __restrict q, T alpha, int lo, int hi) {
  using V4 = lanes::V4<T>;
  V4 rr = {};
  int i = lo;
  for (; i + 4 <= hi; i += 4) {
    lanes::store4(x + i, lanes::load4(x + i) + alpha * lanes::load4(p + i));
    const V4 ri = lanes::load4(r + i) - alpha * lanes::load4(q + i);
    lanes::store4(r + i, ri);
    rr += ri * ri;
  }
  T s = rr[0] + rr[1] + rr[2] + rr[3];
  for (; i < hi; ++i) {
    x[i] += alpha * p[i];
    r[i] -= alpha * q[i];
    s += r[i] * r[i];
  }
  return s;
}

/// The block rows [lo, hi) of this thread's share of n rows (all of them outside a
/// parallel region).
inline void thread_rows(int n, int& lo, int& hi) {
  int t = 0, nt = 1;
#ifdef _OPENMP
  t = omp_get_thread_num();
  nt = omp_get_num_threads();
#endif
  lo = int(std::int64_t(n) * t / nt);
  hi = int(std::int64_t(n) * (t + 1) / nt);
}

/// z = M r for the multigrid preconditioner M: one V-cycle from zero with the hierarchy's
/// finest smoothing (amg::smooth, on A with this block-Jacobi) before and after the coarse
/// correction (amg.h); returns r . z. 2 m products with A for a smoothing of m steps, one
/// restriction and one prolongation.
template <class T>
T multigrid_cycle(const BlockSystem<T>& A, Workspace<T>& w, const T* __restrict r, T* __restrict z, bool parallel) {
  const amg::Hierarchy& H = *w.multigrid;
  const int n = 3 * A.n;
  const T* P = w.precond.data();
  T* __restrict t = w.t.data();
  T* __restrict res = w.s.data();
  T* __restrict d = w.d.data();
  auto mul_a = [&](const T* x, T* y) { multiply(A, x, y, parallel); };
  auto mul_dinv = [&](const T* x, T* y) { precondition(P, x, y, 0, A.n); };
  amg::smooth(H.fine_smoothing(), n, mul_a, mul_dinv, r, z, res, d, t, true, true);
  w.coarse_r.resize(H.restriction().rows());
  amg::multiply(H.restriction(), res, w.coarse_r.data());
  H.coarse_cycle(w.coarse_r, w.coarse_e);
  w.fine_e.resize(n);
  amg::multiply(H.prolongation(), w.coarse_e.data(), w.fine_e.data());
  for (int i = 0; i < n; ++i) z[i] += T(w.fine_e[i]);
  amg::smooth(H.fine_smoothing(), n, mul_a, mul_dinv, r, z, res, d, t, false, false);
  T rz = 0;
  for (int i = 0; i < n; ++i) rz += r[i] * z[i];
  return rz;
}

/// A without its pressure term as one scalar sparse matrix (3 unknowns per block row), in
/// double: with pressure_to_sparse, what the multigrid levels are built from.
template <class T>
amg::SpMat to_sparse(const BlockSystem<T>& A) {
  const int n = 3 * A.n;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(9 * std::size_t(A.row_ptr[A.n]) + 9 * std::size_t(A.n));
  for (int i = 0; i < A.n; ++i)
    for (int k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k)
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
          t.emplace_back(3 * i + r, 3 * A.col[k] + c, double(A.scale) * double(A.blocks[9 * std::size_t(k) + 3 * c + r]));
  if (A.diag)
    for (int i = 0; i < A.n; ++i)
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) t.emplace_back(3 * i + r, 3 * i + c, double(A.diag[9 * std::size_t(i) + 3 * c + r]));
  amg::SpMat M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

/// scale * B^T W B of A's pressure term as a scalar sparse matrix (empty without one):
/// to_sparse(A) plus this is the whole of A.
template <class T>
amg::SpMat pressure_to_sparse(const BlockSystem<T>& A) {
  const int n = 3 * A.n;
  amg::SpMat M(n, n);
  if (A.pressure) {
    // B: the pressure rows (one per node) over the free unknowns.
    const PressureTerm<T>& P = *A.pressure;
    std::vector<Eigen::Triplet<double>> b;
    for (int r = 0; r < P.nnode; ++r)
      for (int k = P.row_ptr[r]; k < P.row_ptr[r + 1]; ++k)
        for (int c = 0; c < 3; ++c) b.emplace_back(r, 3 * P.col[k] + c, double(P.b[3 * std::size_t(k) + c]));
    amg::SpMat B(P.nnode, n);
    B.setFromTriplets(b.begin(), b.end());
    Eigen::VectorXd w(P.nnode);
    for (int r = 0; r < P.nnode; ++r) w[r] = double(A.scale) * double(P.w[r]);
    const amg::SpMat WB = w.asDiagonal() * B;
    const amg::SpMat Bt = B.transpose();
    M = Bt * WB;
  }
  return M;
}

/// Solves A x = b to ||b - A x|| <= tol ||b|| or max_iter iterations; a solve still above
/// rescue_tol ||b|| there goes on to rescue_tol or rescue_iter iterations in all
/// (SolverParams::cg_rescue_tolerance says why). Two passes over memory per iteration: the
/// product (fused with p . q) and one fused update (x, r, z = P r, r . z, r . r).
template <class T>
Result solve(const BlockSystem<T>& A, const T* b, T* x, T tol, int max_iter, Workspace<T>& w, bool parallel,
             T rescue_tol = T(1), int rescue_iter = 0) {
  const int n = 3 * A.n;
  w.resize(n);
  if (!w.precond_kept) build_block_jacobi(A, w.precond.data());
  T* __restrict r = w.r.data();
  T* __restrict z = w.z.data();
  T* __restrict p = w.p.data();
  T* __restrict q = w.q.data();
  const T* __restrict P = w.precond.data();
  Result res;
  const T bnorm = std::sqrt(dot(b, b, n, parallel));
  if (!(bnorm > 0)) {
    for (int i = 0; i < n; ++i) x[i] = 0;
    res.converged = true;
    return res;
  }
  for (int i = 0; i < n; ++i) p[i] = x[i];  // x through p: padded for a product through A.upper
  multiply(A, p, q, parallel);
  T rr = 0;
  for (int i = 0; i < n; ++i) {
    r[i] = b[i] - q[i];
    rr += r[i] * r[i];
  }
  T rnorm = std::sqrt(rr);
  if (!std::isfinite(double(rnorm)) || rnorm > T(1e3) * bnorm) {
    // A warm start that is worse than nothing (or broken): restart from zero.
    for (int i = 0; i < n; ++i) {
      x[i] = 0;
      r[i] = b[i];
    }
    rnorm = bnorm;
  }
  T rz = w.multigrid ? multigrid_cycle(A, w, r, z, parallel) : precondition(P, r, z, 0, A.n);
  for (int i = 0; i < n; ++i) p[i] = z[i];
  int it = 0;
  while ((it < max_iter && rnorm > tol * bnorm) || (it < rescue_iter && rnorm > rescue_tol * bnorm)) {
    T pq = 0;
    multiply(A, p, q, parallel, &pq);
    if (!(pq > 0)) break;  // not positive definite along p (or NaN): stop, report
    const T alpha = rz / pq;
    T rz_new = 0, rr_new = 0;
#pragma omp parallel reduction(+ : rz_new, rr_new) if (parallel)
    {
      int lo, hi;
      thread_rows(A.n, lo, hi);
      rr_new += update_x_r(x, r, p, q, alpha, 3 * lo, 3 * hi);
      if (!w.multigrid) rz_new += precondition(P, r, z, lo, hi);
    }
    if (w.multigrid) rz_new = multigrid_cycle(A, w, r, z, parallel);
    rnorm = std::sqrt(rr_new);
    const T beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (parallel)
    for (int i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    ++it;
  }
  res.iterations = it;
  res.relative_residual = double(rnorm / bnorm);
  res.converged = rnorm <= tol * bnorm;
  res.rescued = it > max_iter;
  return res;
}

}  // namespace palpation::sim::cg
