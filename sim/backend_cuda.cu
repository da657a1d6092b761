// CUDA backends: "cuda" (fast) and "cuda-csr" (textbook baseline). backend_cpu.cpp is the
// specification; this file does the same step on the GPU (docs/gpu-notes.md has the
// design, the alternatives measured and the numbers).
//
// Per step, in one stream (three launches and one synchronisation when in motion):
//   k_element   per element: F, rotation (warm-started quaternion), r_a = R g_a and the
//               element's right-hand-side matrix Q (elastic force and K v folded in), one
//               compact record per element; extra blocks do the contact detection at
//               start-of-step positions against the end-of-step fingers.
//   k_assemble  one warp per block row: stages the records of the elements around the node
//               in shared memory and gathers its 3x3 blocks, the block-Jacobi inverse of
//               its diagonal and its right-hand side (no atomics, every output written once).
//   k_pcg       one persistent cooperative kernel: the PCG of solve_cg.h (warm start,
//               restart and stopping rules), two grid barriers per iteration (the search
//               direction is formed inside the SpMV), rows held in registers when they fit;
//               then v += dv, x += h v, the rest rule, and the finger outputs at the end state.
//   The kernels write the small result (finger sums, statistics) into mapped pinned memory:
//   no copy is queued; the host synchronises once.
// At rest with no contact only k_detect runs (GPU detection, the result read the same way).
// "cuda-csr" shares k_element and k_assemble and replaces k_pcg by the host-driven
// cuSPARSE/cuBLAS loop, k_update, k_rest and k_detect (finish).
//
// Matrix layout: the blocks of block-row i (k0 = row_ptr[i], len blocks) are stored so
// that the whole matrix is also a valid scalar CSR matrix (rows 3i..3i+2, columns sorted):
// value (k, r, c) at 9 k0 + r (3 len) + 3 (k - k0) + c. The fast SpMV reads it with G
// lanes per block row; cuSPARSE reads the same array as CSR.
#include "backend_cuda.h"

#include <cooperative_groups.h>
#include <cuda_runtime.h>

#ifdef PALPATION_HAVE_CUSPARSE
#include <cublas_v2.h>
#include <cusparse.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace palpation::sim {

namespace {

namespace coop = cooperative_groups;

// ---------------------------------------------------------------------------------------
// Error checking: every CUDA call goes through CU(); a failure throws std::runtime_error.

[[noreturn]] void cuda_fail(cudaError_t e, const char* what, const char* file, int line) {
  throw std::runtime_error(std::string("CUDA error ") + cudaGetErrorName(e) + " (" + cudaGetErrorString(e) + ") in " +
                           what + " at " + file + ":" + std::to_string(line));
}
#define CU(call)                                                          \
  do {                                                                    \
    const cudaError_t cu_err_ = (call);                                   \
    if (cu_err_ != cudaSuccess) cuda_fail(cu_err_, #call, __FILE__, __LINE__); \
  } while (0)
#define CU_LAUNCHED(name) CU(cudaPeekAtLastError())

#ifdef PALPATION_HAVE_CUSPARSE
#define CUSP(call)                                                                                      \
  do {                                                                                                  \
    const cusparseStatus_t st_ = (call);                                                                \
    if (st_ != CUSPARSE_STATUS_SUCCESS)                                                                 \
      throw std::runtime_error(std::string("cuSPARSE error ") + cusparseGetErrorString(st_) + " in " #call); \
  } while (0)
#define CUBL(call)                                                                                     \
  do {                                                                                                 \
    const cublasStatus_t st_ = (call);                                                                 \
    if (st_ != CUBLAS_STATUS_SUCCESS)                                                                  \
      throw std::runtime_error(std::string("cuBLAS error ") + std::to_string(int(st_)) + " in " #call); \
  } while (0)
#endif

int env_int(const char* name, int fallback) {
  const char* s = std::getenv(name);
  if (!s || !*s) return fallback;
  return std::atoi(s);
}
std::string env_str(const char* name, const std::string& fallback) {
  const char* s = std::getenv(name);
  return (s && *s) ? std::string(s) : fallback;
}

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
  unsigned int detect_done;
  int start_contacts;
  int rested;
  int pad;
};

/// What comes back to the host each step.
struct DevResult {
  double finger[kMaxFingers][kFingerVals];
  double vmax, dvmax;
  double cg_residual;
  int cg_iterations;
  int start_contacts;
  int rested;
  int pad;
};

// ---------------------------------------------------------------------------------------
// Small device helpers.

__device__ __forceinline__ double warp_sum(double v) {
  for (int o = 16; o > 0; o >>= 1) v += __shfl_xor_sync(0xffffffffu, v, o);
  return v;
}

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
// Contact detection (contact_sphere.h + backend_cpu.cpp add_contacts / finger_outputs).

template <class T>
struct DetectArgs {
  int ntri;
  const int* tri;        // (ntri x 3) surface triangles (outward), node indices
  const int* node_surf;  // (nnode) surface-node index of each node or -1
  const int* dof;        // (nnode) free index or -1
  int nsurf;             // surface nodes (rows of cA, cb)
  const T* x;            // (nnode x 3)
  const T* v;            // (nnode x 3)
  double* cA;            // (nsurf x 6) contact matrix sum_k w_k (h^2 ks + h ke) n n^T; zero at step entry
  double* cb;            // (nsurf x 3) contact rhs; zero at step entry
  DevScratch* scr;
  DevResult* res;        // mapped host memory
};

/// Closest point to p on triangle (a, b, c) and its barycentric weights: Ericson, Real-Time
/// Collision Detection 5.1.5, as contact::closest_on_triangle.
__device__ void closest_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                    double q[3], double w[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto set = [&](double w0, double w1, double w2) {
    w[0] = w0;
    w[1] = w1;
    w[2] = w2;
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    set(1, 0, 0);
    for (int k = 0; k < 3; ++k) q[k] = a[k];
    return;
  }
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    set(0, 1, 0);
    for (int k = 0; k < 3; ++k) q[k] = b[k];
    return;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    set(1 - v, v, 0);
    for (int k = 0; k < 3; ++k) q[k] = a[k] + v * ab[k];
    return;
  }
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    set(0, 0, 1);
    for (int k = 0; k < 3; ++k) q[k] = c[k];
    return;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    set(1 - t, 0, t);
    for (int k = 0; k < 3; ++k) q[k] = a[k] + t * ac[k];
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    set(0, 1 - t, t);
    for (int k = 0; k < 3; ++k) q[k] = b[k] + t * (c[k] - b[k]);
    return;
  }
  const double den = 1.0 / (va + vb + vc);
  const double v = vb * den, u = vc * den;
  set(1 - v - u, v, u);
  for (int k = 0; k < 3; ++k) q[k] = a[k] + ab[k] * v + ac[k] * u;
}

/// Tests surface triangles t = first, first + stride, ... against the fingers
/// (contact::detect): each penetrated triangle is one contact at the closest point, its
/// force F = k_s d + k_e d_dot along n shared by the triangle's nodes with the
/// barycentric weights (backend_cpu.cpp add_contacts: lumped on the diagonal blocks).
/// system: add the per-node contact terms of the linear system (atomics: contacts are
/// few) and count contacts (start of step). sacc != nullptr: per-finger sums (shared).
template <class T>
__device__ void detect_nodes(const DetectArgs<T>& a, const FingersArg& F, const StepConsts& k, bool system,
                             double* sacc, int* scount, int first, int stride) {
  const double h = k.h;
  for (int t = first; t < a.ntri; t += stride) {
    const int nd[3] = {a.tri[3 * t], a.tri[3 * t + 1], a.tri[3 * t + 2]};
    double P[3][3];
    for (int m = 0; m < 3; ++m)
      for (int c = 0; c < 3; ++c) P[m][c] = double(a.x[3 * nd[m] + c]);
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = fmin(fmin(P[0][c], P[1][c]), P[2][c]);
      hi[c] = fmax(fmax(P[0][c], P[1][c]), P[2][c]);
    }
    int count = 0;
    for (int f = 0; f < F.n; ++f) {
      const FingerDev& fi = F.f[f];
      if (!fi.active || !(fi.r > 0)) continue;
      const double r = fi.r;
      bool out = false;
      for (int c = 0; c < 3; ++c) out = out || fi.c[c] + r < lo[c] || fi.c[c] - r > hi[c];
      if (out) continue;
      double q[3], w[3];
      closest_on_triangle(fi.c, P[0], P[1], P[2], q, w);
      const double d0 = q[0] - fi.c[0], d1 = q[1] - fi.c[1], d2 = q[2] - fi.c[2];
      const double dist2 = d0 * d0 + d1 * d1 + d2 * d2;
      if (dist2 >= r * r) continue;
      const double dist = sqrt(dist2);
      double n0, n1, n2;
      if (dist > 1e-12) {
        n0 = d0 / dist;
        n1 = d1 / dist;
        n2 = d2 / dist;
      } else {  // the centre on the surface itself: along the inward normal
        const double e1[3] = {P[1][0] - P[0][0], P[1][1] - P[0][1], P[1][2] - P[0][2]};
        const double e2[3] = {P[2][0] - P[0][0], P[2][1] - P[0][1], P[2][2] - P[0][2]};
        const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                     cz = e1[0] * e2[1] - e1[1] * e2[0];
        const double l = sqrt(cx * cx + cy * cy + cz * cz);
        n0 = -cx / l;
        n1 = -cy / l;
        n2 = -cz / l;
      }
      const double depth = r - dist;
      // Area weight of the penalty (contact::area_scale): triangle area / (pi r^2).
      double sc;
      {
        const double e1[3] = {P[1][0] - P[0][0], P[1][1] - P[0][1], P[1][2] - P[0][2]};
        const double e2[3] = {P[2][0] - P[0][0], P[2][1] - P[0][1], P[2][2] - P[0][2]};
        const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                     cz = e1[0] * e2[1] - e1[1] * e2[0];
        sc = 0.5 * sqrt(cx * cx + cy * cy + cz * cz) / (M_PI * r * r);
      }
      const double ks = sc * k.ks, ke = sc * k.ke;
      double vp[3] = {0, 0, 0};
      for (int m = 0; m < 3; ++m)
        for (int c = 0; c < 3; ++c) vp[c] += w[m] * double(a.v[3 * nd[m] + c]);
      const double rate = -(n0 * (vp[0] - fi.v[0]) + n1 * (vp[1] - fi.v[1]) + n2 * (vp[2] - fi.v[2]));
      const double fpen = ks * depth + ke * rate;
      const double mag = fpen > 0 ? fpen : 0.0;
      ++count;
      if (sacc) {
        double* acc = sacc + f * kFingerVals;
        atomicAdd(acc + 0, -mag * n0);
        atomicAdd(acc + 1, -mag * n1);
        atomicAdd(acc + 2, -mag * n2);
        atomicAdd(acc + 3, -ks * n0 * n0);
        atomicAdd(acc + 4, -ks * n0 * n1);
        atomicAdd(acc + 5, -ks * n0 * n2);
        atomicAdd(acc + 6, -ks * n1 * n1);
        atomicAdd(acc + 7, -ks * n1 * n2);
        atomicAdd(acc + 8, -ks * n2 * n2);
        atomicAdd(acc + 9, q[0]);
        atomicAdd(acc + 10, q[1]);
        atomicAdd(acc + 11, q[2]);
        atomicAdd(acc + 12, 1.0);
      }
      if (system && mag > 0) {
        const double cst = h * h * ks + h * ke, hks = h * ks;
        for (int m = 0; m < 3; ++m) {
          const int node = nd[m];
          if (a.dof[node] < 0 || w[m] <= 0) continue;
          const int s = a.node_surf[node];
          const double v0 = double(a.v[3 * node]), v1 = double(a.v[3 * node + 1]), v2 = double(a.v[3 * node + 2]);
          // Linearised: f(x + h v') ~ f - h ks n n^T v', damping ke n n^T on v'; weight w_m.
          const double nv = n0 * v0 + n1 * v1 + n2 * v2;
          const double hw = h * w[m];
          atomicAdd(a.cb + 3 * s, hw * (mag * n0 - hks * n0 * nv));
          atomicAdd(a.cb + 3 * s + 1, hw * (mag * n1 - hks * n1 * nv));
          atomicAdd(a.cb + 3 * s + 2, hw * (mag * n2 - hks * n2 * nv));
          const double cw = w[m] * cst;
          atomicAdd(a.cA + 6 * s, cw * n0 * n0);
          atomicAdd(a.cA + 6 * s + 1, cw * n0 * n1);
          atomicAdd(a.cA + 6 * s + 2, cw * n0 * n2);
          atomicAdd(a.cA + 6 * s + 3, cw * n1 * n1);
          atomicAdd(a.cA + 6 * s + 4, cw * n1 * n2);
          atomicAdd(a.cA + 6 * s + 5, cw * n2 * n2);
        }
      }
    }
    if (system && count) atomicAdd(scount, count);
  }
}

