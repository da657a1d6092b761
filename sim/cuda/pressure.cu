// Nodal-pressure stage: couplings, pressures, right-hand side and preconditioner (see
// pressure.cuh).
#include "cuda/pressure.cuh"

#include "cuda/element.cuh"

namespace palpation::sim::cuda {

namespace {

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_pairs(PressureArgs<T> a) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= a.npair) return;
  T b0 = 0, b1 = 0, b2 = 0;
  for (int l = a.pinc_ptr[k]; l < a.pinc_ptr[k + 1]; ++l) {
    const int e = __ldg(a.pinc + l) >> 2, ib = __ldg(a.pinc + l) & 3;
    const T q = T(0.25) * __ldg(a.vol + e);
    const T* r = a.rec + std::size_t(kRec) * e + 3 * ib;
    b0 += q * r[0];
    b1 += q * r[1];
    b2 += q * r[2];
  }
  T* bk = a.P.b + 3 * std::size_t(k);
  bk[0] = b0;
  bk[1] = b1;
  bk[2] = b2;
}

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_nodes(PressureArgs<T> a) {
  const int n = blockIdx.x * blockDim.x + threadIdx.x;
  if (n >= a.nnode) return;
  T s = 0;
  for (int l = a.ninc_ptr[n]; l < a.ninc_ptr[n + 1]; ++l) s += a.rest_part[__ldg(a.ninc + l)];
  for (int k = a.P.row_ptr[n]; k < a.P.row_ptr[n + 1]; ++k) {
    const int node = a.free_nodes[a.P.col[k]];
    const T* bk = a.P.b + 3 * std::size_t(k);
#pragma unroll
    for (int c = 0; c < 3; ++c) s += bk[c] * (a.x[3 * node + c] - a.rest[3 * node + c] + a.damp * a.v[3 * node + c]);
  }
  a.P.pi[n] = a.P.w[n] * s;
}

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_free(PressureArgs<T> a) {
  const int j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= a.nf) return;
  T g[3] = {0, 0, 0}, D[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int k = a.P.t_row_ptr[j]; k < a.P.t_row_ptr[j + 1]; ++k) {
    const T* bk = a.P.b + 3 * std::size_t(a.P.t_pair[k]);
    const int n = a.P.t_node[k];
    const T pin = a.P.pi[n], wn = a.P.w[n];
#pragma unroll
    for (int r = 0; r < 3; ++r) {
      g[r] += bk[r] * pin;
#pragma unroll
      for (int c = 0; c < 3; ++c) D[3 * r + c] += wn * bk[r] * bk[c];
    }
  }
#pragma unroll
  for (int c = 0; c < 3; ++c) a.b[3 * j + c] -= a.h * g[c];
  // The assembled diagonal block (mass, contact and kscale K) plus kscale diag(B^T W B).
  const int k0 = a.row_ptr[j], len3 = 3 * (a.row_ptr[j + 1] - k0);
  const T* dv = a.vals + 9 * std::size_t(k0) + 3 * (a.diag_block[j] - k0);
  T A[9];
#pragma unroll
  for (int r = 0; r < 3; ++r)
#pragma unroll
    for (int c = 0; c < 3; ++c) A[3 * r + c] = dv[r * len3 + c] + a.P.scale * D[3 * r + c];
  T inv[9];
  invert3(A, inv);
#pragma unroll
  for (int q = 0; q < 9; ++q) a.precond[9 * j + q] = inv[q];
}

}  // namespace

template <class T>
void launch_pressure(cudaStream_t s, const PressureArgs<T>& a) {
  k_pressure_pairs<T><<<(a.npair + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_pressure_pairs);
  k_pressure_nodes<T><<<(a.nnode + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_pressure_nodes);
  k_pressure_free<T><<<(a.nf + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_pressure_free);
}

template void launch_pressure<float>(cudaStream_t, const PressureArgs<float>&);
template void launch_pressure<double>(cudaStream_t, const PressureArgs<double>&);

}  // namespace palpation::sim::cuda
