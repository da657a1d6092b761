// The library baselines "cuda-csr" and "cuda-bsr" (see baseline.cuh): what the fast
// backend is measured against in docs/gpu-notes.md. They share the element pass and the
// assembly with "cuda" and replace the persistent PCG kernel by cuSPARSE and cuBLAS.
#include "cuda/baseline.cuh"

#include <cublas_v2.h>
#include <cusparse.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "cuda/device_info.h"

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

namespace palpation::sim::cuda {

namespace {

// Separate-kernel versions of the persistent kernel's pieces (pcg.cuh).
template <class T>
__global__ void __launch_bounds__(kBlock) k_update(PcgArgs<T> a) { update_state(a); }
template <class T>
__global__ void __launch_bounds__(kBlock) k_rest(PcgArgs<T> a) { rest_rule(a); }
template <class T>
__global__ void __launch_bounds__(kBlock) k_precondition(int n, const T* P, const T* r, T* z) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) precondition_row(P, r, z, i);
}

int grid_for(int n) { return std::max(1, std::min((n + kBlock - 1) / kBlock, 4 * device_info().sms)); }

/// After the solve: v += dv, x += h v over the free nodes, then the rest rule.
template <class T>
void finish_step(const PcgArgs<T>& a, cudaStream_t s) {
  k_update<T><<<grid_for(a.n), kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_update);
  k_rest<T><<<grid_for(3 * a.nnode), kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_rest);
}

/// A cuSPARSE and a cuBLAS handle working in one stream.
struct LibraryHandles {
  cusparseHandle_t sp = nullptr;
  cublasHandle_t bl = nullptr;
  explicit LibraryHandles(cudaStream_t s) {
    CUSP(cusparseCreate(&sp));
    CUSP(cusparseSetStream(sp, s));
    CUBL(cublasCreate(&bl));
    CUBL(cublasSetStream(bl, s));
  }
  LibraryHandles(const LibraryHandles&) = delete;
  LibraryHandles& operator=(const LibraryHandles&) = delete;
  ~LibraryHandles() {
    if (sp) cusparseDestroy(sp);
    if (bl) cublasDestroy(bl);
  }
};

template <class T>
constexpr cudaDataType kCudaType = std::is_same_v<T, double> ? CUDA_R_64F : CUDA_R_32F;

/// cuBLAS dot of n values; `out` is a host or device pointer as the handle's pointer mode says.
template <class T>
void blas_dot(cublasHandle_t h, int n, const T* a, const T* b, T* out) {
  if constexpr (std::is_same_v<T, double>)
    CUBL(cublasDdot(h, n, a, 1, b, 1, out));
  else
    CUBL(cublasSdot(h, n, a, 1, b, 1, out));
}