/// Zeroes the contact terms for the next step (after the assembly has read them).
template <class T>
__device__ void zero_contact_terms(const DetectArgs<T>& a, int first, int stride) {
  for (int j = first; j < 9 * a.nsurf; j += stride) {
    if (j < 6 * a.nsurf)
      a.cA[j] = 0.0;
    else
      a.cb[j - 6 * a.nsurf] = 0.0;
  }
}

/// Zeroes what one step accumulates (before the PCG kernel runs).
__device__ __forceinline__ void zero_step_scratch(DevScratch* s) {
  for (int r = 0; r < 4; ++r)
    for (int j = 0; j < 4; ++j) s->red[r][j] = 0.0;
  s->vmax_bits = 0ull;
  s->dvmax_bits = 0ull;
  s->rested = 0;
}

/// Copies the finger sums and step results to the host-mapped result, resets the scratch.
/// Called by one block after every block's sums reached facc.
__device__ void finalize_result(DevScratch* scr, DevResult* res, bool end_of_step) {
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
    res->rested = sc->rested;
    sc->detect_done = 0u;
    if (end_of_step) sc->start_contacts = 0;  // the next step counts afresh
  }
}

/// Stand-alone detection. start = 1: start of step (system terms, contact count, zero the
/// step scratch) and finger sums (the outputs when the step is skipped at rest).
/// start = 0: finger outputs of the end state (baseline path). The last block to finish
/// writes the result.
template <class T>
__global__ void __launch_bounds__(kBlock) k_detect(DetectArgs<T> a, FingersArg F, StepConsts k, int start) {
  __shared__ double sacc[kMaxFingers * kFingerVals];
  __shared__ int scount;
  __shared__ bool last;
  for (int t = threadIdx.x; t < kMaxFingers * kFingerVals; t += blockDim.x) sacc[t] = 0.0;
  if (threadIdx.x == 0) scount = 0;
  if (start && blockIdx.x == 0 && threadIdx.x == 0) zero_step_scratch(a.scr);
  __syncthreads();
  detect_nodes(a, F, k, start != 0, sacc, &scount, blockIdx.x * blockDim.x + threadIdx.x, gridDim.x * blockDim.x);
  if (!start) zero_contact_terms(a, blockIdx.x * blockDim.x + threadIdx.x, gridDim.x * blockDim.x);
  __syncthreads();
  for (int t = threadIdx.x; t < F.n * kFingerVals; t += blockDim.x)
    if (sacc[t] != 0.0) atomicAdd(&a.scr->facc[0][0] + t, sacc[t]);
  if (threadIdx.x == 0 && scount) atomicAdd(&a.scr->start_contacts, scount);
  __threadfence();
  __syncthreads();
  if (threadIdx.x == 0) last = atomicAdd(&a.scr->detect_done, 1u) == gridDim.x - 1;
  __syncthreads();
  if (last) finalize_result(a.scr, a.res, !start);
}

// ---------------------------------------------------------------------------------------
// Per-element corotation (fem_corotational.h, line for line).

template <class T>
struct Quat {
  T w, x, y, z;
};

template <class T>
__device__ __forceinline__ void quat_to_mat(const Quat<T>& q, T R[9]) {
  // Eigen's Quaternion::toRotationMatrix.
  const T tx = T(2) * q.x, ty = T(2) * q.y, tz = T(2) * q.z;
  const T twx = tx * q.w, twy = ty * q.w, twz = tz * q.w;
  const T txx = tx * q.x, txy = ty * q.x, txz = tz * q.x;
  const T tyy = ty * q.y, tyz = tz * q.y, tzz = tz * q.z;
  R[0] = T(1) - (tyy + tzz);
  R[1] = txy - twz;
  R[2] = txz + twy;
  R[3] = txy + twz;
  R[4] = T(1) - (txx + tzz);
  R[5] = tyz - twx;
  R[6] = txz - twy;
  R[7] = tyz + twx;
  R[8] = T(1) - (txx + tyy);
}

template <class T>
__device__ __forceinline__ T rot_tol() {
  return sizeof(T) == sizeof(double) ? T(1e-9) : T(1e-6);
}

/// extract_rotation of fem_corotational.h (Mueller et al. 2016), A row-major. Same
/// iteration, threshold and Taylor branch; the divisions are reciprocals and the stopping
/// and branch tests compare squares (w < t <=> w^2 < t^2), which removes most of the
/// long-latency double-precision operations from this dependent chain.
template <class T>
__device__ void extract_rotation(const T A[9], Quat<T>& q) {
  constexpr int kIterations = 4;  // fem::kRotationIterations
  const T tol2 = rot_tol<T>() * rot_tol<T>();
  for (int it = 0; it < kIterations; ++it) {
    T R[9];
    quat_to_mat(q, R);
    T on0 = 0, on1 = 0, on2 = 0, den = 0;
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      const T r0 = R[c], r1 = R[3 + c], r2 = R[6 + c];
      const T a0 = A[c], a1 = A[3 + c], a2 = A[6 + c];
      on0 += r1 * a2 - r2 * a1;
      on1 += r2 * a0 - r0 * a2;
      on2 += r0 * a1 - r1 * a0;
      den += r0 * a0 + r1 * a1 + r2 * a2;
    }
    const T inv = T(1) / (fabs(den) + T(1e-9));
    const T o0 = on0 * inv, o1 = on1 * inv, o2 = on2 * inv;
    const T w2 = o0 * o0 + o1 * o1 + o2 * o2;
    if (w2 < tol2) break;
    T c, s;
    if (w2 < T(1e-4)) {  // w < 1e-2: Taylor series of cos(w/2), sin(w/2)/w
      c = T(1) - w2 * T(0.125) + w2 * w2 * (T(1) / T(384));
      s = T(0.5) - w2 * (T(1) / T(48));
    } else {
      const T w = sqrt(w2);
      c = cos(T(0.5) * w);
      s = sin(T(0.5) * w) / w;
    }
    const T dw = c, dx = s * o0, dy = s * o1, dz = s * o2;
    Quat<T> n;
    n.w = dw * q.w - dx * q.x - dy * q.y - dz * q.z;
    n.x = dw * q.x + dx * q.w + dy * q.z - dz * q.y;
    n.y = dw * q.y - dx * q.z + dy * q.w + dz * q.x;
    n.z = dw * q.z + dx * q.y - dy * q.x + dz * q.w;
    const T nn = n.w * n.w + n.x * n.x + n.y * n.y + n.z * n.z;
    if (nn > T(0)) {
      const T in = rsqrt(nn);
      n.w *= in;
      n.x *= in;
      n.y *= in;
      n.z *= in;
    }
    q = n;
  }
}

// Element record (kRec T): r_a = R g_a (12), V lambda, V mu, and Q (6: xx xy xz yy yz zz),
// the symmetric matrix with which the element adds Q r_a to the right-hand side of node a:
//   h (f_a - (beta + h) (K v)_a) = -h V (R S R^T + (beta + h) Sv) r_a = Q r_a,
// since f_a = -V R S g_a = -V (R S R^T) r_a and (K v)_a = V Sv r_a (fem_corotational.h).
constexpr int kRec = 20;
constexpr int kElemBlock = 128;

template <class T>
struct ElementArgs {
  int ne;
  const int4* tets;
  const T* grad;    // (ne x 12) g_0..g_3
  const T* vol;     // (ne)
  const T* lambda;  // (ne)
  const T* mu;      // (ne)
  T* quat;          // (ne x 4) w x y z
  const T* x;
  const T* v;
  T* rec;           // (ne x kRec)
  T h, beta;
  int elem_blocks;  // blocks [0, elem_blocks) do elements; the others detect contacts
};

/// Elements, and (in the extra blocks) the start-of-step contact detection: the two are
/// independent and both feed the assembly, so one launch does both.
template <class T>
__global__ void __launch_bounds__(kElemBlock) k_element(ElementArgs<T> a, DetectArgs<T> d, FingersArg F, StepConsts k) {
  if (int(blockIdx.x) >= a.elem_blocks) {
    const int db = blockIdx.x - a.elem_blocks, nblk = gridDim.x - a.elem_blocks;
    if (db == 0 && threadIdx.x == 0) zero_step_scratch(d.scr);
    __shared__ int scount;
    if (threadIdx.x == 0) scount = 0;
    __syncthreads();
    detect_nodes(d, F, k, true, nullptr, &scount, db * blockDim.x + threadIdx.x, nblk * blockDim.x);
    __syncthreads();
    if (threadIdx.x == 0 && scount) atomicAdd(&d.scr->start_contacts, scount);
    return;
  }
  const int e = blockIdx.x * blockDim.x + threadIdx.x;
  if (e >= a.ne) return;
  const int4 t = __ldg(a.tets + e);
  const int nodes[4] = {t.x, t.y, t.z, t.w};
  T g[12], xx[12], vv[12];
#pragma unroll
  for (int j = 0; j < 12; ++j) g[j] = __ldg(a.grad + 12 * std::size_t(e) + j);
#pragma unroll
  for (int n = 0; n < 4; ++n)
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      xx[3 * n + c] = a.x[3 * nodes[n] + c];
      vv[3 * n + c] = a.v[3 * nodes[n] + c];
    }
  // F = sum_a x_a g_a^T (row-major).
  T F9[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) {
      T s = xx[i] * g[j];
#pragma unroll
      for (int n = 1; n < 4; ++n) s += xx[3 * n + i] * g[3 * n + j];
      F9[3 * i + j] = s;
    }
  Quat<T> q{a.quat[4 * e], a.quat[4 * e + 1], a.quat[4 * e + 2], a.quat[4 * e + 3]};
  extract_rotation(F9, q);
  a.quat[4 * e] = q.w;
  a.quat[4 * e + 1] = q.x;
  a.quat[4 * e + 2] = q.y;
  a.quat[4 * e + 3] = q.z;
  T R[9];
  quat_to_mat(q, R);
  const T V = a.vol[e], lam = a.lambda[e], mu = a.mu[e];
  // H = R^T F - I, S = 2 mu sym(H) + lambda tr(H) I.
  T H[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j)
      H[3 * i + j] = R[i] * F9[j] + R[3 + i] * F9[3 + j] + R[6 + i] * F9[6 + j] - (i == j ? T(1) : T(0));
  T S[9];
  {
    const T tr = H[0] + H[4] + H[8];
#pragma unroll
    for (int i = 0; i < 3; ++i)
#pragma unroll
      for (int j = 0; j < 3; ++j)
        S[3 * i + j] = T(2) * mu * (T(0.5) * (H[3 * i + j] + H[3 * j + i])) + (i == j ? lam * tr : T(0));
  }
  T r[12];
