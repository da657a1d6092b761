// Assembly stage: gathering the element records into the block system (see assembly.cuh).
#include "cuda/assembly.cuh"

#include "cuda/element.cuh"

namespace palpation::sim::cuda {

namespace {

/// Block row i is one warp: lane l owns block k0 + l (rows longer than 32 blocks take more
/// passes). The warp stages the records of the elements around node i in shared memory
/// (up to 32 at a time, all loads issued together, coalesced), then walks them: the lane
/// whose column node is element node b adds
///   K_ab = V (lambda r_a r_b^T + mu r_b r_a^T + mu (r_a . r_b) I)     (r_a . r_b = g_a . g_b)
/// and lanes 0..2 add component c of Q r_a to the right-hand side. Every output is
/// written once: no atomics, no element colouring.
template <class T>
__global__ void __launch_bounds__(kBlock) k_assemble(AssembleArgs<T> a) {
  constexpr int kWarps = kBlock / 32;
  __shared__ T srec[kWarps][32][kRec];
  __shared__ int4 stet[kWarps][32];
  __shared__ int sinc[kWarps][32];
  const int lane = threadIdx.x & 31, w = threadIdx.x >> 5;
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5;
  const int nwarps = (gridDim.x * blockDim.x) >> 5;
  for (int i = warp; i < a.nf; i += nwarps) {
    const int k0 = a.row_ptr[i], len = a.row_ptr[i + 1] - k0, len3 = 3 * len;
    const int node_i = a.free_nodes[i];
    const int l0 = a.inc_ptr[i], l1 = a.inc_ptr[i + 1];
    for (int base = 0; base < len; base += 32) {
      const int kk = base + lane;
      const int jnode = kk < len ? a.col_node[k0 + kk] : -1;
      T acc[9];
#pragma unroll
      for (int j = 0; j < 9; ++j) acc[j] = T(0);
      T rhs = 0;
      for (int c0 = l0; c0 < l1; c0 += 32) {
        const int cnt = min(32, l1 - c0);
        __syncwarp();
        if (lane < cnt) sinc[w][lane] = __ldg(a.inc + c0 + lane);
        __syncwarp();
        if (lane < cnt) stet[w][lane] = __ldg(a.tets + (sinc[w][lane] >> 2));
        for (int idx = lane; idx < cnt * kRec; idx += 32) {
          const int j = idx / kRec, comp = idx - j * kRec;
          srec[w][j][comp] = a.rec[std::size_t(kRec) * (sinc[w][j] >> 2) + comp];
        }
        __syncwarp();
#pragma unroll 2
        for (int j = 0; j < cnt; ++j) {
          const int ia = sinc[w][j] & 3;
          const int4 t = stet[w][j];
          const T* rec = srec[w][j];
          const int ib = t.x == jnode ? 0 : t.y == jnode ? 1 : t.z == jnode ? 2 : t.w == jnode ? 3 : -1;
          const T ra0 = rec[3 * ia], ra1 = rec[3 * ia + 1], ra2 = rec[3 * ia + 2];
          if (ib >= 0) {
            const T rb0 = rec[3 * ib], rb1 = rec[3 * ib + 1], rb2 = rec[3 * ib + 2];
            const T lv = rec[12], mv = rec[13];
            const T ra[3] = {ra0, ra1, ra2}, rb[3] = {rb0, rb1, rb2};
#pragma unroll
            for (int r = 0; r < 3; ++r)
#pragma unroll
              for (int c = 0; c < 3; ++c) acc[3 * r + c] += lv * ra[r] * rb[c] + mv * rb[r] * ra[c];
            const T d = mv * (ra0 * rb0 + ra1 * rb1 + ra2 * rb2);
            acc[0] += d;
            acc[4] += d;
            acc[8] += d;
          }
          if (base == 0 && lane < 3) {
            // Q row `lane` (symmetric, stored xx xy xz yy yz zz) times r_a.
            const int q0 = lane == 0 ? 14 : (lane == 1 ? 15 : 16);
            const int q1 = lane == 0 ? 15 : (lane == 1 ? 17 : 18);
            const int q2 = lane == 0 ? 16 : (lane == 1 ? 18 : 19);
            rhs += rec[q0] * ra0 + rec[q1] * ra1 + rec[q2] * ra2;
          }
        }
      }
      if (kk < len) {
#pragma unroll
        for (int j = 0; j < 9; ++j) acc[j] *= a.kscale;
        if (jnode == node_i) {
          const T mm = a.mscale * a.mass[node_i];
          acc[0] += mm;
          acc[4] += mm;
          acc[8] += mm;
          const int s = a.free_surf[i];
          if (s >= 0) {
            const double* c = a.cA + 6 * s;
            acc[0] += T(c[0]);
            acc[1] += T(c[1]);
            acc[2] += T(c[2]);
            acc[3] += T(c[1]);
            acc[4] += T(c[3]);
            acc[5] += T(c[4]);
            acc[6] += T(c[2]);
            acc[7] += T(c[4]);
            acc[8] += T(c[5]);
          }
          T inv[9];
          invert3(acc, inv);
#pragma unroll
          for (int j = 0; j < 9; ++j) a.precond[9 * i + j] = inv[j];
        }
        T* dst = a.vals + 9 * std::size_t(k0) + 3 * kk;
#pragma unroll
        for (int r = 0; r < 3; ++r)
#pragma unroll
          for (int c = 0; c < 3; ++c) dst[r * len3 + c] = acc[3 * r + c];
      }
      if (base == 0 && lane < 3) {
        // b = h (f + m g - alpha M v - (beta + h) K v) + contact; the element terms are in rhs.
        const T m = a.mass[node_i];
        const T gc = lane == 0 ? a.g0 : (lane == 1 ? a.g1 : a.g2);
        T bc = rhs + a.h * (m * gc - a.alpha * m * a.v[3 * node_i + lane]);
        const int s = a.free_surf[i];
        if (s >= 0) bc += T(a.cb[3 * s + lane]);
        a.b[3 * i + lane] = bc;
        const T cur = a.dv[3 * i + lane];
        if (a.extrapolate) a.dv[3 * i + lane] = T(2) * cur - a.dv_prev[3 * i + lane];
        a.dv_prev[3 * i + lane] = cur;
      }
    }
  }
}

template <class T>
__global__ void __launch_bounds__(kBlock) k_skin(SkinArgs<T> a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= a.ntri) return;
  T x[9], v[9];
#pragma unroll
  for (int n = 0; n < 3; ++n) {
    const int node = __ldg(a.tri + 3 * t + n);
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      x[3 * n + c] = a.x[3 * node + c];
      v[3 * n + c] = a.v[3 * node + c];
    }
  }
  const membrane::Rest<T> r = a.rest[t];
  T f[9], K[81];
  membrane::element(r, x, a.lambda_p, a.mu, f, K);
#pragma unroll
  for (int n = 0; n < 3; ++n) {
    const int row = __ldg(a.row + 3 * t + n);
    if (row < 0) continue;
#pragma unroll
    for (int i = 0; i < 3; ++i) {
      T kv = 0;
#pragma unroll
      for (int m = 0; m < 3; ++m)
#pragma unroll
        for (int j = 0; j < 3; ++j) kv += K[9 * (3 * n + m) + 3 * i + j] * v[3 * m + j];
      atomicAdd(a.b + row + i, a.h * (f[3 * n + i] - a.damp * kv));
    }
  }
#pragma unroll
  for (int ab = 0; ab < 9; ++ab) {
    const int base = __ldg(a.base + 9 * t + ab);
    if (base < 0) continue;
    const int stride = __ldg(a.stride + 9 * t + ab);
#pragma unroll
    for (int i = 0; i < 3; ++i)
#pragma unroll
      for (int j = 0; j < 3; ++j) atomicAdd(a.vals + base + i * stride + j, a.kscale * K[9 * ab + 3 * i + j]);
  }
}

