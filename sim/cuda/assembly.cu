// Assembly stage: gathering the element records into the block system (see assembly.cuh).
#include "cuda/assembly.cuh"

#include "cuda/element.cuh"

namespace palpation::sim::cuda {

namespace {

/// Threads [0, nb) are blocks: thread k sums, over the element pairs (e, a, b) of block k,
///   K_ab = V (lambda r_a r_b^T + mu r_b r_a^T + mu (r_a . r_b) I)     (r_a . r_b = g_a . g_b)
/// scales it, adds the mass and contact terms and inverts it where it is its row's diagonal
/// block (unless a later stage does: AssembleArgs::invert); with the nodal-pressure term,
/// the same pairs give its coupling b_nj. Threads [nb, nb + nf) are block rows: the element
/// terms Q r_a of the right-hand side over the diagonal block's pairs, then gravity, mass
/// damping and contact, and the warm start. The threads of a warp take neighbouring blocks,
/// mostly of one or two rows, so they read the records of the same elements (cached). Sums
/// run over the elements by ascending index, as the row gather this replaced did: the same
/// rounding.
template <class T>
__global__ void __launch_bounds__(kBlock) k_assemble(AssembleArgs<T> a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < a.nb) {
    const int k = t, i = __ldg(a.block_row + k);
    const int k0 = __ldg(a.row_ptr + i), len3 = 3 * (__ldg(a.row_ptr + i + 1) - k0);
    T acc[9];
#pragma unroll
    for (int j = 0; j < 9; ++j) acc[j] = T(0);
    T pb[3] = {T(0), T(0), T(0)};
    const bool pressure = a.pres_b != nullptr;
    const int c1 = __ldg(a.pair_ptr + k + 1);
    for (int c = __ldg(a.pair_ptr + k); c < c1; ++c) {
      const int code = __ldg(a.pairs + c), e = code >> 4;
      const T* rec = a.rec + std::size_t(kRec) * e;
      const int ia = (code >> 2) & 3, ib = code & 3;
      const T ra[3] = {__ldg(rec + 3 * ia), __ldg(rec + 3 * ia + 1), __ldg(rec + 3 * ia + 2)};
      const T rb[3] = {__ldg(rec + 3 * ib), __ldg(rec + 3 * ib + 1), __ldg(rec + 3 * ib + 2)};
      const T lv = __ldg(rec + 12), mv = __ldg(rec + 13);
#pragma unroll
      for (int r = 0; r < 3; ++r)
#pragma unroll
        for (int cc = 0; cc < 3; ++cc) acc[3 * r + cc] += lv * ra[r] * rb[cc] + mv * rb[r] * ra[cc];
      const T d = mv * (ra[0] * rb[0] + ra[1] * rb[1] + ra[2] * rb[2]);
      acc[0] += d;
      acc[4] += d;
      acc[8] += d;
      if (pressure) {
        const T q = T(0.25) * __ldg(a.vol + e);
#pragma unroll
        for (int cc = 0; cc < 3; ++cc) pb[cc] += q * rb[cc];
      }
    }
    if (pressure) {
      T* dst = a.pres_b + 3 * std::size_t(__ldg(a.pres_pair + k));
#pragma unroll
      for (int cc = 0; cc < 3; ++cc) dst[cc] = pb[cc];
    }
#pragma unroll
    for (int j = 0; j < 9; ++j) acc[j] *= a.kscale;
    if (k == __ldg(a.diag_block + i)) {
      const T mm = a.mscale * a.mass[a.free_nodes[i]];
      acc[0] += mm;
      acc[4] += mm;
      acc[8] += mm;
      const int s = a.free_surf[i];
      if (s >= 0) {
        const double* cA = a.cA + 6 * s;
        acc[0] += T(cA[0]);
        acc[1] += T(cA[1]);
        acc[2] += T(cA[2]);
        acc[3] += T(cA[1]);
        acc[4] += T(cA[3]);
        acc[5] += T(cA[4]);
        acc[6] += T(cA[2]);
        acc[7] += T(cA[4]);
        acc[8] += T(cA[5]);
      }
      if (a.invert) {
        T inv[9];
        invert3(acc, inv);
#pragma unroll
        for (int j = 0; j < 9; ++j) a.precond[9 * i + j] = inv[j];
      }
    }
    T* dst = a.vals + 9 * std::size_t(k0) + 3 * (k - k0);
#pragma unroll
    for (int r = 0; r < 3; ++r)
#pragma unroll
      for (int cc = 0; cc < 3; ++cc) dst[r * len3 + cc] = acc[3 * r + cc];
    return;
  }
  const int i = t - a.nb;
  if (i >= a.nf) return;
  // Q (symmetric, stored xx xy xz yy yz zz) times r_a over the elements around node i.
  T rhs[3] = {T(0), T(0), T(0)};
  const int kd = __ldg(a.diag_block + i), c1 = __ldg(a.pair_ptr + kd + 1);
  for (int c = __ldg(a.pair_ptr + kd); c < c1; ++c) {
    const int code = __ldg(a.pairs + c);
    const T* rec = a.rec + std::size_t(kRec) * (code >> 4);
    const int ia = (code >> 2) & 3;
    const T ra0 = __ldg(rec + 3 * ia), ra1 = __ldg(rec + 3 * ia + 1), ra2 = __ldg(rec + 3 * ia + 2);
    const T qxx = __ldg(rec + 14), qxy = __ldg(rec + 15), qxz = __ldg(rec + 16), qyy = __ldg(rec + 17),
            qyz = __ldg(rec + 18), qzz = __ldg(rec + 19);
    rhs[0] += qxx * ra0 + qxy * ra1 + qxz * ra2;
    rhs[1] += qxy * ra0 + qyy * ra1 + qyz * ra2;
    rhs[2] += qxz * ra0 + qyz * ra1 + qzz * ra2;
  }
  // b = h (f + m g - alpha M v - (beta + h) K v) + contact; the element terms are in rhs.
  const int node_i = a.free_nodes[i];
  const T m = a.mass[node_i];
  const T g[3] = {a.g0, a.g1, a.g2};
  const int s = a.free_surf[i];
#pragma unroll
  for (int c = 0; c < 3; ++c) {
    T bc = rhs[c] + a.h * (m * g[c] - a.alpha * m * a.v[3 * node_i + c]);
    if (s >= 0) bc += T(a.cb[3 * s + c]);
    a.b[3 * i + c] = bc;
    const T cur = a.dv[3 * i + c];
    if (a.extrapolate) a.dv[3 * i + c] = T(2) * cur - a.dv_prev[3 * i + c];
    a.dv_prev[3 * i + c] = cur;
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
  const int threads = a.nb + a.nf;
  k_assemble<T><<<(threads + kBlock - 1) / kBlock, kBlock, 0, s>>>(a);
  CU_LAUNCHED(k_assemble);
}

template void launch_assemble<float>(cudaStream_t, const AssembleArgs<float>&);
template void launch_assemble<double>(cudaStream_t, const AssembleArgs<double>&);

}  // namespace palpation::sim::cuda