#pragma unroll
  for (int n = 0; n < 4; ++n)
#pragma unroll
    for (int i = 0; i < 3; ++i) r[3 * n + i] = R[3 * i] * g[3 * n] + R[3 * i + 1] * g[3 * n + 1] + R[3 * i + 2] * g[3 * n + 2];
  // Sw = R S R^T (world-frame stress).
  T RS[9], Sw[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) RS[3 * i + j] = R[3 * i] * S[j] + R[3 * i + 1] * S[3 + j] + R[3 * i + 2] * S[6 + j];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) Sw[3 * i + j] = RS[3 * i] * R[3 * j] + RS[3 * i + 1] * R[3 * j + 1] + RS[3 * i + 2] * R[3 * j + 2];
  // K v: P = sum_b v_b r_b^T, Sv = sigma(P).
  T P[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) {
      T s = vv[i] * r[j];
#pragma unroll
      for (int n = 1; n < 4; ++n) s += vv[3 * n + i] * r[3 * n + j];
      P[3 * i + j] = s;
    }
  const T trP = P[0] + P[4] + P[8];
  const T c1 = a.beta + a.h, hV = a.h * V;
  auto q_ij = [&](int i, int j) {
    const T sv = T(2) * mu * (T(0.5) * (P[3 * i + j] + P[3 * j + i])) + (i == j ? lam * trP : T(0));
    return -hV * (T(0.5) * (Sw[3 * i + j] + Sw[3 * j + i]) + c1 * sv);
  };
  T out[kRec];
#pragma unroll
  for (int j = 0; j < 12; ++j) out[j] = r[j];
  out[12] = V * lam;
  out[13] = V * mu;
  out[14] = q_ij(0, 0);
  out[15] = q_ij(0, 1);
  out[16] = q_ij(0, 2);
  out[17] = q_ij(1, 1);
  out[18] = q_ij(1, 2);
  out[19] = q_ij(2, 2);
  T* dst = a.rec + std::size_t(kRec) * e;
  if constexpr (sizeof(T) == 8) {
    double2* d2 = reinterpret_cast<double2*>(dst);  // kRec * 8 B = 160 B: 16-byte aligned
#pragma unroll
    for (int j = 0; j < kRec / 2; ++j) d2[j] = make_double2(out[2 * j], out[2 * j + 1]);
  } else {
    float4* d4 = reinterpret_cast<float4*>(dst);  // 80 B
#pragma unroll
    for (int j = 0; j < kRec / 4; ++j) d4[j] = make_float4(out[4 * j], out[4 * j + 1], out[4 * j + 2], out[4 * j + 3]);
  }
}

// ---------------------------------------------------------------------------------------
// Assembly by gathering: one warp per block row.

template <class T>
struct AssembleArgs {
  int nf;
  const int* row_ptr;   // (nf + 1)
  const int* col_node;  // (nb) node of each block's column
  const int* inc_ptr;   // (nf + 1) incidences of each free node
  const int* inc;       // e << 2 | a
  const int4* tets;
  const T* rec;
  const int* free_nodes;
  const int* free_surf;  // (nf) surface index or -1
  const T* mass;         // (nnode)
  const T* v;
  const double* cA;
  const double* cb;
  T* vals;               // (9 nb) system matrix, CSR-compatible layout
  T* precond;            // (nf x 9)
  T* b;                  // (nf x 3)
  T kscale, mscale, h, alpha;
  T g0, g1, g2;
};