template <class T>
__global__ void __launch_bounds__(kBlock) k_skin_invert(SkinArgs<T> a) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= a.nskin_free) return;
  const int j = a.skin_free[k];
  const int k0 = a.row_ptr[j], len3 = 3 * (a.row_ptr[j + 1] - k0);
  const T* d = a.vals + 9 * std::size_t(k0) + 3 * (a.diag_block[j] - k0);
  T A[9], inv[9];
#pragma unroll
  for (int r = 0; r < 3; ++r)
#pragma unroll
    for (int c = 0; c < 3; ++c) A[3 * r + c] = d[r * len3 + c];
  invert3(A, inv);
#pragma unroll
  for (int q = 0; q < 9; ++q) a.precond[9 * j + q] = inv[q];
}

}  // namespace

template <class T>
void launch_skin(cudaStream_t s, const SkinArgs<T>& a, bool invert) {
  if (a.ntri == 0) return;
  k_skin<T><<<(a.ntri + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_skin);
  if (!invert || a.nskin_free == 0) return;
  k_skin_invert<T><<<(a.nskin_free + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_skin_invert);
}

template void launch_skin<float>(cudaStream_t, const SkinArgs<float>&, bool);
template void launch_skin<double>(cudaStream_t, const SkinArgs<double>&, bool);

template <class T>
void launch_assemble(cudaStream_t s, const AssembleArgs<T>& a) {
  const int warps_per_block = kBlock / 32;
  k_assemble<T><<<(a.nf + warps_per_block - 1) / warps_per_block, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_assemble);
}

template void launch_assemble<float>(cudaStream_t, const AssembleArgs<float>&);
template void launch_assemble<double>(cudaStream_t, const AssembleArgs<double>&);

}  // namespace palpation::sim::cuda
