// The multigrid preconditioner on the GPU: the levels that amg::Hierarchy builds on the
// host (amg.h; when, multigrid_keeper.h), copied to the device, and the device pieces of
// its V-cycle that the persistent PCG kernel (pcg.cu) runs between grid barriers.
//
// The V-cycle is solve_cg.h's multigrid_cycle and amg.cpp's Hierarchy::cycle step for
// step: the finest level smoothed on the kernel's own operator with its block-Jacobi, the
// coarse levels on their stored operators, the coarsest solved by its inverse (dense,
// applied as one more matrix: the Cholesky solve's result to rounding). Every matrix is
// scalar CSR, each row read by as many lanes as its length wants (CsrDev::lanes); a
// barrier follows each product whose result another thread reads. The coarse levels'
// vectors and sums are double; their matrices' values are stored in the solve's precision
// (MultigridDevice::upload's `single`): in float a value and its column take 8 bytes, not
// 12, and the products stream the bytes. The rounded matrices keep the V-cycle symmetric
// (a symmetric A_k rounds to a symmetric one, R = P^T entry for entry), so it stays a
// preconditioner CG can use; a float solve's own rounding is of the same size.
#pragma once

#include <deque>
#include <memory>
#include <type_traits>

#include "amg.h"
#include "cuda/common.cuh"

namespace palpation::sim::cuda {

constexpr int kMgMaxLevels = 8;  // amg::Options::max_levels
constexpr int kMgMaxSteps = 4;   // the smoothing's degree
static_assert(kPhases == kPhLevel + 4 * (kMgMaxLevels - 1), "a timed phase for each coarse level's passes");

/// Lanes per row of a CSR product (CsrDev::lanes): a whole block's threads per row.
constexpr int kBlockPerRow = 0;

/// A scalar CSR matrix on the device.
struct CsrDev {
  int rows = 0;
  const int* ptr = nullptr;
  const int* col = nullptr;
  const double* val = nullptr;   // the values in double, or
  const float* val32 = nullptr;  // in float: the one the solve's precision reads
  // Lanes that read a row together, 2 or 8, or kBlockPerRow: set by MultigridDevice from
  // the rows' number and mean length (csr_lanes).
  int lanes = kGroup;
};

/// CsrDev::lanes for a matrix of `rows` rows and `nonzeros` entries read by `threads`
/// threads (the launch's). Measured on the xfine breast's levels (H200, the PCG's phases,
/// docs/gpu-notes.md): a block per row where rows are long (128 entries and more) and few
/// (the restriction to the coarsest level and its inverse: 192 rows of hundreds of entries,
/// 27 -> 5 and 9 -> 5 us a pass against 8 lanes); 2 lanes where short rows outnumber the
/// groups of 8 (the finest prolongation, 244k rows: 25 -> 13 us); 8 elsewhere (2 or 32
/// lanes on the first coarse level's 16.5k rows were 7-70 % slower).
int csr_lanes(long rows, long nonzeros, long threads);

/// One level: its operator and inverse diagonal blocks (levels >= 1), its prolongation
/// from the next level and restriction to it (all but the coarsest), its smoothing
/// (amg::Smoothing), and its vectors (levels >= 1; the finest uses the kernel's).
struct MgLevelDev {
  int n = 0;
  CsrDev A, Dinv, P, R;
  int steps = 0;
  double a[kMgMaxSteps] = {}, c[kMgMaxSteps] = {};
  double* b = nullptr;  // right-hand side (the restricted residual)
  double* x = nullptr;  // correction
  double* r = nullptr;  // residual
  double* d = nullptr;  // smoothing direction
};

struct MgDev {
  int levels = 0;
  MgLevelDev lv[kMgMaxLevels];
  CsrDev coarsest_inverse;  // the last level's operator inverted, as full rows
};

/// The levels on the device. upload() copies a built hierarchy (throws std::runtime_error
/// on one the kernel cannot run: one level, too many, too high a degree); dev() is the
/// descriptor's device address, null before the first upload.
///
/// borrow() gives another backend's solve the same levels without a copy: their matrices
/// (read only, kept alive here for as long as this borrows them, whatever the owner uploads
/// next) with vectors of its own, so that the two solves never share scratch. The borrower
/// names its precision (`single` as upload's): a solve reads the values of its own
/// precision only, so levels of the other one are refused (std::logic_error).
class MultigridDevice {
 public:
  /// `threads`: the solve's launch (CsrDev::lanes); `lanes` >= 0: every matrix's lanes
  /// (CudaTuning::mg_lanes), else csr_lanes's.
  /// `single`: the matrices' values in float (a float solve's), else in double.
  void upload(const amg::Hierarchy& h, cudaStream_t s, long threads, int lanes, bool single);
  void borrow(const MultigridDevice& owner, cudaStream_t s, bool single);
  const MgDev* dev() const { return desc_.size() ? desc_.get() : nullptr; }
  int levels() const { return host_.levels; }