template <class T>
__device__ void invert3(const T m[9], T inv[9]) {
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

/// Block row i is one warp: lane l owns block k0 + l (rows longer than 32 blocks take more
/// passes). The warp stages the records of the elements around node i in shared memory
/// (up to 32 at a time, all loads issued together, coalesced), then walks them: the lane
/// whose column node is element node b adds
///   K_ab = V (lambda r_a r_b^T + mu r_b r_a^T + mu (r_a . r_b) I)     (r_a . r_b = g_a . g_b)
/// and lanes 0..2 add component c of Q r_a to the right-hand side. Every output is
/// written once: no atomics, no element colouring.
template <class T>
__global__ void __launch_bounds__(kBlock) k_assemble(AssembleArgs<T> a) {
  constexpr int kWarps = kBlock / 32;
  __shared__ T srec[kWarps][32][kRec];
  __shared__ int4 stet[kWarps][32];
  __shared__ int sinc[kWarps][32];
  const int lane = threadIdx.x & 31, w = threadIdx.x >> 5;
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5;
  const int nwarps = (gridDim.x * blockDim.x) >> 5;
  for (int i = warp; i < a.nf; i += nwarps) {
    const int k0 = a.row_ptr[i], len = a.row_ptr[i + 1] - k0, len3 = 3 * len;
    const int node_i = a.free_nodes[i];
    const int l0 = a.inc_ptr[i], l1 = a.inc_ptr[i + 1];
    for (int base = 0; base < len; base += 32) {
      const int kk = base + lane;
      const int jnode = kk < len ? a.col_node[k0 + kk] : -1;
      T acc[9];
#pragma unroll
      for (int j = 0; j < 9; ++j) acc[j] = T(0);
      T rhs = 0;
      for (int c0 = l0; c0 < l1; c0 += 32) {
        const int cnt = min(32, l1 - c0);
        __syncwarp();
        if (lane < cnt) sinc[w][lane] = __ldg(a.inc + c0 + lane);
        __syncwarp();
        if (lane < cnt) stet[w][lane] = __ldg(a.tets + (sinc[w][lane] >> 2));
        for (int idx = lane; idx < cnt * kRec; idx += 32) {
          const int j = idx / kRec, comp = idx - j * kRec;
          srec[w][j][comp] = a.rec[std::size_t(kRec) * (sinc[w][j] >> 2) + comp];
        }
        __syncwarp();
#pragma unroll 2
        for (int j = 0; j < cnt; ++j) {
          const int ia = sinc[w][j] & 3;
          const int4 t = stet[w][j];
          const T* rec = srec[w][j];
          const int ib = t.x == jnode ? 0 : t.y == jnode ? 1 : t.z == jnode ? 2 : t.w == jnode ? 3 : -1;
          const T ra0 = rec[3 * ia], ra1 = rec[3 * ia + 1], ra2 = rec[3 * ia + 2];
          if (ib >= 0) {
            const T rb0 = rec[3 * ib], rb1 = rec[3 * ib + 1], rb2 = rec[3 * ib + 2];
            const T lv = rec[12], mv = rec[13];
            const T ra[3] = {ra0, ra1, ra2}, rb[3] = {rb0, rb1, rb2};
#pragma unroll
            for (int r = 0; r < 3; ++r)
#pragma unroll
              for (int c = 0; c < 3; ++c) acc[3 * r + c] += lv * ra[r] * rb[c] + mv * rb[r] * ra[c];
            const T d = mv * (ra0 * rb0 + ra1 * rb1 + ra2 * rb2);
            acc[0] += d;
            acc[4] += d;
            acc[8] += d;
          }
          if (base == 0 && lane < 3) {
            // Q row `lane` (symmetric, stored xx xy xz yy yz zz) times r_a.
            const int q0 = lane == 0 ? 14 : (lane == 1 ? 15 : 16);
            const int q1 = lane == 0 ? 15 : (lane == 1 ? 17 : 18);
            const int q2 = lane == 0 ? 16 : (lane == 1 ? 18 : 19);
            rhs += rec[q0] * ra0 + rec[q1] * ra1 + rec[q2] * ra2;
          }
        }
      }
      if (kk < len) {
#pragma unroll
        for (int j = 0; j < 9; ++j) acc[j] *= a.kscale;
        if (jnode == node_i) {
          const T mm = a.mscale * a.mass[node_i];
          acc[0] += mm;
          acc[4] += mm;
          acc[8] += mm;
          const int s = a.free_surf[i];
          if (s >= 0) {
            const double* c = a.cA + 6 * s;
            acc[0] += T(c[0]);
            acc[1] += T(c[1]);
            acc[2] += T(c[2]);
            acc[3] += T(c[1]);
            acc[4] += T(c[3]);
            acc[5] += T(c[4]);
            acc[6] += T(c[2]);
            acc[7] += T(c[4]);
            acc[8] += T(c[5]);
          }
          T inv[9];
          invert3(acc, inv);
#pragma unroll
          for (int j = 0; j < 9; ++j) a.precond[9 * i + j] = inv[j];
        }
        T* dst = a.vals + 9 * std::size_t(k0) + 3 * kk;
#pragma unroll
        for (int r = 0; r < 3; ++r)
#pragma unroll
          for (int c = 0; c < 3; ++c) dst[r * len3 + c] = acc[3 * r + c];
      }
      if (base == 0 && lane < 3) {
        // b = h (f + m g - alpha M v - (beta + h) K v) + contact; the element terms are in rhs.
        const T m = a.mass[node_i];
        const T gc = lane == 0 ? a.g0 : (lane == 1 ? a.g1 : a.g2);
        T bc = rhs + a.h * (m * gc - a.alpha * m * a.v[3 * node_i + lane]);
        const int s = a.free_surf[i];
        if (s >= 0) bc += T(a.cb[3 * s + lane]);
        a.b[3 * i + lane] = bc;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// PCG (solve_cg.h) inside one persistent cooperative kernel.

template <class T>
struct PcgArgs {
  int n;  // block rows (free nodes)
  const int* row_ptr;
  const int* col;
  const T* vals;
  const T* P;  // block-Jacobi inverse (n x 9)
  const T* b;
  T* x;  // dv: warm start in, solution out
  T* r;
  T* z;
  T* p0;
  T* p1;
  T* q;
  // State update and rest detection.
  int nnode;
  const int* free_nodes;
  T* xpos;
  T* vel;
  T h;
  T tol;
  int max_it;
  int fused;  // 1: search direction updated inside the SpMV (2 barriers per iteration)
  DevScratch* scr;
  DevResult* res;
};

/// The first block row of each lane group, held in registers for the whole solve: lane gl
/// keeps blocks gl, gl + G, ..., gl + (B - 1) G of it (9 values and the column each). When
/// every row fits (the paper mesh: rows of at most 24 blocks, one row per group) the
/// iterations read no matrix data from memory at all.
template <class T, int B>
struct RowCache {
  T v[B > 0 ? B : 1][9];
  int j[B > 0 ? B : 1];
  int k0 = 0, len = 0;
};

template <class T, int B>
__device__ void load_row_cache(const PcgArgs<T>& a, RowCache<T, B>& rc) {
  constexpr int G = kGroup, RPW = 32 / G;
  const int lane = threadIdx.x & 31, gl = lane % G, gw = lane / G;
  const int i = ((blockIdx.x * blockDim.x + threadIdx.x) >> 5) * RPW + gw;
  if constexpr (B > 0) {
    if (i < a.n) {
      rc.k0 = a.row_ptr[i];
      rc.len = a.row_ptr[i + 1] - rc.k0;
      const int len3 = 3 * rc.len;
      const T* rv = a.vals + 9 * std::size_t(rc.k0);
#pragma unroll
      for (int b = 0; b < B; ++b) {
        const int kk = gl + b * G;
        rc.j[b] = 0;
#pragma unroll
        for (int c = 0; c < 9; ++c) rc.v[b][c] = T(0);
        if (kk < rc.len) {
          rc.j[b] = a.col[rc.k0 + kk];
          const T* bv = rv + 3 * kk;
#pragma unroll
          for (int r = 0; r < 3; ++r)
#pragma unroll
            for (int c = 0; c < 3; ++c) rc.v[b][3 * r + c] = bv[r * len3 + c];
        }
      }
    }
  }
}

/// y_i = sum_k A_k u_col(k) for the block rows of this thread's group, then
/// emit(i, c, y_c) on lanes c = 0..2 of the group. `fetch(j, c)` reads the input vector.
/// The first pass takes its row from the register cache; other passes (rows beyond one
/// per group, on large meshes) stream the matrix. Warp-uniform loop bounds: every lane of
/// a warp takes part in every shuffle.
template <class T, int B, class Fetch, class Emit>
__device__ __forceinline__ void spmv_groups(const PcgArgs<T>& a, const RowCache<T, B>& rc, Fetch fetch, Emit emit) {
  constexpr int G = kGroup, RPW = 32 / G;
  const int lane = threadIdx.x & 31;
  const int gl = lane % G, gw = lane / G;
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5;
  const int nwarps = (gridDim.x * blockDim.x) >> 5;
  bool first_pass = true;
  for (int base = warp * RPW; base < a.n; base += nwarps * RPW) {
    const int i = base + gw;
    T y0 = 0, y1 = 0, y2 = 0;
    if (i < a.n) {
      int k0, len, kstart = gl;
      if (B > 0 && first_pass) {
        k0 = rc.k0;
        len = rc.len;
#pragma unroll
        for (int b = 0; b < (B > 0 ? B : 1); ++b) {
          if (gl + b * G < len) {
            const int jj = rc.j[b];
            const T u0 = fetch(jj, 0), u1 = fetch(jj, 1), u2 = fetch(jj, 2);
            const T* m = rc.v[b];
            y0 += m[0] * u0 + m[1] * u1 + m[2] * u2;
            y1 += m[3] * u0 + m[4] * u1 + m[5] * u2;
            y2 += m[6] * u0 + m[7] * u1 + m[8] * u2;
          }
        }
        kstart = gl + B * G;
      } else {
        k0 = a.row_ptr[i];
        len = a.row_ptr[i + 1] - k0;
      }
      const int len3 = 3 * len;
      const T* rv = a.vals + 9 * std::size_t(k0);
      for (int kk = kstart; kk < len; kk += G) {
        const int j = __ldg(a.col + k0 + kk);
        const T u0 = fetch(j, 0), u1 = fetch(j, 1), u2 = fetch(j, 2);
        const T* bv = rv + 3 * kk;
        y0 += __ldg(bv) * u0 + __ldg(bv + 1) * u1 + __ldg(bv + 2) * u2;
        y1 += __ldg(bv + len3) * u0 + __ldg(bv + len3 + 1) * u1 + __ldg(bv + len3 + 2) * u2;
        y2 += __ldg(bv + 2 * len3) * u0 + __ldg(bv + 2 * len3 + 1) * u1 + __ldg(bv + 2 * len3 + 2) * u2;
      }
    }
    first_pass = false;
#pragma unroll
    for (int o = G / 2; o > 0; o >>= 1) {
      y0 += __shfl_xor_sync(0xffffffffu, y0, o);
      y1 += __shfl_xor_sync(0xffffffffu, y1, o);
      y2 += __shfl_xor_sync(0xffffffffu, y2, o);
    }
    if (i < a.n && gl < 3) emit(i, gl, gl == 0 ? y0 : (gl == 1 ? y1 : y2));
  }
}

/// Reduction ring: the values reduced before barrier m live in slot m % 4.
struct Ring {
  int m = 0;
  __device__ double* slot(DevScratch* s) const { return s->red[m & 3]; }
  /// After the barrier: read slot m % 4, zero slot (m + 2) % 4, advance. One thread per
  /// block reads the slot and shares it: every thread of the grid reading one L2 line is a
  /// hot spot (docs/gpu-notes.md).
  template <int K>
  __device__ void take(DevScratch* s, double (&out)[K]) {
    __shared__ double sh[K];
    if (threadIdx.x == 0) {
#pragma unroll
      for (int k = 0; k < K; ++k) sh[k] = __ldcg(&s->red[m & 3][k]);
      if (blockIdx.x == 0)
        for (int k = 0; k < 4; ++k) s->red[(m + 2) & 3][k] = 0.0;
    }
    __syncthreads();
#pragma unroll
    for (int k = 0; k < K; ++k) out[k] = sh[k];
    ++m;
  }
  /// A barrier that carries no reduction still advances the ring (and zeroes ahead).
  __device__ void skip(DevScratch* s) {
    if (blockIdx.x == 0 && threadIdx.x == 0)
      for (int k = 0; k < 4; ++k) s->red[(m + 2) & 3][k] = 0.0;
    ++m;
  }
};


template <class T>
__device__ __forceinline__ void precondition_row(const T* P, const T* r, T* z, int i) {
  const T* Pi = P + 9 * i;
  const T r0 = r[3 * i], r1 = r[3 * i + 1], r2 = r[3 * i + 2];
  z[3 * i] = Pi[0] * r0 + Pi[1] * r1 + Pi[2] * r2;
  z[3 * i + 1] = Pi[3] * r0 + Pi[4] * r1 + Pi[5] * r2;
  z[3 * i + 2] = Pi[6] * r0 + Pi[7] * r1 + Pi[8] * r2;
}

/// v += dv, x += h v over the free nodes; block maxima of |v| and |dv| into the scratch.
template <class T>
__device__ void update_state(const PcgArgs<T>& a) {
  double vmax = 0, dvmax = 0;
  bool bad = false;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < a.n; i += gridDim.x * blockDim.x) {
    const int node = a.free_nodes[i];
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      const T dv = a.x[3 * i + c];
      const T v = a.vel[3 * node + c] + dv;
      a.vel[3 * node + c] = v;
      a.xpos[3 * node + c] += a.h * v;
      vmax = fmax(vmax, double(fabs(v)));
      dvmax = fmax(dvmax, double(fabs(dv)));
      bad = bad || !isfinite(v) || !isfinite(dv);
    }
  }
  // A non-finite velocity must reach the host (fmax drops NaN): report it as +inf.
  if (bad) vmax = dvmax = INFINITY;
  double m2[2] = {vmax, dvmax};
  unsigned long long* const dst[2] = {&a.scr->vmax_bits, &a.scr->dvmax_bits};
  block_max_atomic<2>(m2, dst);
}

/// Rest rule of backend_cpu.cpp: no contact at the start, |v| < 1e-6, |dv| < 1e-7 ->
/// v = 0. Every thread reads the same global values and takes the same branch.
template <class T>
__device__ void rest_rule(const PcgArgs<T>& a) {
  __shared__ bool sh_rested;
  if (threadIdx.x == 0) {
    const volatile DevScratch* sc = a.scr;
    const T vmax = T(bits_to_double(sc->vmax_bits)), dvmax = T(bits_to_double(sc->dvmax_bits));
    sh_rested = sc->start_contacts == 0 && vmax < T(1e-6) && dvmax < T(1e-7);
  }
  __syncthreads();
  const bool rested = sh_rested;
  if (rested)
    for (int j = blockIdx.x * blockDim.x + threadIdx.x; j < 3 * a.nnode; j += gridDim.x * blockDim.x) a.vel[j] = T(0);
  if (blockIdx.x == 0 && threadIdx.x == 0) a.scr->rested = rested ? 1 : 0;
}

/// The whole PCG of solve_cg.h (same warm start, restart rule, stopping rule and
/// breakdown test) in one persistent cooperative kernel, then the state update, the rest
/// rule and the finger outputs. Per iteration two grid barriers: the search direction
/// p = z + beta p is formed inside the SpMV from z and the previous p (double-buffered),
/// so its own barrier disappears. B > 0: the first row of each lane group is held in
/// registers (k_pcg is then launched with at most two blocks per multiprocessor).
template <class T, int B>
__global__ void __launch_bounds__(kPcgMaxBlock, B > 0 ? 1 : 2) k_pcg(PcgArgs<T> a, DetectArgs<T> d, FingersArg F, StepConsts k) {
  coop::grid_group grid = coop::this_grid();
  const int tid = blockIdx.x * blockDim.x + threadIdx.x, nthreads = gridDim.x * blockDim.x;
  Ring ring;
  RowCache<T, B> rc;
  load_row_cache(a, rc);

  // r = b - A x (warm start), ||b||^2, ||r||^2.
  {
    double acc[2] = {0, 0};
    spmv_groups<T, B>(
        a, rc, [&](int j, int c) { return a.x[3 * j + c]; },
        [&](int i, int c, T y) {
          const T bi = a.b[3 * i + c];
          const T ri = bi - y;
          a.r[3 * i + c] = ri;
          acc[0] += double(bi) * double(bi);
          acc[1] += double(ri) * double(ri);
        });
    block_sum_atomic<2>(acc, ring.slot(a.scr));
  }
  grid.sync();
  double br[2];
  ring.take<2>(a.scr, br);
  const T bnorm = sqrt(T(br[0]));
  T rnorm = sqrt(T(br[1]));
  int it = 0;
  if (bnorm > T(0)) {
    const bool restart = !isfinite(rnorm) || rnorm > T(1e3) * bnorm;
    {
      double acc[1] = {0};
      for (int i = tid; i < a.n; i += nthreads) {
        if (restart)
          for (int c = 0; c < 3; ++c) {
            a.x[3 * i + c] = T(0);
            a.r[3 * i + c] = a.b[3 * i + c];
          }
        precondition_row(a.P, a.r, a.z, i);
        for (int c = 0; c < 3; ++c) acc[0] += double(a.r[3 * i + c]) * double(a.z[3 * i + c]);
      }
      block_sum_atomic<1>(acc, ring.slot(a.scr));
    }
    grid.sync();
    double rz1[1];
    ring.take<1>(a.scr, rz1);
    T rz = T(rz1[0]);
    if (restart) rnorm = bnorm;
    T beta = 0;
    bool first = true;
    T* pold = a.p0;
    T* pnew = a.p1;
    while (it < a.max_it && rnorm > a.tol * bnorm) {
      // Search direction p = z + beta p (first: p = z) and q = A p.
      if (!a.fused) {
        for (int j = tid; j < 3 * a.n; j += nthreads) pnew[j] = first ? a.z[j] : a.z[j] + beta * pold[j];
        grid.sync();
        ring.skip(a.scr);
      }
      double acc[1] = {0};
      if (a.fused) {
        const T* z = a.z;
        const T* po = pold;
        T* pn = pnew;
        const bool fst = first;
        const T bt = beta;
        auto pfly = [=](int j, int c) { return fst ? z[3 * j + c] : fma(bt, po[3 * j + c], z[3 * j + c]); };
        spmv_groups<T, B>(a, rc, pfly, [&](int i, int c, T y) {
          const T pi = pfly(i, c);
          pn[3 * i + c] = pi;
          a.q[3 * i + c] = y;
          acc[0] += double(pi) * double(y);
        });
      } else {
        const T* pn = pnew;
        spmv_groups<T, B>(
            a, rc, [=](int j, int c) { return pn[3 * j + c]; },
            [&](int i, int c, T y) {
              a.q[3 * i + c] = y;
              acc[0] += double(pn[3 * i + c]) * double(y);
            });
      }
      block_sum_atomic<1>(acc, ring.slot(a.scr));
      grid.sync();
      double pq1[1];
      ring.take<1>(a.scr, pq1);
      const T pq = T(pq1[0]);
      if (!(pq > T(0))) break;
      const T alpha = rz / pq;
      {
        double acc2[2] = {0, 0};
        for (int i = tid; i < a.n; i += nthreads) {
          for (int c = 0; c < 3; ++c) {
            a.x[3 * i + c] += alpha * pnew[3 * i + c];
            a.r[3 * i + c] -= alpha * a.q[3 * i + c];
          }
          precondition_row(a.P, a.r, a.z, i);
          for (int c = 0; c < 3; ++c) {
            const double rr = double(a.r[3 * i + c]);
            acc2[0] += rr * double(a.z[3 * i + c]);
            acc2[1] += rr * rr;
          }
        }
        block_sum_atomic<2>(acc2, ring.slot(a.scr));
      }
      grid.sync();
      double rr2[2];
      ring.take<2>(a.scr, rr2);
      const T rz_new = T(rr2[0]);
      rnorm = sqrt(T(rr2[1]));
      beta = rz_new / rz;
      rz = rz_new;
      T* tmp = pold;
      pold = pnew;
      pnew = tmp;
      first = false;
      ++it;
    }
  } else {
    for (int j = tid; j < 3 * a.n; j += nthreads) a.x[j] = T(0);
    grid.sync();
    ring.skip(a.scr);
  }
  if (tid == 0) {
    a.res->cg_iterations = it;
    a.res->cg_residual = bnorm > T(0) ? double(rnorm / bnorm) : 0.0;
  }
  update_state(a);
  grid.sync();
  rest_rule(a);
  grid.sync();
  // Finger outputs at the end state (v already zeroed when the body came to rest).
  __shared__ double sacc[kMaxFingers * kFingerVals];
  for (int t = threadIdx.x; t < kMaxFingers * kFingerVals; t += blockDim.x) sacc[t] = 0.0;
  __syncthreads();
  detect_nodes(d, F, k, false, sacc, nullptr, tid, nthreads);
  zero_contact_terms(d, tid, nthreads);
  __syncthreads();
  for (int t = threadIdx.x; t < F.n * kFingerVals; t += blockDim.x)
    if (sacc[t] != 0.0) atomicAdd(&a.scr->facc[0][0] + t, sacc[t]);
  grid.sync();
  if (blockIdx.x == 0) finalize_result(a.scr, a.res, true);
}

// Separate-kernel versions for the baseline.
template <class T>
__global__ void __launch_bounds__(kBlock) k_update(PcgArgs<T> a) { update_state(a); }
template <class T>
__global__ void __launch_bounds__(kBlock) k_rest(PcgArgs<T> a) { rest_rule(a); }
template <class T>
__global__ void __launch_bounds__(kBlock) k_precondition(int n, const T* P, const T* r, T* z) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) precondition_row(P, r, z, i);
}

// ---------------------------------------------------------------------------------------
// Floor measurement kernels.

template <class T>
__global__ void __launch_bounds__(kBlock) k_stream_passes(const T* __restrict__ in, T* __restrict__ out, std::size_t n,
                                                           int passes) {
  coop::grid_group grid = coop::this_grid();
  const std::size_t tid = blockIdx.x * std::size_t(blockDim.x) + threadIdx.x, nt = gridDim.x * std::size_t(blockDim.x);
  for (int p = 0; p < passes; ++p) {
    const T* src = (p & 1) ? out : in;
    T* dst = (p & 1) ? const_cast<T*>(in) : out;
    for (std::size_t j = tid; j < n; j += nt) dst[j] = src[j] * T(0.999) + T(1e-3);
    grid.sync();
  }
}

/// An empty phase: what a kernel boundary costs when each CG phase is its own kernel.
__global__ void __launch_bounds__(kPcgMaxBlock) k_empty(int* sink) {
  if (blockIdx.x == 0 && threadIdx.x == 0 && sink[0] < 0) sink[0] = 0;
}

/// Writes a flag (to mapped host memory in the round-trip measurement).
__global__ void k_flag(int* p) {
  if (threadIdx.x == 0) *p = 1;
}

__global__ void __launch_bounds__(kPcgMaxBlock) k_sync_only(int syncs, int* sink) {
  coop::grid_group grid = coop::this_grid();
  for (int s = 0; s < syncs; ++s) grid.sync();
  if (blockIdx.x == 0 && threadIdx.x == 0) *sink = syncs;
}

// ---------------------------------------------------------------------------------------
// Host side.

struct DeviceInfo {
  bool ok = false;
  std::string why;
  std::string name;
  int device = 0;
  int sms = 0;
  int cc_major = 0, cc_minor = 0;
  bool cooperative = false;
};

const DeviceInfo& device_info() {
  static DeviceInfo info;
  static std::once_flag once;
  std::call_once(once, [] {
    int count = 0;
    const cudaError_t e = cudaGetDeviceCount(&count);
    if (e != cudaSuccess) {
      info.why = std::string("no usable CUDA device (") + cudaGetErrorName(e) + ": " + cudaGetErrorString(e) + ")";
      cudaGetLastError();
      return;
    }
    if (count <= 0) {
      info.why = "no CUDA device found";
      return;
    }
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
      info.why = "cudaGetDeviceProperties failed";
      cudaGetLastError();
      return;
    }
    info.name = prop.name;
    info.sms = prop.multiProcessorCount;
    info.cc_major = prop.major;
    info.cc_minor = prop.minor;
    info.cooperative = prop.cooperativeLaunch != 0;
    if (prop.major < 6) {
      info.why = std::string("GPU ") + prop.name + " has compute capability " + std::to_string(prop.major) + "." +
                 std::to_string(prop.minor) + " (6.0 or newer needed)";
      return;
    }
    if (!info.cooperative) {
      info.why = std::string("GPU ") + prop.name + " does not support cooperative launches";
      return;
    }
    const cudaError_t e2 = cudaFree(nullptr);  // creates the context: catches driver/runtime mismatch
    if (e2 != cudaSuccess) {
      info.why = std::string("cannot use the CUDA device (") + cudaGetErrorName(e2) + ": " + cudaGetErrorString(e2) + ")";
      cudaGetLastError();
      return;
    }
    info.ok = true;
  });
  return info;
}

