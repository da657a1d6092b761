// The textbook baseline "cuda-csr" (see baseline.cuh): what the fast backend is measured
// against in docs/gpu-notes.md. It shares the element pass and the assembly with "cuda"
// and replaces the persistent PCG kernel by this host-driven loop.
#include "cuda/baseline.cuh"

#include <cublas_v2.h>
#include <cusparse.h>

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
class CsrBaselineImpl final : public CsrBaseline<T> {
 public:
  CsrBaselineImpl(const Model& m, const PcgArgs<T>& a, cudaStream_t s) : stream_(s), nf_(a.n), nn_(a.nnode) {
    std::vector<int> srow_ptr, scol;
    scalar_csr_pattern(m, srow_ptr, scol);
    srow_ptr_.upload(srow_ptr, stream_);
    scol_.upload(scol, stream_);
    CUSP(cusparseCreate(&sp_));
    CUSP(cusparseSetStream(sp_, stream_));
    CUBL(cublasCreate(&bl_));
    CUBL(cublasSetStream(bl_, stream_));
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
    if (sp_) cusparseDestroy(sp_);
    if (bl_) cublasDestroy(bl_);
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
    const int g = std::max(1, std::min((nf_ + kBlock - 1) / kBlock, 4 * device_info().sms));
    k_update<T><<<g, kBlock, 0, stream_>>>(a);
    CU_LAUNCHED(k_update);
    const int g2 = std::max(1, std::min((3 * nn_ + kBlock - 1) / kBlock, 4 * device_info().sms));
    k_rest<T><<<g2, kBlock, 0, stream_>>>(a);
    CU_LAUNCHED(k_rest);
  }

 private:
  static constexpr cudaDataType kCudaType = std::is_same_v<T, double> ? CUDA_R_64F : CUDA_R_32F;

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
  void zero_dv(T* x) {
    if (nf_) CU(cudaMemsetAsync(x, 0, 3 * std::size_t(nf_) * sizeof(T), stream_));
  }
  void precondition(const T* P, const T* r, T* z) {
    k_precondition<T><<<(nf_ + kBlock - 1) / kBlock, kBlock, 0, stream_>>>(nf_, P, r, z);
    CU_LAUNCHED(k_precondition);
  }

  cudaStream_t stream_;
  int nf_, nn_;
  DeviceArray<int> srow_ptr_, scol_;
  cusparseHandle_t sp_ = nullptr;
  cublasHandle_t bl_ = nullptr;
  cusparseSpMatDescr_t mat_ = nullptr;
  cusparseDnVecDescr_t vec_dv_ = nullptr, vec_p_ = nullptr, vec_q_ = nullptr;
  void* spmv_buf_ = nullptr;
};

}  // namespace

template <class T>
std::unique_ptr<CsrBaseline<T>> make_csr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s) {
  return std::make_unique<CsrBaselineImpl<T>>(m, a, s);
}

template std::unique_ptr<CsrBaseline<float>> make_csr_baseline<float>(const Model&, const PcgArgs<float>&, cudaStream_t);
template std::unique_ptr<CsrBaseline<double>> make_csr_baseline<double>(const Model&, const PcgArgs<double>&,
                                                                        cudaStream_t);

}  // namespace palpation::sim::cuda
