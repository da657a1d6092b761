// The library baselines of the benchmark (baseline.cu): the fast backend's PCG measured
// against ports of the same algorithm onto cuSPARSE and cuBLAS. Both solve the system that
// the assembly (assembly.cuh) built, then run the state update and the rest rule as
// separate kernels. Built only with cuSPARSE and cuBLAS (PALPATION_HAVE_CUSPARSE); the
// backend (backend_cuda.cu) holds either through this interface.
//
// "cuda-csr", the textbook port: the matrix seen as scalar CSR, cuSPARSE SpMV, cuBLAS
//   dot/axpy with the scalars on the host, so every dot product synchronises and the host
//   decides each iteration.
// "cuda-bsr", the good first port: the matrix as 3x3 blocks (BSR SpMV), the dot products
//   and the CG scalars kept on the GPU (cuBLAS device pointer mode, one-thread kernels for
//   alpha, beta and the stopping rule), the iterations captured in a CUDA graph and
//   replayed in chunks, the host reading back only the iteration count and stop flag after
//   each chunk.
#pragma once

#include <memory>

#include "cuda/pcg.cuh"
#include "model.h"

namespace palpation::sim::cuda {

template <class T>
class BaselineSolver {
 public:
  virtual ~BaselineSolver() = default;
  /// solve_cg.h's algorithm on the system of `a` (vals, P, b; dv = a.x warm start in,
  /// solution out; r, z, p0, q as workspace), then v += dv, x += h v and the rest rule.
  /// Enqueued on the stream it was made with.
  virtual void solve(const PcgArgs<T>& a, int& iterations, double& residual) = 0;
};

/// The textbook port for model m over the device arrays of `a` (the values array a.vals
/// with the scalar CSR pattern of m, a.x, a.p0 and a.q bound to cuSPARSE descriptors: they
/// must outlive it), working in stream s.
template <class T>
std::unique_ptr<BaselineSolver<T>> make_csr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s);

/// The good first port for model m over the device arrays of `a` (bound to cuSPARSE
/// descriptors and captured into its graphs: they must outlive it), working in stream s.
template <class T>
std::unique_ptr<BaselineSolver<T>> make_bsr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s);

}  // namespace palpation::sim::cuda
