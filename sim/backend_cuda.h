// The CUDA backends. Declared here, implemented in sim/cuda/ (one file per stage:
// backend_cuda.cu composes them, baseline.cu the library baselines, floor_bench.cu the floor);
// only backend.cpp includes this header, and only in builds with PALPATION_HAVE_CUDA.
//
// "cuda"     : the fast backend. Every per-step computation on the GPU: contact
//              detection, per-element corotation and forces, assembly of the 3x3-block
//              system by gathering (no atomics), block-Jacobi PCG inside one persistent
//              cooperative kernel (two grid-wide barriers per iteration, no host round
//              trip), the state update, rest detection and the finger outputs. One small
//              copy back per step (finger sums and solver statistics). See
//              docs/gpu-notes.md for the design and the measurements behind it.
// "cuda-csr" : the textbook baseline of the benchmark: the same assembled matrix seen as
//              a scalar CSR matrix, cuSPARSE SpMV, cuBLAS dot/axpy, the host driving each
//              CG iteration (a synchronising dot product per reduction).
// "cuda-bsr" : the good first port: 3x3-block (BSR) SpMV, the dot products and CG scalars
//              kept on the GPU (cuBLAS device pointer mode), the iterations replayed from a
//              CUDA graph in chunks of four, one read-back per chunk (baseline.cuh).
#pragma once

#include <memory>
#include <string>

#include "backend.h"

namespace palpation::sim {

/// True when a CUDA device is present and usable by this build (driver new enough,
/// compute capability at least 6.0). `why_not` says why not, in one line.
bool cuda_probe(std::string* why_not = nullptr);

/// Makes the fast CUDA backend in the precision of params.solver.precision.
/// Throws std::runtime_error when the device cannot be used.
std::unique_ptr<Backend> make_cuda_backend(const Model& model, const SimParams& params);

/// Makes the library baseline `name` ("cuda-csr" or "cuda-bsr") in the precision of
/// params.solver.precision. Throws std::runtime_error when this build has no
/// cuSPARSE/cuBLAS.
std::unique_ptr<Backend> make_cuda_baseline_backend(const std::string& name, const Model& model,
                                                    const SimParams& params);

/// Measures the floor of one CG iteration of the fast backend on this model: the bytes
/// its iteration must move, the grid-wide barriers it needs, and the bandwidth and
/// barrier cost measured on the device now, with the same launch configuration.
bool cuda_measure_floor(const Model& model, Precision precision, FloorEstimate& out);

}  // namespace palpation::sim
