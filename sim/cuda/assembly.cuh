// Assembly stage of the CUDA backends: the 3x3-block system matrix, its block-Jacobi
// inverse and the right-hand side, gathered from the element records (element.cuh) by one
// warp per block row: no atomics, every output written once.
//
// Matrix layout: the blocks of block-row i (k0 = row_ptr[i], len blocks) are stored so
// that the whole matrix is also a valid scalar CSR matrix (rows 3i..3i+2, columns sorted):
// value (k, r, c) at 9 k0 + r (3 len) + 3 (k - k0) + c. The fast SpMV (pcg.cu) reads it
// with kGroup lanes per block row; the baseline's cuSPARSE (baseline.cu) reads it as CSR.
#pragma once

#include "cuda/common.cuh"

namespace palpation::sim::cuda {

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
  // The PCG's warm start (backend_cpu.cpp's rule): after a converged solve the last two
  // solutions extrapolated, dv = 2 dv - dv_prev; else dv as it is. dv_prev takes the
  // last solution either way.
  T* dv;                 // (nf x 3)
  T* dv_prev;            // (nf x 3)
  int extrapolate;
  T kscale, mscale, h, alpha;
  T g0, g1, g2;
};

/// Launches k_assemble in stream s: one warp per block row, kBlock threads per block.
template <class T>
void launch_assemble(cudaStream_t s, const AssembleArgs<T>& a);

}  // namespace palpation::sim::cuda