constexpr int kCacheBlocks = 3;  // blocks per lane held in registers: rows of up to 24 blocks

/// Launch configuration of the persistent kernel for n block rows. Default: blocks of 512
/// threads, at most one per multiprocessor where the rows live in registers (fewer blocks
/// make the grid barriers and the reductions cheaper: measured, docs/gpu-notes.md).
struct PcgLaunch {
  const void* fn = nullptr;
  int grid = 1;
  int block = kPcgMaxBlock;
  bool cached = false;  // every row's matrix held in registers
};

template <class T>
PcgLaunch pcg_launch(int n) {
  const DeviceInfo& d = device_info();
  PcgLaunch L;
  const int want_block = env_int("PALPATION_CUDA_PCG_BLOCK", kPcgMaxBlock);
  L.block = want_block == 256 ? 256 : kPcgMaxBlock;
  const int rows_per_block = L.block / kGroup;
  const int forced = env_int("PALPATION_CUDA_GRID", 0);
  const int cap_per_sm = env_int("PALPATION_CUDA_BLOCKS_PER_SM", 0);
  // Register-resident rows when one pass of lane groups covers every row.
  int per_sm_c = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm_c, k_pcg<T, kCacheBlocks>, L.block, 0));
  if (cap_per_sm > 0) per_sm_c = std::min(per_sm_c, cap_per_sm);
  const int need = (n + rows_per_block - 1) / rows_per_block;
  if (env_int("PALPATION_CUDA_CACHE", 1) != 0 && per_sm_c > 0 && need <= per_sm_c * d.sms) {
    L.fn = reinterpret_cast<const void*>(&k_pcg<T, kCacheBlocks>);
    L.cached = true;
    L.grid = std::max(need, 1);
    if (forced > 0) L.grid = std::min(forced, per_sm_c * d.sms);
    return L;
  }
  int per_sm = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, k_pcg<T, 0>, L.block, 0));
  per_sm = std::max(per_sm, 1);
  if (cap_per_sm > 0) per_sm = std::min(per_sm, cap_per_sm);
  const int max_blocks = per_sm * d.sms;
  // Enough blocks that each lane group gets about one block row per SpMV pass; more only
  // makes the barriers dearer.
  L.fn = reinterpret_cast<const void*>(&k_pcg<T, 0>);
  L.grid = std::clamp(need, 1, max_blocks);
  if (forced > 0) L.grid = std::min(forced, max_blocks);
  return L;
}

/// Host copies of the model arrays in the GPU layout (built once per backend).
template <class T>
struct HostLayout {
  std::vector<int4> tets;
  std::vector<T> grad, vol;
  std::vector<int> col_node, inc_ptr, inc, free_surf;
  std::vector<T> mass;
  std::vector<int> srow_ptr, scol;  // scalar CSR pattern (baseline)