/// Scalar CSR pattern of the assembled values array (assembly.cuh's layout): rows
/// 3i..3i+2 of block row i, 3 len entries each, columns sorted.
void scalar_csr_pattern(const Model& m, std::vector<int>& srow_ptr, std::vector<int>& scol) {
  const int nf = m.num_free(), nb = m.num_blocks();
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

template <class T>
class CsrBaselineImpl final : public BaselineSolver<T> {
 public:
  CsrBaselineImpl(const Model& m, const PcgArgs<T>& a, cudaStream_t s)
      : stream_(s), nf_(a.n), lib_(s), sp_(lib_.sp), bl_(lib_.bl) {
    std::vector<int> srow_ptr, scol;
    scalar_csr_pattern(m, srow_ptr, scol);
    srow_ptr_.upload(srow_ptr, stream_);
    scol_.upload(scol, stream_);
    const int64_t n = 3 * int64_t(nf_), nnz = 9 * int64_t(m.num_blocks());
    // cuSPARSE takes the values non-const; SpMV only reads them.
    CUSP(cusparseCreateCsr(&mat_, n, n, nnz, srow_ptr_.get(), scol_.get(), const_cast<T*>(a.vals), CUSPARSE_INDEX_32I,
                           CUSPARSE_INDEX_32I, CUSPARSE_INDEX_BASE_ZERO, kCudaType));
    CUSP(cusparseCreateDnVec(&vec_dv_, n, a.x, kCudaType));
    CUSP(cusparseCreateDnVec(&vec_p_, n, a.p0, kCudaType));
    CUSP(cusparseCreateDnVec(&vec_q_, n, a.q, kCudaType));
    const T one = 1, zero = 0;
    std::size_t bytes = 0;
    CUSP(cusparseSpMV_bufferSize(sp_, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, vec_p_, &zero, vec_q_, kCudaType,
                                 CUSPARSE_SPMV_CSR_ALG1, &bytes));
    CU(cudaMalloc(&spmv_buf_, std::max<std::size_t>(bytes, 16)));
  }

  ~CsrBaselineImpl() override {
    if (spmv_buf_) cudaFree(spmv_buf_);
    if (mat_) cusparseDestroySpMat(mat_);
    for (auto* vd : {&vec_dv_, &vec_p_, &vec_q_})
      if (*vd) cusparseDestroyDnVec(*vd);
  }

  // solve_cg.h's algorithm, one library call per vector operation, the host deciding.
  void solve(const PcgArgs<T>& a, int& iterations, double& residual) override {
    T* x = a.x;
    T* r = a.r;
    T* z = a.z;
    T* p = a.p0;
    T* q = a.q;
    const T* b = a.b;
    const T tol = a.tol;
    const int max_it = a.max_it;
    const T bnorm = std::sqrt(dot(b, b));
    int it = 0;
    T rnorm = 0;
    if (!(bnorm > 0)) {
      zero_dv(x);
    } else {
      spmv(vec_dv_);
      copy(b, r);
      axpy(T(-1), q, r);
      rnorm = std::sqrt(dot(r, r));
      if (!std::isfinite(double(rnorm)) || rnorm > T(1e3) * bnorm) {
        zero_dv(x);
        copy(b, r);
        rnorm = bnorm;
      }
      precondition(a.P, r, z);
      copy(z, p);
      T rz = dot(r, z);
      while ((it < max_it && rnorm > tol * bnorm) || (it < a.rescue_it && rnorm > a.rescue_tol * bnorm)) {
        spmv(vec_p_);
        const T pq = dot(p, q);
        if (!(pq > 0)) break;
        const T alpha = rz / pq;
        axpy(alpha, p, x);
        axpy(-alpha, q, r);
        precondition(a.P, r, z);
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
    finish_step(a, stream_);
  }

 private:
  static constexpr cudaDataType kCudaType = cuda::kCudaType<T>;

  void spmv(cusparseDnVecDescr_t in) {
    const T one = 1, zero = 0;
    CUSP(cusparseSpMV(sp_, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, in, &zero, vec_q_, kCudaType,
                      CUSPARSE_SPMV_CSR_ALG1, spmv_buf_));
  }
  T dot(const T* a, const T* b) {
    T r = 0;
    blas_dot(bl_, 3 * nf_, a, b, &r);
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
  void zero_dv(T* x) {
    if (nf_) CU(cudaMemsetAsync(x, 0, 3 * std::size_t(nf_) * sizeof(T), stream_));
  }
  void precondition(const T* P, const T* r, T* z) {
    k_precondition<T><<<(nf_ + kBlock - 1) / kBlock, kBlock, 0, stream_>>>(nf_, P, r, z);
    CU_LAUNCHED(k_precondition);
  }

  cudaStream_t stream_;
  int nf_;
  LibraryHandles lib_;
  cusparseHandle_t sp_;
  cublasHandle_t bl_;
  DeviceArray<int> srow_ptr_, scol_;
  cusparseSpMatDescr_t mat_ = nullptr;
  cusparseDnVecDescr_t vec_dv_ = nullptr, vec_p_ = nullptr, vec_q_ = nullptr;
  void* spmv_buf_ = nullptr;
};

// ---------------------------------------------------------------------------------------
// The good first port ("cuda-bsr").

/// What the stopping rule reads: set by the host before each solve (the error controller
/// moves the tolerance from step to step), read by the one-thread kernels.
template <class T>
struct CgControl {
  T tol, rescue_tol;
  int max_it, rescue_it;
};

/// The CG scalars in device memory: cuBLAS writes the dot products here (device pointer
/// mode), the one-thread kernels turn them into alpha, beta and the stopping decision.
template <class T>
struct CgScalars {
  T bb, rr, rz, rz_new, pq;
  T alpha, beta, bnorm, rnorm;
  int it;
  int done;     // stopped (converged, capped or broken down): later iterations change nothing
  int active;   // this iteration updates x, r, z and p
  int zero_x;   // the warm start is dropped (restart, or b = 0)
  int restart;  // and r = b
};

/// solve_cg.h's stopping rule: on while above the tolerance and under the cap, or above
/// the rescue tolerance and under the rescue cap.
template <class T>
__device__ bool cg_continues(const CgControl<T>& c, int it, T rnorm, T bnorm) {
  return (it < c.max_it && rnorm > c.tol * bnorm) || (it < c.rescue_it && rnorm > c.rescue_tol * bnorm);
}

/// The assembled values (assembly.cuh: block row i's three scalar rows one after the other,
/// 3 len values each) as row-major 3x3 blocks, one warp per block row: reads coalesced,
/// writes within the row's 9 len values.
template <class T>
__global__ void __launch_bounds__(kBlock) k_to_bsr(int n, const int* row_ptr, const T* vals, T* bsr) {
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5, lane = threadIdx.x & 31;
  if (warp >= n) return;
  const int k0 = row_ptr[warp], len3 = 3 * (row_ptr[warp + 1] - k0);
  const T* src = vals + 9 * std::size_t(k0);
  T* dst = bsr + 9 * std::size_t(k0);
  for (int t = lane; t < 3 * len3; t += 32) {
    const int r = t / len3, rem = t - r * len3, kk = rem / 3, c = rem - 3 * kk;
    dst[9 * kk + 3 * r + c] = src[t];
  }
}

/// r = b - q (q = A x of the warm start).
template <class T>
__global__ void __launch_bounds__(kBlock) k_residual(int n3, const T* b, const T* q, T* r) {
  for (int j = blockIdx.x * blockDim.x + threadIdx.x; j < n3; j += gridDim.x * blockDim.x) r[j] = b[j] - q[j];
}

/// The start of a solve from ||b||^2 and ||r||^2 of the warm start: its restart rule (drop a
/// warm start that is not finite or 1e3 times b) and whether to iterate at all.
template <class T>
__global__ void k_cg_begin(const CgControl<T>* c, CgScalars<T>* s) {
  const T bnorm = sqrt(s->bb);
  T rnorm = sqrt(s->rr);
  s->restart = bnorm > T(0) && (!isfinite(rnorm) || rnorm > T(1e3) * bnorm);
  s->zero_x = !(bnorm > T(0)) || s->restart;
  if (s->restart) rnorm = bnorm;
  s->bnorm = bnorm;
  s->rnorm = rnorm;
  s->it = 0;
  s->active = 0;
  s->done = !(bnorm > T(0)) || !cg_continues(*c, 0, rnorm, bnorm);
}

/// x = 0 and r = b where the start says so; then z = P r and p = z.
template <class T>
__global__ void __launch_bounds__(kBlock) k_cg_first(int n, const CgScalars<T>* s, const T* P, const T* b, T* x, T* r,
                                                     T* z, T* p) {
  const bool zero_x = s->zero_x, restart = s->restart;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
    for (int c = 0; c < 3; ++c) {
      if (zero_x) x[3 * i + c] = T(0);
      if (restart) r[3 * i + c] = b[3 * i + c];
    }
    precondition_row(P, r, z, i);
    for (int c = 0; c < 3; ++c) p[3 * i + c] = z[3 * i + c];
  }
}

/// alpha = rz / pq, or the stop on a breakdown (pq not positive).
template <class T>
__global__ void k_cg_alpha(CgScalars<T>* s) {
  const bool go = !s->done && s->pq > T(0);
  if (!s->done && !go) s->done = 1;
  s->active = go;
  s->alpha = go ? s->rz / s->pq : T(0);
}

/// x += alpha p, r -= alpha q, z = P r (an iteration after the stop changes nothing).
template <class T>
__global__ void __launch_bounds__(kBlock) k_cg_update(int n, const CgScalars<T>* s, const T* P, const T* p, const T* q,
                                                      T* x, T* r, T* z) {
  if (!s->active) return;
  const T alpha = s->alpha;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
    for (int c = 0; c < 3; ++c) {
      x[3 * i + c] += alpha * p[3 * i + c];
      r[3 * i + c] -= alpha * q[3 * i + c];
    }
    precondition_row(P, r, z, i);
  }
}

/// beta = rz_new / rz, the iteration counted and the stopping rule applied.
template <class T>
__global__ void k_cg_beta(const CgControl<T>* c, CgScalars<T>* s) {
  if (!s->active) return;
  s->beta = s->rz_new / s->rz;
  s->rz = s->rz_new;
  s->rnorm = sqrt(s->rr);
  s->it += 1;
  s->done = !cg_continues(*c, s->it, s->rnorm, s->bnorm);
}

/// p = z + beta p.
template <class T>
__global__ void __launch_bounds__(kBlock) k_cg_direction(int n3, const CgScalars<T>* s, const T* z, T* p) {
  if (!s->active) return;
  const T beta = s->beta;
  for (int j = blockIdx.x * blockDim.x + threadIdx.x; j < n3; j += gridDim.x * blockDim.x) p[j] = z[j] + beta * p[j];
}

/// An instantiated CUDA graph, captured from the calls `record` makes on stream s.
class Graph {
 public:
  Graph() = default;
  Graph(const Graph&) = delete;
  Graph& operator=(const Graph&) = delete;
  ~Graph() {
    if (exec_) cudaGraphExecDestroy(exec_);
  }
  template <class Record>
  void capture(cudaStream_t s, Record record) {
    CU(cudaStreamBeginCapture(s, cudaStreamCaptureModeThreadLocal));
    try {
      record();
    } catch (...) {
      cudaGraph_t broken = nullptr;
      cudaStreamEndCapture(s, &broken);
      if (broken) cudaGraphDestroy(broken);
      throw;
    }
    cudaGraph_t g = nullptr;
    CU(cudaStreamEndCapture(s, &g));
    const cudaError_t e = cudaGraphInstantiate(&exec_, g, 0);
    cudaGraphDestroy(g);
    CU(e);
  }
  bool ready() const { return exec_ != nullptr; }
  void launch(cudaStream_t s) { CU(cudaGraphLaunch(exec_, s)); }

 private:
  cudaGraphExec_t exec_ = nullptr;
};

/// The good first port of solve_cg.h: the same warm start, restart, stopping and breakdown
/// rules as the persistent kernel, written as an ordinary port would be with the libraries:
/// BSR SpMV (cuSPARSE), dot products into device memory (cuBLAS device pointer mode),
/// small kernels for the rest, everything up to the first iteration captured in one graph
/// and kChunk iterations in another. The host replays the chunk graph and reads back the
/// small scalar record after each replay (one synchronisation per chunk, not per dot
/// product); the first read waits for as many chunks as the last solve took iterations.
template <class T>
class BsrGraphBaseline final : public BaselineSolver<T> {
 public:
  static constexpr int kChunk = 4;  // iterations per replay of the chunk graph

  BsrGraphBaseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s)
      : stream_(s), nf_(a.n), nb_(m.num_blocks()), lib_(s) {
    bsr_.alloc(9 * std::size_t(nb_));
    control_.alloc(1);
    scalars_.alloc(1);
    CU(cudaHostAlloc(reinterpret_cast<void**>(&host_control_), sizeof(CgControl<T>), cudaHostAllocDefault));
    CU(cudaHostAlloc(reinterpret_cast<void**>(&host_scalars_), sizeof(CgScalars<T>), cudaHostAllocDefault));
    // The dot products write into device memory; a preset workspace keeps cuBLAS from
    // allocating while a graph is captured.
    CUBL(cublasSetPointerMode(lib_.bl, CUBLAS_POINTER_MODE_DEVICE));
    workspace_.alloc(kWorkspaceBytes);
    CUBL(cublasSetWorkspace(lib_.bl, workspace_.get(), kWorkspaceBytes));
    // cuSPARSE takes the arrays non-const; SpMV only reads them.
    CUSP(cusparseCreateBsr(&mat_, nf_, nf_, nb_, 3, 3, const_cast<int*>(a.row_ptr), const_cast<int*>(a.col), bsr_.get(),
                           CUSPARSE_INDEX_32I, CUSPARSE_INDEX_32I, CUSPARSE_INDEX_BASE_ZERO, kCudaType<T>,
                           CUSPARSE_ORDER_ROW));
    const int64_t n = 3 * int64_t(nf_);
    CUSP(cusparseCreateDnVec(&vec_x_, n, a.x, kCudaType<T>));
    CUSP(cusparseCreateDnVec(&vec_p_, n, a.p0, kCudaType<T>));
    CUSP(cusparseCreateDnVec(&vec_q_, n, a.q, kCudaType<T>));
    const T one = 1, zero = 0;
    std::size_t bytes = 0;
    CUSP(cusparseSpMV_bufferSize(lib_.sp, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, vec_p_, &zero, vec_q_,
                                 kCudaType<T>, CUSPARSE_SPMV_BSR_ALG1, &bytes));
    spmv_buf_.alloc(std::max<std::size_t>(bytes, 16));
  }

  ~BsrGraphBaseline() override {
    if (mat_) cusparseDestroySpMat(mat_);
    for (auto* vd : {&vec_x_, &vec_p_, &vec_q_})
      if (*vd) cusparseDestroyDnVec(*vd);
    if (host_control_) cudaFreeHost(host_control_);
    if (host_scalars_) cudaFreeHost(host_scalars_);
  }

  void solve(const PcgArgs<T>& a, int& iterations, double& residual) override {
    if (!begin_.ready()) {  // the arrays of `a` are the backend's for its whole life
      begin_.capture(stream_, [&] { record_begin(a); });
      chunk_.capture(stream_, [&] {
        for (int k = 0; k < kChunk; ++k) record_iteration(a);
      });
    }
    *host_control_ = CgControl<T>{a.tol, a.rescue_tol, a.max_it, a.rescue_it};
    CU(cudaMemcpyAsync(control_.get(), host_control_, sizeof(CgControl<T>), cudaMemcpyHostToDevice, stream_));
    begin_.launch(stream_);
    const int most = std::max(a.max_it, a.rescue_it);
    const int max_chunks = (most + kChunk - 1) / kChunk + 1;
    // The first read after one chunk fewer than the last solve filled: iteration counts
    // move little from step to step, and a replay past the stop changes nothing.
    int chunks = std::clamp(last_iterations_ / kChunk - 1, 1, max_chunks);
    for (int k = 0; k < chunks; ++k) chunk_.launch(stream_);
    for (;;) {
      CU(cudaMemcpyAsync(host_scalars_, scalars_.get(), sizeof(CgScalars<T>), cudaMemcpyDeviceToHost, stream_));
      CU(cudaStreamSynchronize(stream_));
      if (host_scalars_->done || chunks >= max_chunks) break;
      chunk_.launch(stream_);
      ++chunks;
    }
    const CgScalars<T>& S = *host_scalars_;
    iterations = S.it;
    last_iterations_ = S.it;
    residual = S.bnorm > T(0) ? double(S.rnorm / S.bnorm) : 0.0;
    finish_step(a, stream_);
  }

 private:
  static constexpr std::size_t kWorkspaceBytes = 4u << 20;

  void spmv(cusparseDnVecDescr_t in) {
    const T one = 1, zero = 0;  // host scalars: cuSPARSE's pointer mode stays host
    CUSP(cusparseSpMV(lib_.sp, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, mat_, in, &zero, vec_q_, kCudaType<T>,
                      CUSPARSE_SPMV_BSR_ALG1, spmv_buf_.get()));
  }
  void dot(const T* x, const T* y, T* out) { blas_dot(lib_.bl, 3 * nf_, x, y, out); }

  /// The values as BSR, r = b - A x, the restart rule, z = P r, p = z and r.z.
  void record_begin(const PcgArgs<T>& a) {
    CgScalars<T>* s = scalars_.get();
    k_to_bsr<T><<<(32 * nf_ + kBlock - 1) / kBlock, kBlock, 0, stream_>>>(nf_, a.row_ptr, a.vals, bsr_.get());
    CU_LAUNCHED(k_to_bsr);
    spmv(vec_x_);
    k_residual<T><<<grid_for(3 * nf_), kBlock, 0, stream_>>>(3 * nf_, a.b, a.q, a.r);
    CU_LAUNCHED(k_residual);
    dot(a.b, a.b, &s->bb);
    dot(a.r, a.r, &s->rr);
    k_cg_begin<T><<<1, 1, 0, stream_>>>(control_.get(), s);
    CU_LAUNCHED(k_cg_begin);
    k_cg_first<T><<<grid_for(nf_), kBlock, 0, stream_>>>(nf_, s, a.P, a.b, a.x, a.r, a.z, a.p0);
    CU_LAUNCHED(k_cg_first);
    dot(a.r, a.z, &s->rz);
  }

  /// One iteration: q = A p, alpha, x and r and z, beta, p.
  void record_iteration(const PcgArgs<T>& a) {
    CgScalars<T>* s = scalars_.get();
    spmv(vec_p_);
    dot(a.p0, a.q, &s->pq);
    k_cg_alpha<T><<<1, 1, 0, stream_>>>(s);
    CU_LAUNCHED(k_cg_alpha);
    k_cg_update<T><<<grid_for(nf_), kBlock, 0, stream_>>>(nf_, s, a.P, a.p0, a.q, a.x, a.r, a.z);
    CU_LAUNCHED(k_cg_update);
    dot(a.r, a.z, &s->rz_new);
    dot(a.r, a.r, &s->rr);
    k_cg_beta<T><<<1, 1, 0, stream_>>>(control_.get(), s);
    CU_LAUNCHED(k_cg_beta);
    k_cg_direction<T><<<grid_for(3 * nf_), kBlock, 0, stream_>>>(3 * nf_, s, a.z, a.p0);
    CU_LAUNCHED(k_cg_direction);
  }

  cudaStream_t stream_;
  int nf_, nb_;
  LibraryHandles lib_;
  DeviceArray<T> bsr_;
  DeviceArray<CgControl<T>> control_;
  DeviceArray<CgScalars<T>> scalars_;
  DeviceArray<unsigned char> workspace_, spmv_buf_;
  CgControl<T>* host_control_ = nullptr;
  CgScalars<T>* host_scalars_ = nullptr;
  cusparseSpMatDescr_t mat_ = nullptr;
  cusparseDnVecDescr_t vec_x_ = nullptr, vec_p_ = nullptr, vec_q_ = nullptr;
  Graph begin_, chunk_;
  int last_iterations_ = 0;
};

}  // namespace

template <class T>
std::unique_ptr<BaselineSolver<T>> make_csr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s) {
  return std::make_unique<CsrBaselineImpl<T>>(m, a, s);
}

template <class T>
std::unique_ptr<BaselineSolver<T>> make_bsr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s) {
  return std::make_unique<BsrGraphBaseline<T>>(m, a, s);
}

template std::unique_ptr<BaselineSolver<float>> make_csr_baseline<float>(const Model&, const PcgArgs<float>&,
                                                                         cudaStream_t);
template std::unique_ptr<BaselineSolver<double>> make_csr_baseline<double>(const Model&, const PcgArgs<double>&,
                                                                           cudaStream_t);
template std::unique_ptr<BaselineSolver<float>> make_bsr_baseline<float>(const Model&, const PcgArgs<float>&,
                                                                         cudaStream_t);
template std::unique_ptr<BaselineSolver<double>> make_bsr_baseline<double>(const Model&, const PcgArgs<double>&,
                                                                           cudaStream_t);

}  // namespace palpation::sim::cuda
