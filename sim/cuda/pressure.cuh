// Nodal-pressure stage of the CUDA backend: the average-nodal-pressure volumetric term
// B^T W B of nodal_pressure.h on the GPU (backend_cpu.cpp, nodal_pressure_forces and
// rotate_pairs, is the specification), kept factored as on the CPU.
//
// Per step, after k_assemble (whose element records carry no lambda: the element's
// volumetric part lives here):
//   k_pressure_pairs one thread per pair (n, j) of a fixed node n: its coupling b_nj = sum
//                    over the elements holding both of (V_e / 4) r_{e,j}, afresh from the
//                    element records (the GPU re-rotates every element every step, so
//                    nothing is kept). The free nodes' pairs are blocks of the system: the
//                    assembly forms them from the same element pairs (assembly.cuh).
//   k_pressure_nodes a group of lanes per node n (every node: the chest wall's pressures act on
//                    their free neighbours): the rest part c_n = sum over its elements of
//                    (V_e / 4) (tr R_e - 3) and its pressure
//                    pi_n = w_n (sum_j b_nj . (u + (beta + h) v)_j + c_n).
//   k_pressure_free  a group of lanes per free node j: the right-hand side loses
//                    h (B^T pi)_j, and its block-Jacobi inverse is formed again with the
//                    term's diagonal block kscale sum_n w_n b_nj b_nj^T added.
// Inside k_pcg each product A p gains kscale B^T W B p: the pressures of p over every node
// (pressure_rows, one more grid barrier per iteration), then (B^T pi)_i added to each
// row's SpMV result (pressure_gather).
#pragma once

#include "cuda/common.cuh"

namespace palpation::sim::cuda {

/// B (by pressure rows and by free columns), W and the pressures: what the PCG needs.
/// Off when b is null.
template <class T>
struct PressureDev {
  const int* row_ptr = nullptr;    // (nnode + 1) pairs of each pressure row
  const int* col = nullptr;        // (npair) free index j of each pair
  const int* t_row_ptr = nullptr;  // (nf + 1) pairs of each free column
  const int* t_node = nullptr;     // (npair) pressure node n of each of those
  const int* t_pair = nullptr;     // (npair) pair index of each of those
  T* b = nullptr;                  // (npair x 3) couplings b_nj
  const T* w = nullptr;            // (nnode) lambda_n / V_n
  T* pi = nullptr;                 // (nnode) the pressures of the last product
  T scale = 0;                     // the stiffness factor h^2 + h beta of the step
};

template <class T>
struct PressureArgs {
  PressureDev<T> P;
  int nnode, nf;
  int nfixed;            // the pairs (n, j) of fixed nodes n, which the assembly does not form
  const int* fixed_pairs;  // (nfixed)
  const int* pinc_ptr;   // (nfixed + 1) the elements holding each fixed pair, by its slot
  const int* pinc;       // e << 2 | b, b the local index of j
  const int* ninc_ptr;   // (nnode + 1) the elements at every node
  const int* ninc;       // e
  const T* rec;          // element records (element.cuh): r_a at 3 a
  const T* vol;          // (ne)
  const T* rest_part;    // (ne) (V_e / 4) (tr R_e - 3), written by k_element
  const int* free_nodes;
  const T* x;
  const T* v;
  const T* rest;         // (3 nnode)
  T damp;                // beta + h
  T h;
  const int* row_ptr;    // (nf + 1) the system's block rows
  const int* diag_block; // (nf) block index of each row's diagonal
  const T* vals;         // the assembled system (assembly.cuh layout)
  T* b;                  // (nf x 3) right-hand side
  T* precond;            // (nf x 9) block-Jacobi inverse
};

/// Launches k_pressure_pairs (where fixed nodes have pairs), k_pressure_nodes and
/// k_pressure_free in stream s, after the assembly (which forms the free rows' pairs).
template <class T>
void launch_pressure(cudaStream_t s, const PressureArgs<T>& a);

/// pi_n = scale w_n sum_j b_nj . u_j for every node, G lanes a node (grid-stride over the
/// warps, as the SpMV: warp-uniform bounds, every lane in every shuffle); fetch(j, c)
/// reads component c of the vector at free node j.
template <class T, int G, class Fetch>
__device__ __forceinline__ void pressure_rows(const PressureDev<T>& P, int nnode, Fetch fetch, int tid, int nthreads) {
  constexpr int RPW = 32 / G;
  const int lane = threadIdx.x & 31, gl = lane % G, gw = lane / G;
  const int warp = tid >> 5, nwarps = nthreads >> 5;
  for (int base = warp * RPW; base < nnode; base += nwarps * RPW) {
    const int n = base + gw;
    T s = 0;
    if (n < nnode)
      for (int k = P.row_ptr[n] + gl; k < P.row_ptr[n + 1]; k += G) {
        const int j = P.col[k];
        const T* bk = P.b + 3 * std::size_t(k);
        s += bk[0] * fetch(j, 0) + bk[1] * fetch(j, 1) + bk[2] * fetch(j, 2);
      }
    s = group_sum<G>(s);
    if (n < nnode && gl == 0) P.pi[n] = P.scale * P.w[n] * s;
  }
}

/// Adds lane gl's share (pairs gl, gl + G, ...) of (B^T pi)_i to y; the caller's
/// reduction over the G lanes completes it. Plain loads: pi was written in the same
/// kernel before a grid barrier (the read-only cache is not coherent with that).
template <class T, int G>
__device__ __forceinline__ void pressure_gather(const PressureDev<T>& P, int i, int gl, T& y0, T& y1, T& y2) {
  for (int k = P.t_row_ptr[i] + gl; k < P.t_row_ptr[i + 1]; k += G) {
    const T* bk = P.b + 3 * std::size_t(P.t_pair[k]);
    const T pn = P.pi[P.t_node[k]];
    y0 += bk[0] * pn;
    y1 += bk[1] * pn;
    y2 += bk[2] * pn;
  }
}

}  // namespace palpation::sim::cuda
