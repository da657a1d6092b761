// The textbook baseline "cuda-csr" (baseline.cu): the system that the assembly
// (assembly.cuh) built, seen as a scalar CSR matrix; cuSPARSE SpMV, cuBLAS dot/axpy, the
// host driving each CG iteration (a synchronising dot product per reduction); then the
// state update and the rest rule as separate kernels. Built only with cuSPARSE and cuBLAS
// (PALPATION_HAVE_CUSPARSE); the backend (backend_cuda.cu) holds it through this interface.
#pragma once

#include <memory>

#include "cuda/pcg.cuh"
#include "model.h"

namespace palpation::sim::cuda {

template <class T>
class CsrBaseline {
 public:
  virtual ~CsrBaseline() = default;
  /// solve_cg.h's algorithm on the system of `a` (vals, P, b; dv = a.x warm start in,
  /// solution out; r, z, p0, q as workspace), one library call per vector operation,
  /// then v += dv, x += h v and the rest rule. Enqueued on the stream it was made with.
  virtual void solve(const PcgArgs<T>& a, int& iterations, double& residual) = 0;
};

/// Makes the baseline for model m over the device arrays of `a` (the values array a.vals
/// with the scalar CSR pattern of m, a.x, a.p0 and a.q bound to cuSPARSE descriptors: they
/// must outlive it), working in stream s.
template <class T>
std::unique_ptr<CsrBaseline<T>> make_csr_baseline(const Model& m, const PcgArgs<T>& a, cudaStream_t s);

}  // namespace palpation::sim::cuda