 private:
  struct Matrices {
    std::deque<DeviceArray<int>> ints;
    std::deque<DeviceArray<double>> dbls;
    std::deque<DeviceArray<float>> flts;
  };
  CsrDev csr(const amg::SpMat& M, cudaStream_t s, long threads, int lanes, bool single);
  double* vec(int n);
  /// The level vectors of host_ allocated here, and the descriptor uploaded.
  void own_vectors(cudaStream_t s);
  std::shared_ptr<Matrices> mats_;
  std::deque<DeviceArray<double>> vecs_;
  MgDev host_{};  // the descriptor as uploaded (its vectors this object's own)
  bool single_ = false;  // the matrices' values in float (upload's `single`)
  DeviceArray<MgDev> desc_;
};

#ifdef __CUDACC__

/// M's values as the solve of precision V reads them (MultigridDevice::upload's `single`).
template <class V>
__device__ __forceinline__ const V* csr_values(const CsrDev& M) {
  if constexpr (std::is_same_v<V, float>) return M.val32;
  else return M.val;
}

/// y_row = sum_k M_row,k x(col_k) for every row, then emit(row, y_row) on one lane. Groups
/// of G lanes per row; warp-uniform loop bounds (every lane takes part in every shuffle).
template <int G, class V, class Fetch, class Emit>
__device__ __forceinline__ void csr_groups(const CsrDev& M, Fetch fetch, Emit emit) {
  const V* __restrict val = csr_values<V>(M);
  constexpr int RPW = 32 / G;
  const int lane = threadIdx.x & 31, gl = lane % G, gw = lane / G;
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5;
  const int nwarps = (gridDim.x * blockDim.x) >> 5;
  for (int base = warp * RPW; base < M.rows; base += nwarps * RPW) {
    const int row = base + gw;
    double y = 0;
    if (row < M.rows)
      for (int k = M.ptr[row] + gl; k < M.ptr[row + 1]; k += G) y += double(val[k]) * double(fetch(M.col[k]));
    y = group_sum<G>(y);
    if (row < M.rows && gl == 0) emit(row, y);
  }
}

/// The same with a block per row: its threads' sums over warps, then through shared
/// memory; block-uniform loop bounds (every thread of the block takes part).
template <class V, class Fetch, class Emit>
__device__ __forceinline__ void csr_blocks(const CsrDev& M, Fetch fetch, Emit emit) {
  __shared__ double part[32];
  const V* __restrict val = csr_values<V>(M);
  const int lane = threadIdx.x & 31, warp = threadIdx.x >> 5, nw = (blockDim.x + 31) >> 5;
  for (int row = blockIdx.x; row < M.rows; row += gridDim.x) {
    double y = 0;
    for (int k = M.ptr[row] + threadIdx.x; k < M.ptr[row + 1]; k += blockDim.x) y += double(val[k]) * double(fetch(M.col[k]));
    y = warp_sum(y);
    if (lane == 0) part[warp] = y;
    __syncthreads();
    if (threadIdx.x == 0) {
      double t = 0;
      for (int w = 0; w < nw; ++w) t += part[w];
      emit(row, t);
    }
    __syncthreads();
  }
}

/// y = M x row by row, emit(row, y_row), with M.lanes lanes a row; V: the solve's precision.
template <class V, class Fetch, class Emit>
__device__ __forceinline__ void csr_rows(const CsrDev& M, Fetch fetch, Emit emit) {
  switch (M.lanes) {
    case kBlockPerRow: csr_blocks<V>(M, fetch, emit); break;
    case 2: csr_groups<2, V>(M, fetch, emit); break;
    default: csr_groups<8, V>(M, fetch, emit); break;
  }
}

/// One coarse level's smoothing (amg::smooth) of L.b into L.x, with a barrier after each
/// product that another row reads. from_zero: L.x is taken as zero; residual: L.r holds
/// L.b - A L.x on return. Ends on a barrier. bar(ph) follows its block-Jacobi passes,
/// bar(ph + 1) its products (PcgPhase). V: the solve's precision (csr_rows).
template <class V, class Bar>
__device__ void mg_smooth(const MgLevelDev& L, bool from_zero, bool residual, Bar bar, int ph) {
  if (from_zero) {
    // r = b; d = c0 D^-1 b; x = d (D^-1 reads its own node's rows of b, complete).
    const double c0 = L.c[0];
    csr_rows<V>(L.Dinv, [&](int j) { return L.b[j]; }, [&](int i, double t) {
      L.r[i] = L.b[i];
      L.d[i] = c0 * t;
      L.x[i] = c0 * t;
    });
  } else {
    csr_rows<V>(L.A, [&](int j) { return L.x[j]; }, [&](int i, double y) { L.r[i] = L.b[i] - y; });
    bar(ph + 1);
    const double c0 = L.c[0];
    csr_rows<V>(L.Dinv, [&](int j) { return L.r[j]; }, [&](int i, double t) {
      L.d[i] = c0 * t;
      L.x[i] += c0 * t;
    });
  }
  bar(ph);
  for (int k = 1; k < L.steps; ++k) {
    csr_rows<V>(L.A, [&](int j) { return L.d[j]; }, [&](int i, double y) { L.r[i] -= y; });
    bar(ph + 1);
    const double ak = L.a[k], ck = L.c[k];
    csr_rows<V>(L.Dinv, [&](int j) { return L.r[j]; }, [&](int i, double t) {
      L.d[i] = ak * L.d[i] + ck * t;
      L.x[i] += L.d[i];
    });
    bar(ph);
  }
  if (residual) {
    csr_rows<V>(L.A, [&](int j) { return L.d[j]; }, [&](int i, double y) { L.r[i] -= y; });
    bar(ph + 1);
  }
}

/// Hierarchy::coarse_cycle: lv[1].x ~ A_1^{-1} lv[1].b, lv[1].b complete on entry. Ends on
/// a barrier. V: the solve's precision (csr_rows).
template <class V, class Bar>
__device__ void mg_coarse_cycle(const MgDev& M, Bar bar) {
  const int L = M.levels;
  for (int k = 1; k + 1 < L; ++k) {
    const MgLevelDev& lv = M.lv[k];
    const int ph = kPhLevel + 4 * (k - 1);
    mg_smooth<V>(lv, true, true, bar, ph);
    const MgLevelDev& next = M.lv[k + 1];
    csr_rows<V>(lv.R, [&](int j) { return lv.r[j]; }, [&](int i, double y) { next.b[i] = y; });
    bar(ph + 2);
  }
  const MgLevelDev& last = M.lv[L - 1];
  csr_rows<V>(M.coarsest_inverse, [&](int j) { return last.b[j]; }, [&](int i, double y) { last.x[i] = y; });
  bar(kPhMgCoarsest);
  for (int k = L - 2; k >= 1; --k) {
    const MgLevelDev& lv = M.lv[k];
    const MgLevelDev& next = M.lv[k + 1];
    const int ph = kPhLevel + 4 * (k - 1);
    csr_rows<V>(lv.P, [&](int j) { return next.x[j]; }, [&](int i, double y) { lv.x[i] += y; });
    bar(ph + 3);
    mg_smooth<V>(lv, false, false, bar, ph);
  }
}

#endif  // __CUDACC__

}  // namespace palpation::sim::cuda