  HostLayout(const Model& m, bool scalar_csr) {
    const int ne = m.num_tets(), nf = m.num_free(), nb = m.num_blocks();
    tets.resize(ne);
    grad.resize(12 * std::size_t(ne));
    vol.resize(ne);
    for (int e = 0; e < ne; ++e) {
      tets[e] = make_int4(m.tets[e][0], m.tets[e][1], m.tets[e][2], m.tets[e][3]);
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) grad[12 * std::size_t(e) + 3 * a + c] = T(m.grad[e][a][c]);
      vol[e] = T(m.volume[e]);
    }
    // Node of each block's column (what the assembly warp matches element nodes with).
    col_node.resize(nb);
    for (int k = 0; k < nb; ++k) col_node[k] = m.free_nodes[m.col[k]];
    // Incidences of each free node.
    inc_ptr.assign(nf + 1, 0);
    for (int e = 0; e < ne; ++e)
      for (int a = 0; a < 4; ++a)
        if (m.dof[m.tets[e][a]] >= 0) ++inc_ptr[m.dof[m.tets[e][a]] + 1];
    for (int i = 0; i < nf; ++i) inc_ptr[i + 1] += inc_ptr[i];
    inc.resize(inc_ptr[nf]);
    {
      std::vector<int> fill(inc_ptr.begin(), inc_ptr.end() - 1);
      for (int e = 0; e < ne; ++e)
        for (int a = 0; a < 4; ++a) {
          const int i = m.dof[m.tets[e][a]];
          if (i >= 0) inc[fill[i]++] = (e << 2) | a;
        }
    }
    const int ns = static_cast<int>(m.surface_nodes.size());
    free_surf.assign(nf, -1);
    for (int s = 0; s < ns; ++s) {
      const int i = m.dof[m.surface_nodes[s]];
      if (i >= 0) free_surf[i] = s;
    }
    mass.resize(m.num_nodes());
    for (int j = 0; j < m.num_nodes(); ++j) mass[j] = T(m.mass[j]);
    if (!scalar_csr) return;
    // Scalar CSR pattern of the same values array.
    srow_ptr.assign(3 * nf + 1, 0);
    scol.resize(9 * std::size_t(nb));
    for (int i = 0; i < nf; ++i) {
      const int k0 = m.row_ptr[i], len = m.row_ptr[i + 1] - k0;
      for (int r = 0; r < 3; ++r) {
        srow_ptr[3 * i + r + 1] = srow_ptr[3 * i + r] + 3 * len;
        for (int kk = 0; kk < len; ++kk)
          for (int c = 0; c < 3; ++c) scol[9 * std::size_t(k0) + r * 3 * len + 3 * kk + c] = 3 * m.col[k0 + kk] + c;
      }
    }
  }
};

enum class Solver { Persistent, Csr };

/// Stage timing with events (PALPATION_CUDA_PROFILE=1): printed when the backend dies.
struct Profiler {
  bool on = false;
  static constexpr int kStages = 4;
  const char* names[kStages] = {"element+detect", "assemble", "solve+finish", "wait"};
  cudaEvent_t ev[kStages + 1]{};
  std::vector<float> ms[kStages];
  int steps = 0;
  void init() {
    on = env_int("PALPATION_CUDA_PROFILE", 0) != 0;
    if (on)
      for (auto& e : ev) CU(cudaEventCreate(&e));
  }
  void mark(int i, cudaStream_t s) {
    if (on) CU(cudaEventRecord(ev[i], s));
  }
  void collect() {
    if (!on) return;
    for (int i = 0; i < kStages; ++i) {
      float t = 0;
      CU(cudaEventElapsedTime(&t, ev[i], ev[i + 1]));
      ms[i].push_back(t);
    }
    ++steps;
  }
  void report(const std::string& who) {
    if (!on || steps == 0) return;
    std::fprintf(stderr, "cuda profile (%s, %d solved steps), median us per stage:", who.c_str(), steps);
    for (int i = 0; i < kStages; ++i) {
      auto v = ms[i];
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      std::fprintf(stderr, " %s %.1f", names[i], 1000.0 * v[v.size() / 2]);
    }
    std::fprintf(stderr, "\n");
  }
  ~Profiler() {
    for (auto& e : ev)
      if (e) cudaEventDestroy(e);
  }
};

