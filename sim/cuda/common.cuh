// Shared by every stage of the CUDA backends (sim/cuda/*.cu): error checking, the owning
// device array, the launch constants, the data that host and device share per step, and
// the block-wide reductions. Header-only: each .cu file that includes it compiles its own
// copy of the device helpers (whole-program compilation, no device linking).
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace palpation::sim::cuda {

// ---------------------------------------------------------------------------------------
// Error checking: every CUDA call goes through CU(); a failure throws std::runtime_error.

[[noreturn]] inline void cuda_fail(cudaError_t e, const char* what, const char* file, int line) {
  throw std::runtime_error(std::string("CUDA error ") + cudaGetErrorName(e) + " (" + cudaGetErrorString(e) + ") in " +
                           what + " at " + file + ":" + std::to_string(line));
}
#define CU(call)                                                                                       \
  do {                                                                                                 \
    const cudaError_t cu_err_ = (call);                                                                \
    if (cu_err_ != cudaSuccess) ::palpation::sim::cuda::cuda_fail(cu_err_, #call, __FILE__, __LINE__); \
  } while (0)
#define CU_LAUNCHED(name) CU(cudaPeekAtLastError())

/// Owning device allocation.
template <class T>
class DeviceArray {
 public:
  DeviceArray() = default;
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() {
    if (p_) cudaFree(p_);
  }
  void alloc(std::size_t n) {
    if (p_) cudaFree(p_);
    p_ = nullptr;
    n_ = n;
    CU(cudaMalloc(reinterpret_cast<void**>(&p_), std::max<std::size_t>(n, 1) * sizeof(T)));
  }
  /// Copies in stream order and waits: the backend's stream does not synchronise with
  /// the legacy default stream, so a plain cudaMemcpy could race its kernels.
  void upload(const std::vector<T>& v, cudaStream_t s) { upload(v.data(), v.size(), s); }
  void upload(const T* v, std::size_t n, cudaStream_t s) {
    if (n != n_) alloc(n);
    if (n) CU(cudaMemcpyAsync(p_, v, n * sizeof(T), cudaMemcpyHostToDevice, s));
    CU(cudaStreamSynchronize(s));
  }
  /// Copies another array's contents in stream order (device to device; no wait).
  void copy_from(const DeviceArray& o, cudaStream_t s) {
    if (o.n_ != n_) alloc(o.n_);
    if (n_) CU(cudaMemcpyAsync(p_, o.p_, n_ * sizeof(T), cudaMemcpyDeviceToDevice, s));
  }
  /// The contents on the host, in double, copied in stream order (waits for it).
  std::vector<double> to_host_double(cudaStream_t s) const {
    std::vector<T> t(n_);
    if (n_) CU(cudaMemcpyAsync(t.data(), p_, n_ * sizeof(T), cudaMemcpyDeviceToHost, s));
    CU(cudaStreamSynchronize(s));
    if constexpr (std::is_same_v<T, double>)
      return t;
    else
      return std::vector<double>(t.begin(), t.end());
  }
  void zero(cudaStream_t s) {
    if (n_) CU(cudaMemsetAsync(p_, 0, n_ * sizeof(T), s));
  }
  T* get() const { return p_; }
  std::size_t size() const { return n_; }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

// ---------------------------------------------------------------------------------------
// Data shared by host and device.

constexpr int kMaxFingers = 8;
// Per finger: force_raw (3), stiffness (6: xx xy xz yy yz zz), contact point sum (3),
// contact count (1), pad (1).
constexpr int kFingerVals = 14;
constexpr int kBlock = 256;  // threads per block everywhere but the persistent kernel
constexpr int kPcgMaxBlock = 512;  // the persistent kernel: one fat block per SM by default
constexpr int kGroup = 8;    // lanes per block row in the SpMV

/// The phases of the persistent PCG kernel that CudaTuning::phases times (pcg.cu,
/// PhaseClock): the wall time from one grid barrier to the next, summed by the phase that
/// the later barrier ends. The coarse levels' phases follow kPhLevel, four per level k >= 1
/// at kPhLevel + 4 (k - 1): its block-Jacobi passes, its products, the restriction to
/// level k + 1 and the prolongation from it.
enum PcgPhase : int {
  kPhStart,       // r = b - A x of the warm start, and the first preconditioning's reduction
  kPhCgPressure,  // the CG product's nodal pressures
  kPhCgProduct,   // the CG product (with p . q)
  kPhCgUpdate,    // x, r (and z under block-Jacobi, the V-cycle's first pass under the multigrid) with their reductions
  kPhMgJacobi,    // the finest level's block-Jacobi passes (each V-cycle's first in kPhCgUpdate, but the start's)
  kPhMgPressure,  // the finest level's smoothing products: their nodal pressures
  kPhMgProduct,   // ... the products
  kPhMgRestrict,  // the restriction to level 1
  kPhMgProlong,   // the prolongation from level 1
  kPhMgCoarsest,  // the coarsest level's inverse
  kPhMgDot,       // the V-cycle's last pass with r . z
  kPhFinish,      // the state update, rest rule and finger outputs (or a slice's end)
  kPhLevel,
  kPhases = kPhLevel + 4 * 7,  // multigrid.cuh's kMgMaxLevels - 1 coarse levels
};

struct FingerDev {
  double c[3];
  double v[3];
  double r;
  int active;
};
struct FingersArg {
  FingerDev f[kMaxFingers];
  int n;
};

struct StepConsts {
  double h, alpha, beta, ks, ke;
  double g[3];
};

/// Scratch that lives across kernels of one step. Invariant at step entry: facc,
/// detect_done and start_contacts are zero; the start-of-step detection zeroes the
/// reduction ring and the maxima.
struct DevScratch {
  double facc[kMaxFingers][kFingerVals];
  double red[4][4];  // reduction ring of the persistent kernel
  unsigned long long vmax_bits, dvmax_bits;
  unsigned long long v2max_bits, d2max_bits;  // largest |v|^2 and |x - X|^2 over the nodes
  double ke;                                  // kinetic energy, 1/2 sum m |v|^2
  unsigned int detect_done;
  int start_contacts;
  int rested;
  int pad;
  // A solve in slices (PcgArgs::slice): where the last slice stopped, for the next.
  double cg_rz, cg_beta, cg_bnorm, cg_rnorm;
  int cg_it, cg_first, cg_p1, cg_pad;
};

/// What comes back to the host each step.
struct DevResult {
  double finger[kMaxFingers][kFingerVals];
  double vmax, dvmax;
  double v2max, d2max, ke;  // the divergence guard's summary (StepStats::max_speed ...)
  double cg_residual;
  int cg_iterations;
  int start_contacts;
  int rested;
  int unfinished;  // a slice of a solve ended short of its end (PcgArgs::slice)
};

// ---------------------------------------------------------------------------------------
// Small device helpers.

/// Inverse of a 3x3 matrix (row-major).
template <class T>
__device__ __forceinline__ void invert3(const T m[9], T inv[9]) {
  // Cofactor inverse (as Eigen's 3x3 inverse); a non-finite result becomes zero.
  const T c00 = m[4] * m[8] - m[5] * m[7];
  const T c01 = m[5] * m[6] - m[3] * m[8];
  const T c02 = m[3] * m[7] - m[4] * m[6];
  const T det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  const T id = T(1) / det;
  inv[0] = c00 * id;
  inv[1] = (m[2] * m[7] - m[1] * m[8]) * id;
  inv[2] = (m[1] * m[5] - m[2] * m[4]) * id;
  inv[3] = c01 * id;
  inv[4] = (m[0] * m[8] - m[2] * m[6]) * id;
  inv[5] = (m[2] * m[3] - m[0] * m[5]) * id;
  inv[6] = c02 * id;
  inv[7] = (m[1] * m[6] - m[0] * m[7]) * id;
  inv[8] = (m[0] * m[4] - m[1] * m[3]) * id;
  bool finite = true;
  for (int j = 0; j < 9; ++j) finite = finite && isfinite(inv[j]);
  if (!finite)
    for (int j = 0; j < 9; ++j) inv[j] = T(0);
}

/// The sum of v over the G lanes of each group (G a power of two dividing 32: lanes
/// gG .. gG + G - 1), on every lane of the group; every lane of the warp must call it.
template <int G, class T>
__device__ __forceinline__ T group_sum(T v) {
#pragma unroll
  for (int off = G / 2; off > 0; off >>= 1) v += __shfl_xor_sync(0xffffffffu, v, off);
  return v;
}

__device__ __forceinline__ double warp_sum(double v) { return group_sum<32>(v); }

/// Sums K values over the block and atomically adds them to dst[0..K). All threads call.
template <int K>
__device__ void block_sum_atomic(double (&v)[K], double* dst) {
  __shared__ double sh[K][32];
  const int lane = threadIdx.x & 31, warp = threadIdx.x >> 5, nw = (blockDim.x + 31) >> 5;
#pragma unroll
  for (int k = 0; k < K; ++k) v[k] = warp_sum(v[k]);
  if (lane == 0)
#pragma unroll
    for (int k = 0; k < K; ++k) sh[k][warp] = v[k];
  __syncthreads();
  if (warp == 0) {
#pragma unroll
    for (int k = 0; k < K; ++k) {
      double t = lane < nw ? sh[k][lane] : 0.0;
      t = warp_sum(t);
      if (lane == 0) atomicAdd(dst + k, t);
    }
  }
  __syncthreads();
}

/// Max of non-negative values over the block, atomically into the bit pattern at dst
/// (IEEE order of non-negative doubles equals the order of their bit patterns; NaN wins).
template <int K>
__device__ void block_max_atomic(double (&v)[K], unsigned long long* const (&dst)[K]) {
  __shared__ double sh[K][32];
  const int lane = threadIdx.x & 31, warp = threadIdx.x >> 5, nw = (blockDim.x + 31) >> 5;
#pragma unroll
  for (int k = 0; k < K; ++k) {
    // A NaN must survive the reduction: fmax drops NaN, so carry it as +inf's successor.
    double x = isnan(v[k]) ? __longlong_as_double(0x7ff8000000000000ll) : v[k];
    unsigned long long bits = static_cast<unsigned long long>(__double_as_longlong(x));
    for (int o = 16; o > 0; o >>= 1) {
      const unsigned long long other = __shfl_xor_sync(0xffffffffu, bits, o);
      bits = other > bits ? other : bits;
    }
    if (lane == 0) sh[k][warp] = __longlong_as_double(static_cast<long long>(bits));
  }
  __syncthreads();
  if (warp == 0) {
#pragma unroll
    for (int k = 0; k < K; ++k) {
      unsigned long long bits =
          lane < nw ? static_cast<unsigned long long>(__double_as_longlong(sh[k][lane])) : 0ull;
      for (int o = 16; o > 0; o >>= 1) {
        const unsigned long long other = __shfl_xor_sync(0xffffffffu, bits, o);
        bits = other > bits ? other : bits;
      }
      if (lane == 0) atomicMax(dst[k], bits);
    }
  }
  __syncthreads();
}

__device__ __forceinline__ double bits_to_double(unsigned long long b) {
  return __longlong_as_double(static_cast<long long>(b));
}

// ---------------------------------------------------------------------------------------
// The step's scratch and result (written by the detection, the PCG kernel and the baseline).

/// Zeroes what one step accumulates (before the PCG kernel runs).
__device__ __forceinline__ void zero_step_scratch(DevScratch* s) {
  for (int r = 0; r < 4; ++r)
    for (int j = 0; j < 4; ++j) s->red[r][j] = 0.0;
  s->vmax_bits = 0ull;
  s->dvmax_bits = 0ull;
  s->v2max_bits = 0ull;
  s->d2max_bits = 0ull;
  s->ke = 0.0;
  s->rested = 0;
}

/// Copies the finger sums and step results to the host-mapped result, resets the scratch.
/// Called by one block after every block's sums reached facc.
inline __device__ void finalize_result(DevScratch* scr, DevResult* res, bool end_of_step) {
  __threadfence();
  volatile double* facc = &scr->facc[0][0];
  for (int t = threadIdx.x; t < kMaxFingers * kFingerVals; t += blockDim.x) {
    (&res->finger[0][0])[t] = facc[t];
    facc[t] = 0.0;
  }
  if (threadIdx.x == 0) {
    volatile DevScratch* sc = scr;
    res->start_contacts = sc->start_contacts;
    res->vmax = bits_to_double(sc->vmax_bits);
    res->dvmax = bits_to_double(sc->dvmax_bits);
    res->v2max = bits_to_double(sc->v2max_bits);
    res->d2max = bits_to_double(sc->d2max_bits);
    res->ke = sc->ke;
    res->rested = sc->rested;
    sc->detect_done = 0u;
    if (end_of_step) sc->start_contacts = 0;  // the next step counts afresh
  }
}

}  // namespace palpation::sim::cuda
