// Assembly stage of the CUDA backends: the 3x3-block system matrix, its block-Jacobi
// inverse and the right-hand side, gathered from the element records (element.cuh): one
// thread per block, over the element pairs that add to it (listed once, when the backend
// is made), and one thread per block row for its right-hand side. No atomics, every
// output written once.
//
// Matrix layout: the blocks of block-row i (k0 = row_ptr[i], len blocks) are stored so
// that the whole matrix is also a valid scalar CSR matrix (rows 3i..3i+2, columns sorted):
// value (k, r, c) at 9 k0 + r (3 len) + 3 (k - k0) + c. The fast SpMV (pcg.cu) reads it
// with kGroup lanes per block row; the baseline's cuSPARSE (baseline.cu) reads it as CSR.
#pragma once

#include "cuda/common.cuh"
#include "fem_membrane.h"

namespace palpation::sim::cuda {

template <class T>
struct AssembleArgs {
  int nf, nb;
  const int* row_ptr;     // (nf + 1)
  const int* block_row;   // (nb) block row of each block
  const int* diag_block;  // (nf) the diagonal block of each block row
  // The element pairs that add to each block (pair_ptr: nb + 1), e << 4 | a << 2 | b for
  // the block of element e's nodes a (row) and b (column), by ascending e. The diagonal
  // block's are (e, a, a) for every element around its node: the right-hand side's too.
  const int* pair_ptr;
  const int* pairs;
  const T* rec;
  // The nodal-pressure term's couplings of the free nodes' pressure rows (pressure.cuh),
  // summed here over the same element pairs: block k = (dof n, j) writes b_nj, pair
  // pres_pair[k], as sum (V_e / 4) r_{e,j}. Off when pres_b is null.
  T* pres_b;
  const int* pres_pair;  // (nb)
  const T* vol;          // (ne)
  const int* free_nodes;
  const int* free_surf;  // (nf) surface index or -1
  const T* mass;         // (nnode)
  const T* v;
  const double* cA;
  const double* cb;
  T* vals;               // (9 nb) system matrix, CSR-compatible layout
  // The diagonal blocks' inverses for block-Jacobi; written only when `invert`: the
  // nodal-pressure stage (pressure.cuh) forms every one again with its own term.
  T* precond;            // (nf x 9)
  int invert;
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

/// Launches k_assemble in stream s: nb + nf threads, kBlock a block.
template <class T>
void launch_assemble(cudaStream_t s, const AssembleArgs<T>& a);

/// The skin membrane (fem_membrane.h) added onto the assembled system: per triangle, its
/// scaled blocks into vals and h (f_a - (beta + h) (K v)_a) into b. Triangles share nodes,
/// so these adds are atomic; a surface holds a few thousand triangles against the
/// elements' tens of thousands, which keeps the contention small.
template <class T>
struct SkinArgs {
  int ntri;
  const int* tri;                  // (ntri x 3) nodes
  const membrane::Rest<T>* rest;   // (ntri)
  const int* row;                  // (ntri x 3) 3 x free index of each node, -1 if fixed
  const int* base;                 // (ntri x 9) vals offset of block (a, b): 9 k0 + 3 (k - k0); -1 if fixed
  const int* stride;               // (ntri x 9) its row stride, 3 len
  const T* x;
  const T* v;
  T lambda_p, mu, h, damp, kscale;  // damp = beta + h, kscale = h^2 + h beta
  T* vals;
  T* b;
  // Block-Jacobi after the adds: the free nodes under the skin get the inverse of their
  // diagonal block again (the nodal-pressure stage inverts every node itself).
  int nskin_free;
  const int* skin_free;            // (nskin_free) free index
  const int* row_ptr;
  const int* diag_block;
  T* precond;
};

/// Launches the skin stage in stream s; `invert`: also re-invert the diagonal blocks under
/// the skin.
template <class T>
void launch_skin(cudaStream_t s, const SkinArgs<T>& a, bool invert);

}  // namespace palpation::sim::cuda