template <class T>
class CudaBackend final : public Backend {
 public:
  CudaBackend(const Model& model, const SimParams& params, Solver solver) : m_(model), p_(params), solver_(solver) {
    const DeviceInfo& d = device_info();
    if (!d.ok) throw std::runtime_error("cuda backend: " + d.why);
    CU(cudaSetDevice(d.device));
    CU(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
    nn_ = m_.num_nodes();
    ne_ = m_.num_tets();
    nf_ = m_.num_free();
    nb_ = m_.num_blocks();
    ns_ = static_cast<int>(m_.surface_nodes.size());
    nt_ = static_cast<int>(m_.surface.size());
    if (static_cast<long long>(ne_) >= (1ll << 27)) throw std::runtime_error("cuda backend: too many elements");
    HostLayout<T> L(m_, solver_ == Solver::Csr);
    tets_.upload(L.tets, stream_);
    grad_.upload(L.grad, stream_);
    vol_.upload(L.vol, stream_);
    col_node_.upload(L.col_node, stream_);
    inc_ptr_.upload(L.inc_ptr, stream_);
    inc_.upload(L.inc, stream_);
    free_surf_.upload(L.free_surf, stream_);
    {
      std::vector<int> tri(3 * std::size_t(nt_)), node_surf(nn_, -1);
      for (int t = 0; t < nt_; ++t)
        for (int k = 0; k < 3; ++k) tri[3 * std::size_t(t) + k] = m_.surface[t][k];
      for (int s = 0; s < ns_; ++s) node_surf[m_.surface_nodes[s]] = s;
      tri_.upload(tri, stream_);
      node_surf_.upload(node_surf, stream_);
      dof_.upload(m_.dof, stream_);
    }
    mass_.upload(L.mass, stream_);
    row_ptr_.upload(m_.row_ptr, stream_);
    col_.upload(m_.col, stream_);
    free_nodes_.upload(m_.free_nodes, stream_);
    x_.alloc(3 * std::size_t(nn_));
    v_.alloc(3 * std::size_t(nn_));
    quat_.alloc(4 * std::size_t(ne_));
    lambda_.alloc(ne_);
    mu_.alloc(ne_);
    rec_.alloc(kRec * std::size_t(ne_));
    vals_.alloc(9 * std::size_t(nb_));
    precond_.alloc(9 * std::size_t(nf_));
    for (auto* v : {&b_, &dv_, &r_, &z_, &p0_, &p1_, &q_}) v->alloc(3 * std::size_t(nf_));
    cA_.alloc(6 * std::size_t(std::max(ns_, 1)));
    cb_.alloc(3 * std::size_t(std::max(ns_, 1)));
    scratch_.alloc(1);
    // The result lives in mapped pinned memory: the kernels write it, no copy is queued.
    CU(cudaHostAlloc(reinterpret_cast<void**>(&host_res_), sizeof(DevResult), cudaHostAllocMapped));
    CU(cudaHostGetDevicePointer(reinterpret_cast<void**>(&dev_res_), host_res_, 0));
    rest_.resize(3 * std::size_t(nn_));
    for (int j = 0; j < nn_; ++j)
      for (int c = 0; c < 3; ++c) rest_[3 * j + c] = T(m_.rest[j][c]);
    detect_grid_ = std::max(1, std::min((nt_ + kBlock - 1) / kBlock, 4 * d.sms));
    if (solver_ == Solver::Persistent) {
      launch_ = pcg_launch<T>(nf_);
      fused_ = env_str("PALPATION_CUDA_CG", "fused") != "3sync";
    } else {
      init_csr(L);
    }
    prof_.init();
    update_materials();
    reset();
  }

  ~CudaBackend() override {
    prof_.report(name() + (std::is_same_v<T, double> ? " double" : " float"));
#ifdef PALPATION_HAVE_CUSPARSE
    if (spmv_buf_) cudaFree(spmv_buf_);
    if (mat_) cusparseDestroySpMat(mat_);
    for (auto* vd : {&vec_dv_, &vec_p_, &vec_q_})
      if (*vd) cusparseDestroyDnVec(*vd);
    if (sp_) cusparseDestroy(sp_);
    if (bl_) cublasDestroy(bl_);
#endif
    if (host_res_) cudaFreeHost(host_res_);
    if (stream_) cudaStreamDestroy(stream_);
  }

  std::string name() const override { return solver_ == Solver::Persistent ? "cuda" : "cuda-csr"; }
  std::string device_name() const override { return device_info().name; }
  Precision precision() const override { return std::is_same_v<T, double> ? Precision::Double : Precision::Float; }
  const SimParams& params() const override { return p_; }
  void set_params(const SimParams& p) override { p_ = p; }

  void update_materials() override {
    std::vector<T> l(ne_), mu(ne_);
    for (int e = 0; e < ne_; ++e) {
      l[e] = T(m_.lambda[e]);
      mu[e] = T(m_.mu[e]);
    }
    CU(cudaStreamSynchronize(stream_));
    lambda_.upload(l, stream_);
    mu_.upload(mu, stream_);
    rested_ = false;
  }

  void reset() override {
    CU(cudaStreamSynchronize(stream_));
    x_.upload(rest_, stream_);
    v_.zero(stream_);
    dv_.zero(stream_);
    p0_.zero(stream_);
    p1_.zero(stream_);
    std::vector<T> q(4 * std::size_t(ne_), T(0));
    for (int e = 0; e < ne_; ++e) q[4 * std::size_t(e)] = T(1);
    CU(cudaMemcpyAsync(quat_.get(), q.data(), sizeof(T) * q.size(), cudaMemcpyHostToDevice, stream_));
    scratch_.zero(stream_);
    cA_.zero(stream_);
    cb_.zero(stream_);
    CU(cudaStreamSynchronize(stream_));
    std::memset(static_cast<void*>(host_res_), 0, sizeof(DevResult));
    filtered_.clear();
    rested_ = p_.gravity.squaredNorm() == 0;
  }

  void positions(std::vector<double>& xyz) const override { download(x_, xyz); }
  void velocities(std::vector<double>& xyz) const override { download(v_, xyz); }

  StepStats step(std::span<const FingerInput> fingers, std::span<FingerOutput> out) override {
    if (fingers.size() > std::size_t(kMaxFingers))
      throw std::runtime_error("cuda backend: at most " + std::to_string(kMaxFingers) + " fingers");
    StepStats st;
    if (filtered_.size() != fingers.size()) filtered_.assign(fingers.size(), Eigen::Vector3d::Zero());
    FingersArg F{};
    F.n = static_cast<int>(fingers.size());
    for (int f = 0; f < F.n; ++f) {
      for (int c = 0; c < 3; ++c) {
        F.f[f].c[c] = fingers[f].position[c];
        F.f[f].v[c] = fingers[f].velocity[c];
      }
      F.f[f].r = fingers[f].radius;
      F.f[f].active = fingers[f].active ? 1 : 0;
    }
    StepConsts k{};
    k.h = p_.solver.dt;
    k.alpha = p_.damping.mass;
    k.beta = p_.damping.stiffness;
    k.ks = p_.contact.stiffness;
    k.ke = p_.contact.damping;
    for (int c = 0; c < 3; ++c) k.g[c] = p_.gravity[c];

    bool detected = false;
    if (rested_) {
      // At rest: the solve is needed only if something touches. Detection on the GPU and
      // the result in mapped memory: one launch and one synchronisation decide.
      launch_detect(F, k, true);
      fetch_result();
      if (host_res_->start_contacts == 0) {
        finger_outputs(fingers, out);
        st.contacts = 0;
        st.finite = true;
        for (const auto& o : out) st.finite = st.finite && o.force.allFinite();
        return st;
      }
      detected = true;
    }
    prof_.mark(0, stream_);
    launch_element(F, k, !detected);
    prof_.mark(1, stream_);
    launch_assemble(k);
    prof_.mark(2, stream_);
    int iterations = 0;
    double residual = 0;
    if (solver_ == Solver::Persistent) {
      launch_pcg(F, k);
    } else {
      solve_csr(iterations, residual);
      launch_detect(F, k, false);
    }
    prof_.mark(3, stream_);
    fetch_result();
    prof_.mark(4, stream_);
    if (prof_.on) {
      CU(cudaEventSynchronize(prof_.ev[4]));
      prof_.collect();
    }
    const DevResult& R = *host_res_;
    if (solver_ == Solver::Persistent) {
      iterations = R.cg_iterations;
      residual = R.cg_residual;
    }
    st.cg_iterations = iterations;
    st.cg_residual = residual;
    st.solved = true;
    st.contacts = R.start_contacts;
    rested_ = R.rested != 0;
    st.finite = std::isfinite(R.vmax) && std::isfinite(residual);
    finger_outputs(fingers, out);
    for (const auto& o : out) st.finite = st.finite && o.force.allFinite();
    return st;
  }

 private:
  void download(const DeviceArray<T>& a, std::vector<double>& xyz) const {
    std::vector<T> tmp(a.size());
    CU(cudaMemcpyAsync(tmp.data(), a.get(), sizeof(T) * tmp.size(), cudaMemcpyDeviceToHost, stream_));
    CU(cudaStreamSynchronize(stream_));
    xyz.assign(tmp.begin(), tmp.end());
  }

  void fetch_result() { CU(cudaStreamSynchronize(stream_)); }

  DetectArgs<T> detect_args() {
    return DetectArgs<T>{nt_,      tri_.get(), node_surf_.get(), dof_.get(), ns_,     x_.get(),
                         v_.get(), cA_.get(), cb_.get(),        scratch_.get(), dev_res_};
  }

  void launch_detect(const FingersArg& F, const StepConsts& k, bool start) {
    k_detect<T><<<detect_grid_, kBlock, 0, stream_>>>(detect_args(), F, k, start ? 1 : 0);
    CU_LAUNCHED(k_detect);
  }

  /// Elements, plus the start-of-step contact detection in extra blocks when `detect`.
  void launch_element(const FingersArg& F, const StepConsts& k, bool detect) {
    ElementArgs<T> a{ne_, tets_.get(), grad_.get(), vol_.get(), lambda_.get(), mu_.get(), quat_.get(), x_.get(), v_.get(),
                     rec_.get(), T(k.h), T(k.beta), (ne_ + kElemBlock - 1) / kElemBlock};
    const int dblocks = detect ? std::max(1, (nt_ + kElemBlock - 1) / kElemBlock) : 0;
    k_element<T><<<a.elem_blocks + dblocks, kElemBlock, 0, stream_>>>(a, detect_args(), F, k);
    CU_LAUNCHED(k_element);
  }

  void launch_assemble(const StepConsts& k) {
    AssembleArgs<T> a{};
    a.nf = nf_;
    a.row_ptr = row_ptr_.get();
    a.col_node = col_node_.get();
    a.inc_ptr = inc_ptr_.get();
    a.inc = inc_.get();
    a.tets = tets_.get();
    a.rec = rec_.get();
    a.free_nodes = free_nodes_.get();
    a.free_surf = free_surf_.get();
    a.mass = mass_.get();
    a.v = v_.get();
    a.cA = cA_.get();
    a.cb = cb_.get();
    a.vals = vals_.get();
    a.precond = precond_.get();
    a.b = b_.get();
    const T h = T(k.h);
    a.kscale = h * h + h * T(k.beta);
    a.mscale = T(1) + h * T(k.alpha);
    a.h = h;
    a.alpha = T(k.alpha);
    a.g0 = T(k.g[0]);
    a.g1 = T(k.g[1]);
    a.g2 = T(k.g[2]);
    const int warps_per_block = kBlock / 32;
    k_assemble<T><<<(nf_ + warps_per_block - 1) / warps_per_block, kBlock, 0, stream_>>>(a);
    CU_LAUNCHED(k_assemble);
  }

  PcgArgs<T> pcg_args() {
    PcgArgs<T> a{};
    a.n = nf_;
    a.row_ptr = row_ptr_.get();
    a.col = col_.get();
    a.vals = vals_.get();
    a.P = precond_.get();
    a.b = b_.get();
    a.x = dv_.get();
    a.r = r_.get();
    a.z = z_.get();
    a.p0 = p0_.get();
    a.p1 = p1_.get();
    a.q = q_.get();
    a.nnode = nn_;
    a.free_nodes = free_nodes_.get();
    a.xpos = x_.get();
    a.vel = v_.get();
    a.h = T(p_.solver.dt);
    a.tol = T(p_.solver.cg_tolerance);
    a.max_it = p_.solver.cg_max_iterations;
    a.fused = fused_ ? 1 : 0;
    a.scr = scratch_.get();
    a.res = dev_res_;
    return a;
  }

  void launch_pcg(const FingersArg& F, const StepConsts& k) {
    PcgArgs<T> a = pcg_args();
    DetectArgs<T> d = detect_args();
    FingersArg f = F;
    StepConsts kk = k;
    void* args[] = {&a, &d, &f, &kk};
    CU(cudaLaunchCooperativeKernel(launch_.fn, dim3(launch_.grid), dim3(launch_.block), args, 0, stream_));
  }

  void finger_outputs(std::span<const FingerInput> fingers, std::span<FingerOutput> out) {
    const double h = p_.solver.dt;
    constexpr double kPi = 3.14159265358979323846;
    const double a = 1.0 - std::exp(-2.0 * kPi * p_.contact.force_filter_hz * h);
    for (std::size_t f = 0; f < out.size(); ++f) out[f] = FingerOutput{};
    for (std::size_t f = 0; f < out.size() && f < fingers.size(); ++f) {
      const double* s = host_res_->finger[f];
      FingerOutput& o = out[f];
      o.force_raw = Eigen::Vector3d(s[0], s[1], s[2]);
      o.stiffness << s[3], s[4], s[5], s[4], s[6], s[7], s[5], s[7], s[8];
      o.contacts = static_cast<int>(std::lround(s[12]));
      o.contact_point = Eigen::Vector3d(s[9], s[10], s[11]);
      if (o.contacts > 0) o.contact_point /= o.contacts;
      const double fn = o.force_raw.norm();
      o.normal = fn > 0 ? Eigen::Vector3d(o.force_raw / fn) : Eigen::Vector3d::Zero();
      filtered_[f] += a * (o.force_raw - filtered_[f]);
      o.force = filtered_[f];
    }
  }

  // --- textbook baseline ---------------------------------------------------------------
#ifdef PALPATION_HAVE_CUSPARSE
  static constexpr cudaDataType kCudaType = std::is_same_v<T, double> ? CUDA_R_64F : CUDA_R_32F;
  void init_csr(const HostLayout<T>& L) {
    srow_ptr_.upload(L.srow_ptr, stream_);
    scol_.upload(L.scol, stream_);
    CUSP(cusparseCreate(&sp_));
    CUSP(cusparseSetStream(sp_, stream_));
    CUBL(cublasCreate(&bl_));
    CUBL(cublasSetStream(bl_, stream_));
    const int64_t n = 3 * int64_t(nf_), nnz = 9 * int64_t(nb_);
    CUSP(cusparseCreateCsr(&mat_, n, n, nnz, srow_ptr_.get(), scol_.get(), vals_.get(), CUSPARSE_INDEX_32I,
                           CUSPARSE_INDEX_32I, CUSPARSE_INDEX_BASE_ZERO, kCudaType));
    CUSP(cusparseCreateDnVec(&vec_dv_, n, dv_.get(), kCudaType));
    CUSP(cusparseCreateDnVec(&vec_p_, n, p0_.get(), kCudaType));
    CUSP(cusparseCreateDnVec(&vec_q_, n, q_.get(), kCudaType));
    const T one = 1, zero = 0;
    std::size_t bytes = 0;
    CUSP(cusparseSpMV_bufferSize(sp_, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, vec_p_, &zero, vec_q_, kCudaType,
                                 CUSPARSE_SPMV_CSR_ALG1, &bytes));
    CU(cudaMalloc(&spmv_buf_, std::max<std::size_t>(bytes, 16)));
  }
  void spmv(cusparseDnVecDescr_t in) {
    const T one = 1, zero = 0;
    CUSP(cusparseSpMV(sp_, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, in, &zero, vec_q_, kCudaType,
                      CUSPARSE_SPMV_CSR_ALG1, spmv_buf_));
  }
  T dot(const T* a, const T* b) {
    T r = 0;
    const int n = 3 * nf_;
    if constexpr (std::is_same_v<T, double>)
      CUBL(cublasDdot(bl_, n, a, 1, b, 1, &r));
    else
      CUBL(cublasSdot(bl_, n, a, 1, b, 1, &r));
    return r;
  }
  void axpy(T alpha, const T* x, T* y) {
    const int n = 3 * nf_;
    if constexpr (std::is_same_v<T, double>)
      CUBL(cublasDaxpy(bl_, n, &alpha, x, 1, y, 1));
    else
      CUBL(cublasSaxpy(bl_, n, &alpha, x, 1, y, 1));
  }
  void scal(T alpha, T* x) {
    const int n = 3 * nf_;
    if constexpr (std::is_same_v<T, double>)
      CUBL(cublasDscal(bl_, n, &alpha, x, 1));
    else
      CUBL(cublasSscal(bl_, n, &alpha, x, 1));
  }
  void copy(const T* x, T* y) {
    CU(cudaMemcpyAsync(y, x, sizeof(T) * 3 * std::size_t(nf_), cudaMemcpyDeviceToDevice, stream_));
  }
  void precondition() {
    k_precondition<T><<<(nf_ + kBlock - 1) / kBlock, kBlock, 0, stream_>>>(nf_, precond_.get(), r_.get(), z_.get());
    CU_LAUNCHED(k_precondition);
  }
  // solve_cg.h's algorithm, one library call per vector operation, the host deciding.
  void solve_csr(int& iterations, double& residual) {
    T* x = dv_.get();
    T* r = r_.get();
    T* z = z_.get();
    T* p = p0_.get();
    T* q = q_.get();
    const T* b = b_.get();
    const T tol = T(p_.solver.cg_tolerance);
    const int max_it = p_.solver.cg_max_iterations;
    const T bnorm = std::sqrt(dot(b, b));
    int it = 0;
    T rnorm = 0;
    if (!(bnorm > 0)) {
      dv_.zero(stream_);
    } else {
      spmv(vec_dv_);
      copy(b, r);
      axpy(T(-1), q, r);
      rnorm = std::sqrt(dot(r, r));
      if (!std::isfinite(double(rnorm)) || rnorm > T(1e3) * bnorm) {
        dv_.zero(stream_);
        copy(b, r);
        rnorm = bnorm;
      }
      precondition();
      copy(z, p);
      T rz = dot(r, z);
      while (it < max_it && rnorm > tol * bnorm) {
        spmv(vec_p_);
        const T pq = dot(p, q);
        if (!(pq > 0)) break;
        const T alpha = rz / pq;
        axpy(alpha, p, x);
        axpy(-alpha, q, r);
        precondition();
        const T rz_new = dot(r, z);
        rnorm = std::sqrt(dot(r, r));
        const T beta = rz_new / rz;
        rz = rz_new;
        scal(beta, p);
        axpy(T(1), z, p);
        ++it;
      }
    }
    iterations = it;
    residual = bnorm > 0 ? double(rnorm / bnorm) : 0.0;
    PcgArgs<T> a = pcg_args();
    const int g = std::max(1, std::min((nf_ + kBlock - 1) / kBlock, 4 * device_info().sms));
    k_update<T><<<g, kBlock, 0, stream_>>>(a);
    CU_LAUNCHED(k_update);
    const int g2 = std::max(1, std::min((3 * nn_ + kBlock - 1) / kBlock, 4 * device_info().sms));
    k_rest<T><<<g2, kBlock, 0, stream_>>>(a);
    CU_LAUNCHED(k_rest);
  }
  DeviceArray<int> srow_ptr_, scol_;
  cusparseHandle_t sp_ = nullptr;
  cublasHandle_t bl_ = nullptr;
  cusparseSpMatDescr_t mat_ = nullptr;
  cusparseDnVecDescr_t vec_dv_ = nullptr, vec_p_ = nullptr, vec_q_ = nullptr;
  void* spmv_buf_ = nullptr;
#else
  void init_csr(const HostLayout<T>&) {
    throw std::runtime_error("backend cuda-csr: this build has no cuSPARSE/cuBLAS");
  }
  void solve_csr(int&, double&) {}
#endif

  const Model& m_;
  SimParams p_;
  Solver solver_;
  int nn_ = 0, ne_ = 0, nf_ = 0, nb_ = 0, ns_ = 0, nt_ = 0;
  PcgLaunch launch_;
  int detect_grid_ = 1;
  bool fused_ = true;
  cudaStream_t stream_ = nullptr;
  DeviceArray<int4> tets_;
  DeviceArray<T> grad_, vol_, lambda_, mu_, quat_, mass_;
  DeviceArray<int> col_node_, inc_ptr_, inc_, free_surf_, row_ptr_, col_, free_nodes_, tri_, node_surf_, dof_;
  DeviceArray<T> x_, v_, rec_, vals_, precond_, b_, dv_, r_, z_, p0_, p1_, q_;
  DeviceArray<double> cA_, cb_;
  DeviceArray<DevScratch> scratch_;
  DevResult* host_res_ = nullptr;  // mapped pinned memory
  DevResult* dev_res_ = nullptr;   // its device address
  std::vector<T> rest_;
  std::vector<Eigen::Vector3d> filtered_;
  bool rested_ = true;
  Profiler prof_;
};

// ---------------------------------------------------------------------------------------
// Floor.

/// Median of: launch a tiny kernel that writes 4 bytes of mapped host memory, synchronise.
double host_round_trip_us(cudaStream_t s, int* dev_scratch) {
  (void)dev_scratch;
  int* host = nullptr;
  int* dev = nullptr;
  CU(cudaHostAlloc(reinterpret_cast<void**>(&host), sizeof(int), cudaHostAllocMapped));
  CU(cudaHostGetDevicePointer(reinterpret_cast<void**>(&dev), host, 0));
  std::vector<double> rt;
  for (int rep = 0; rep < 101; ++rep) {
    const auto a0 = std::chrono::steady_clock::now();
    k_flag<<<1, 32, 0, s>>>(dev);
    CU(cudaPeekAtLastError());
    CU(cudaStreamSynchronize(s));
    rt.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - a0).count());
  }
  cudaFreeHost(host);
  std::sort(rt.begin(), rt.end());
  return rt[rt.size() / 2];
}

