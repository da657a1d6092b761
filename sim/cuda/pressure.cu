// Nodal-pressure stage: couplings, pressures, right-hand side and preconditioner (see
// pressure.cuh).
#include "cuda/pressure.cuh"

#include "cuda/element.cuh"

namespace palpation::sim::cuda {

namespace {

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_pairs(PressureArgs<T> a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= a.nfixed) return;
  const int k = a.fixed_pairs[t];
  T b0 = 0, b1 = 0, b2 = 0;
  for (int l = a.pinc_ptr[t]; l < a.pinc_ptr[t + 1]; ++l) {
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

// The sums of the two kernels below are a few dozen terms per node over scattered
// indices: one thread per node left three quarters of the multiprocessors idle on the
// paper mesh (33 blocks of 256 for 8.4k nodes, 50 us on an H200). A group of lanes per
// node splits each sum and adds the parts by shuffles.
constexpr int kNodeLanes = 8;  // k_pressure_nodes: about 25 elements and 20 pairs a node
constexpr int kFreeLanes = 4;  // k_pressure_free: about 15 pairs a free node

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_nodes(PressureArgs<T> a) {
  constexpr int G = kNodeLanes;
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  const int n = t / G, gl = t % G;
  // No early return: every lane of the warp takes part in the shuffles.
  T s = 0;
  if (n < a.nnode) {
    for (int l = a.ninc_ptr[n] + gl; l < a.ninc_ptr[n + 1]; l += G) s += a.rest_part[__ldg(a.ninc + l)];
    for (int k = a.P.row_ptr[n] + gl; k < a.P.row_ptr[n + 1]; k += G) {
      const int node = a.free_nodes[a.P.col[k]];
      const T* bk = a.P.b + 3 * std::size_t(k);
#pragma unroll
      for (int c = 0; c < 3; ++c) s += bk[c] * (a.x[3 * node + c] - a.rest[3 * node + c] + a.damp * a.v[3 * node + c]);
    }
  }
  s = group_sum<G>(s);
  if (n < a.nnode && gl == 0) a.P.pi[n] = a.P.w[n] * s;
}

template <class T>
__global__ void __launch_bounds__(kBlock) k_pressure_free(PressureArgs<T> a) {
  constexpr int G = kFreeLanes;
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = t / G, gl = t % G;
  // g, then the symmetric D = sum w b b^T by its upper triangle (xx xy xz yy yz zz).
  T g[3] = {0, 0, 0}, D[6] = {0, 0, 0, 0, 0, 0};
  if (j < a.nf) {
    for (int k = a.P.t_row_ptr[j] + gl; k < a.P.t_row_ptr[j + 1]; k += G) {
      const T* bk = a.P.b + 3 * std::size_t(a.P.t_pair[k]);
      const int n = a.P.t_node[k];
      const T pin = a.P.pi[n], wn = a.P.w[n];
      const T b0 = bk[0], b1 = bk[1], b2 = bk[2];
      g[0] += b0 * pin;
      g[1] += b1 * pin;
      g[2] += b2 * pin;
      D[0] += wn * b0 * b0;
      D[1] += wn * b0 * b1;
      D[2] += wn * b0 * b2;
      D[3] += wn * b1 * b1;
      D[4] += wn * b1 * b2;
      D[5] += wn * b2 * b2;
    }
  }
#pragma unroll
  for (int c = 0; c < 3; ++c) g[c] = group_sum<G>(g[c]);
#pragma unroll
  for (int c = 0; c < 6; ++c) D[c] = group_sum<G>(D[c]);
  if (j >= a.nf || gl != 0) return;
#pragma unroll
  for (int c = 0; c < 3; ++c) a.b[3 * j + c] -= a.h * g[c];
  // The assembled diagonal block (mass, contact and kscale K) plus kscale diag(B^T W B).
  const int k0 = a.row_ptr[j], len3 = 3 * (a.row_ptr[j + 1] - k0);
  const T* dv = a.vals + 9 * std::size_t(k0) + 3 * (a.diag_block[j] - k0);
  constexpr int kUpper[9] = {0, 1, 2, 1, 3, 4, 2, 4, 5};  // row-major 3x3 -> upper triangle
  T A[9];
#pragma unroll
  for (int r = 0; r < 3; ++r)
#pragma unroll
    for (int c = 0; c < 3; ++c) A[3 * r + c] = dv[r * len3 + c] + a.P.scale * D[kUpper[3 * r + c]];
  T inv[9];
  invert3(A, inv);
#pragma unroll
  for (int q = 0; q < 9; ++q) a.precond[9 * j + q] = inv[q];
}

}  // namespace

template <class T>
void launch_pressure(cudaStream_t s, const PressureArgs<T>& a) {
  if (a.nfixed > 0) {
    k_pressure_pairs<T><<<(a.nfixed + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
    CU_LAUNCHED(k_pressure_pairs);
  }
  k_pressure_nodes<T><<<(a.nnode * kNodeLanes + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_pressure_nodes);
  k_pressure_free<T><<<(a.nf * kFreeLanes + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_pressure_free);
}

template void launch_pressure<float>(cudaStream_t, const PressureArgs<float>&);
template void launch_pressure<double>(cudaStream_t, const PressureArgs<double>&);

}  // namespace palpation::sim::cuda