template <class T>
bool measure_floor(const Model& m, FloorEstimate& out) {
  const DeviceInfo& d = device_info();
  if (!d.ok) return false;
  const int nf = m.num_free(), nb = m.num_blocks(), ne = m.num_tets(), nn = m.num_nodes();
  const double S = sizeof(T);
  // One fused PCG iteration must read the matrix (values, column indices, row pointers)
  // and the block-Jacobi inverse once; phase A gathers z and p (each once, ideally),
  // writes p and q; phase B reads p, q, x, r and writes x, r, z: 11 vector passes.
  const double matrix = 9.0 * nb * S + 4.0 * nb + 4.0 * (nf + 1);
  const double vectors = 11.0 * 3.0 * nf * S + 9.0 * nf * S;
  // Where the rows live in registers the iterations do not read the matrix: it is read
  // once per step (counted with the step), and the floor of an iteration is its vectors.
  const PcgLaunch launch = pcg_launch<T>(nf);
  out.bytes_per_iteration = (launch.cached ? 0.0 : matrix) + vectors;
  out.syncs_per_iteration = 2;
  // Per step outside CG: the element pass (read tets, gradients, materials, quaternions and
  // each node's x and v once; write quaternions and one record per element), the assembly
  // (incidences, each element record and tet once, the matrix, preconditioner and
  // right-hand side written once) and the state update.
  const double elem = ne * (16.0 + 12 * S + 8 * S + 3 * S + kRec * S) + 2 * 3.0 * nn * S;
  const double assemble = ne * (4 * 4.0 + 16.0 + kRec * S) + 4.0 * nb + 9.0 * nb * S + 9.0 * nf * S + 3.0 * nf * S + 4.0 * nn * S;
  const double update = 3.0 * nf * S * 5;
  const double step_bytes = elem + assemble + update + (launch.cached ? matrix : 0.0);

  cudaStream_t s;
  CU(cudaStreamCreateWithFlags(&s, cudaStreamNonBlocking));
  const int grid = launch.grid;
  cudaEvent_t e0, e1;
  CU(cudaEventCreate(&e0));
  CU(cudaEventCreate(&e1));
  auto time_coop = [&](const void* fn, void** args, int g, int block) {
    std::vector<float> t;
    for (int rep = 0; rep < 7; ++rep) {
      CU(cudaEventRecord(e0, s));
      CU(cudaLaunchCooperativeKernel(fn, dim3(g), dim3(block), args, 0, s));
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      t.push_back(ms);
    }
    std::sort(t.begin(), t.end());
    return double(t[t.size() / 2]);
  };
  // Barrier cost: a kernel of nothing but barriers, with the PCG's grid.
  DeviceArray<int> sink;
  sink.alloc(1);
  int syncs = 2000;
  int* sinkp = sink.get();
  void* sargs[] = {&syncs, &sinkp};
  const double t_sync = time_coop(reinterpret_cast<const void*>(&k_sync_only), sargs, grid, launch.block) * 1000.0 / syncs;
  // The alternatives to a grid barrier, measured once per process for docs/gpu-notes.md:
  // a kernel boundary in a stream and in a replayed CUDA graph, same grid.
  static std::once_flag said;
  std::call_once(said, [&] {
    constexpr int kLaunches = 200;
    auto time_stream = [&] {
      CU(cudaEventRecord(e0, s));
      for (int l = 0; l < kLaunches; ++l) k_empty<<<grid, launch.block, 0, s>>>(sinkp);
      CU(cudaPeekAtLastError());
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      return ms * 1000.0 / kLaunches;
    };
    time_stream();
    const double t_stream = time_stream();
    cudaGraph_t g;
    cudaGraphExec_t ge;
    CU(cudaStreamBeginCapture(s, cudaStreamCaptureModeThreadLocal));
    for (int l = 0; l < kLaunches; ++l) k_empty<<<grid, launch.block, 0, s>>>(sinkp);
    CU(cudaStreamEndCapture(s, &g));
    CU(cudaGraphInstantiate(&ge, g, 0));
    CU(cudaGraphLaunch(ge, s));
    CU(cudaStreamSynchronize(s));
    std::vector<float> t;
    for (int rep = 0; rep < 5; ++rep) {
      CU(cudaEventRecord(e0, s));
      CU(cudaGraphLaunch(ge, s));
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      t.push_back(ms);
    }
    std::sort(t.begin(), t.end());
    const double t_graph = t[t.size() / 2] * 1000.0 / kLaunches;
    cudaGraphExecDestroy(ge);
    cudaGraphDestroy(g);
    std::fprintf(stderr,
                 "cuda floor: %s, grid %d x %d%s: grid barrier %.2f us; kernel boundary %.2f us (stream), %.2f us "
                 "(graph replay); host round trip %.1f us (median)\n",
                 d.name.c_str(), grid, launch.block, launch.cached ? " (rows in registers)" : "", t_sync, t_stream, t_graph,
                 host_round_trip_us(s, sinkp));
  });
  // Bandwidth at the iteration's working-set size: passes that read and write it.
  std::size_t n = std::max<std::size_t>(1024, std::size_t(out.bytes_per_iteration / (2 * S)));
  DeviceArray<T> a, b;
  a.alloc(n);
  b.alloc(n);
  a.zero(s);
  b.zero(s);
  int passes = 200;
  T* ap = a.get();
  T* bp = b.get();
  void* bargs[] = {&ap, &bp, &n, &passes};
  int sgrid = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&sgrid, k_stream_passes<T>, kBlock, 0));
  sgrid = std::max(1, sgrid) * d.sms;
  const double t_pass = time_coop(reinterpret_cast<const void*>(&k_stream_passes<T>), bargs, sgrid, kBlock) * 1000.0 / passes;
  // Sync cost of the stream kernel's own (full) grid, to subtract.
  void* sargs2[] = {&syncs, &sinkp};
  const double t_sync_full = time_coop(reinterpret_cast<const void*>(&k_sync_only), sargs2, sgrid, kBlock) * 1000.0 / syncs;
  const double moved = 2.0 * n * S;
  const double t_move = std::max(t_pass - t_sync_full, 0.05);
  out.bandwidth_gbs = moved / (t_move * 1e-6) / 1e9;
  out.sync_us = t_sync;
  out.iteration_us = out.bytes_per_iteration / (out.bandwidth_gbs * 1e3) + out.syncs_per_iteration * t_sync;
  // Step floor outside CG: its bytes at the same bandwidth (an optimistic figure where the
  // data does not fit in L2), the dependent phases that need a grid-wide barrier (element,
  // assembly, two in the PCG set-up, update, rest rule, finger sums: 7), and one host
  // round trip (a synchronous step() must launch and wait at least once).
  out.step_fixed_us = step_bytes / (out.bandwidth_gbs * 1e3) + 7 * t_sync + host_round_trip_us(s, sinkp);
  out.device = d.name;
  cudaEventDestroy(e0);
  cudaEventDestroy(e1);
  CU(cudaStreamSynchronize(s));
  cudaStreamDestroy(s);
  return true;
}

}  // namespace

bool cuda_probe(std::string* why_not) {
  const DeviceInfo& d = device_info();
  if (!d.ok && why_not) *why_not = d.why;
  return d.ok;
}

std::unique_ptr<Backend> make_cuda_backend(const Model& model, const SimParams& params) {
  if (params.solver.precision == Precision::Float)
    return std::make_unique<CudaBackend<float>>(model, params, Solver::Persistent);
  return std::make_unique<CudaBackend<double>>(model, params, Solver::Persistent);
}

std::unique_ptr<Backend> make_cuda_csr_backend(const Model& model, const SimParams& params) {
#ifndef PALPATION_HAVE_CUSPARSE
  (void)model;
  (void)params;
  throw std::runtime_error("backend cuda-csr: this build has no cuSPARSE/cuBLAS");
#else
  if (params.solver.precision == Precision::Float)
    return std::make_unique<CudaBackend<float>>(model, params, Solver::Csr);
  return std::make_unique<CudaBackend<double>>(model, params, Solver::Csr);
#endif
}

bool cuda_measure_floor(const Model& model, Precision precision, FloorEstimate& out) {
  try {
    return precision == Precision::Float ? measure_floor<float>(model, out) : measure_floor<double>(model, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cuda floor: %s\n", e.what());
    return false;
  }
}

}  // namespace palpation::sim
