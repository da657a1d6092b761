// Element stage: the corotation and the element records (see element.cuh).
#include "cuda/element.cuh"

namespace palpation::sim::cuda {

namespace {

// Per-element corotation (fem_corotational.h, line for line).

template <class T>
struct Quat {
  T w, x, y, z;
};

template <class T>
__device__ __forceinline__ void quat_to_mat(const Quat<T>& q, T R[9]) {
  // Eigen's Quaternion::toRotationMatrix.
  const T tx = T(2) * q.x, ty = T(2) * q.y, tz = T(2) * q.z;
  const T twx = tx * q.w, twy = ty * q.w, twz = tz * q.w;
  const T txx = tx * q.x, txy = ty * q.x, txz = tz * q.x;
  const T tyy = ty * q.y, tyz = tz * q.y, tzz = tz * q.z;
  R[0] = T(1) - (tyy + tzz);
  R[1] = txy - twz;
  R[2] = txz + twy;
  R[3] = txy + twz;
  R[4] = T(1) - (txx + tzz);
  R[5] = tyz - twx;
  R[6] = txz - twy;
  R[7] = tyz + twx;
  R[8] = T(1) - (txx + tyy);
}

template <class T>
__device__ __forceinline__ T rot_tol() {
  return sizeof(T) == sizeof(double) ? T(1e-9) : T(1e-6);
}

/// extract_rotation of fem_corotational.h (Mueller et al. 2016), A row-major. Same
/// iteration, threshold and Taylor branch; the divisions are reciprocals and the stopping
/// and branch tests compare squares (w < t <=> w^2 < t^2), which removes most of the
/// long-latency double-precision operations from this dependent chain.
template <class T>
__device__ void extract_rotation(const T A[9], Quat<T>& q) {
  constexpr int kIterations = 4;  // fem::kRotationIterations
  const T tol2 = rot_tol<T>() * rot_tol<T>();
  for (int it = 0; it < kIterations; ++it) {
    T R[9];
    quat_to_mat(q, R);
    T on0 = 0, on1 = 0, on2 = 0, den = 0;
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      const T r0 = R[c], r1 = R[3 + c], r2 = R[6 + c];
      const T a0 = A[c], a1 = A[3 + c], a2 = A[6 + c];
      on0 += r1 * a2 - r2 * a1;
      on1 += r2 * a0 - r0 * a2;
      on2 += r0 * a1 - r1 * a0;
      den += r0 * a0 + r1 * a1 + r2 * a2;
    }
    const T inv = T(1) / (fabs(den) + T(1e-9));
    const T o0 = on0 * inv, o1 = on1 * inv, o2 = on2 * inv;
    const T w2 = o0 * o0 + o1 * o1 + o2 * o2;
    if (w2 < tol2) break;
    T c, s;
    if (w2 < T(1e-4)) {  // w < 1e-2: Taylor series of cos(w/2), sin(w/2)/w
      c = T(1) - w2 * T(0.125) + w2 * w2 * (T(1) / T(384));
      s = T(0.5) - w2 * (T(1) / T(48));
    } else {
      const T w = sqrt(w2);
      c = cos(T(0.5) * w);
      s = sin(T(0.5) * w) / w;
    }
    const T dw = c, dx = s * o0, dy = s * o1, dz = s * o2;
    Quat<T> n;
    n.w = dw * q.w - dx * q.x - dy * q.y - dz * q.z;
    n.x = dw * q.x + dx * q.w + dy * q.z - dz * q.y;
    n.y = dw * q.y - dx * q.z + dy * q.w + dz * q.x;
    n.z = dw * q.z + dx * q.y - dy * q.x + dz * q.w;
    const T nn = n.w * n.w + n.x * n.x + n.y * n.y + n.z * n.z;
    if (nn > T(0)) {
      const T in = rsqrt(nn);
      n.w *= in;
      n.x *= in;
      n.y *= in;
      n.z *= in;
    }
    q = n;
  }
}

/// Elements, and (in the extra blocks) the start-of-step contact detection: the two are
/// independent and both feed the assembly, so one launch does both.
template <class T>
__global__ void __launch_bounds__(kElemBlock) k_element(ElementArgs<T> a, DetectArgs<T> d, FingersArg F, StepConsts k) {
  if (int(blockIdx.x) >= a.elem_blocks) {
    const int db = blockIdx.x - a.elem_blocks, nblk = gridDim.x - a.elem_blocks;
    if (db == 0 && threadIdx.x == 0) zero_step_scratch(d.scr);
    __shared__ int scount;
    if (threadIdx.x == 0) scount = 0;
    __syncthreads();
    detect_nodes(d, F, k, true, nullptr, &scount, db * blockDim.x + threadIdx.x, nblk * blockDim.x);
    __syncthreads();
    if (threadIdx.x == 0 && scount) atomicAdd(&d.scr->start_contacts, scount);
    return;
  }
  const int e = blockIdx.x * blockDim.x + threadIdx.x;
  if (e >= a.ne) return;
  const int4 t = __ldg(a.tets + e);
  const int nodes[4] = {t.x, t.y, t.z, t.w};
  T g[12], xx[12], vv[12];
#pragma unroll
  for (int j = 0; j < 12; ++j) g[j] = __ldg(a.grad + 12 * std::size_t(e) + j);
#pragma unroll
  for (int n = 0; n < 4; ++n)
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      xx[3 * n + c] = a.x[3 * nodes[n] + c];
      vv[3 * n + c] = a.v[3 * nodes[n] + c];
    }
  // F = sum_a x_a g_a^T (row-major).
  T F9[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) {
      T s = xx[i] * g[j];
#pragma unroll
      for (int n = 1; n < 4; ++n) s += xx[3 * n + i] * g[3 * n + j];
      F9[3 * i + j] = s;
    }
  Quat<T> q{a.quat[4 * e], a.quat[4 * e + 1], a.quat[4 * e + 2], a.quat[4 * e + 3]};
  extract_rotation(F9, q);
  a.quat[4 * e] = q.w;
  a.quat[4 * e + 1] = q.x;
  a.quat[4 * e + 2] = q.y;
  a.quat[4 * e + 3] = q.z;
  T R[9];
  quat_to_mat(q, R);
  const T V = a.vol[e], lam = a.lambda[e], mu = a.mu[e];
  if (a.rest_part) a.rest_part[e] = T(0.25) * V * (R[0] + R[4] + R[8] - T(3));
  // H = R^T F - I, S = 2 mu sym(H) + lambda tr(H) I.
  T H[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j)
      H[3 * i + j] = R[i] * F9[j] + R[3 + i] * F9[3 + j] + R[6 + i] * F9[6 + j] - (i == j ? T(1) : T(0));
  T S[9];
  {
    const T tr = H[0] + H[4] + H[8];
#pragma unroll
    for (int i = 0; i < 3; ++i)
#pragma unroll
      for (int j = 0; j < 3; ++j)
        S[3 * i + j] = T(2) * mu * (T(0.5) * (H[3 * i + j] + H[3 * j + i])) + (i == j ? lam * tr : T(0));
  }
  T r[12];
#pragma unroll
  for (int n = 0; n < 4; ++n)
#pragma unroll
    for (int i = 0; i < 3; ++i) r[3 * n + i] = R[3 * i] * g[3 * n] + R[3 * i + 1] * g[3 * n + 1] + R[3 * i + 2] * g[3 * n + 2];
  // Sw = R S R^T (world-frame stress).
  T RS[9], Sw[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) RS[3 * i + j] = R[3 * i] * S[j] + R[3 * i + 1] * S[3 + j] + R[3 * i + 2] * S[6 + j];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) Sw[3 * i + j] = RS[3 * i] * R[3 * j] + RS[3 * i + 1] * R[3 * j + 1] + RS[3 * i + 2] * R[3 * j + 2];
  // K v: P = sum_b v_b r_b^T, Sv = sigma(P).
  T P[9];
#pragma unroll
  for (int i = 0; i < 3; ++i)
#pragma unroll
    for (int j = 0; j < 3; ++j) {
      T s = vv[i] * r[j];
#pragma unroll
      for (int n = 1; n < 4; ++n) s += vv[3 * n + i] * r[3 * n + j];
      P[3 * i + j] = s;
    }
  const T trP = P[0] + P[4] + P[8];
  const T c1 = a.beta + a.h, hV = a.h * V;
  auto q_ij = [&](int i, int j) {
    const T sv = T(2) * mu * (T(0.5) * (P[3 * i + j] + P[3 * j + i])) + (i == j ? lam * trP : T(0));
    return -hV * (T(0.5) * (Sw[3 * i + j] + Sw[3 * j + i]) + c1 * sv);
  };
  T out[kRec];
#pragma unroll
  for (int j = 0; j < 12; ++j) out[j] = r[j];
  out[12] = V * lam;
  out[13] = V * mu;
  out[14] = q_ij(0, 0);
  out[15] = q_ij(0, 1);
  out[16] = q_ij(0, 2);
  out[17] = q_ij(1, 1);
  out[18] = q_ij(1, 2);
  out[19] = q_ij(2, 2);
  T* dst = a.rec + std::size_t(kRec) * e;
  if constexpr (sizeof(T) == 8) {
    double2* d2 = reinterpret_cast<double2*>(dst);  // kRec * 8 B = 160 B: 16-byte aligned
#pragma unroll
    for (int j = 0; j < kRec / 2; ++j) d2[j] = make_double2(out[2 * j], out[2 * j + 1]);
  } else {
    float4* d4 = reinterpret_cast<float4*>(dst);  // 80 B
#pragma unroll
    for (int j = 0; j < kRec / 4; ++j) d4[j] = make_float4(out[4 * j], out[4 * j + 1], out[4 * j + 2], out[4 * j + 3]);
  }
}

}  // namespace

template <class T>
void launch_element(cudaStream_t s, ElementArgs<T> a, const DetectArgs<T>& d, const FingersArg& F, const StepConsts& k,
                    bool detect) {
  a.elem_blocks = (a.ne + kElemBlock - 1) / kElemBlock;
  const int dblocks = detect ? std::max(1, (d.ntri + kElemBlock - 1) / kElemBlock) : 0;
  k_element<T><<<a.elem_blocks + dblocks, kElemBlock, 0, s>>>(a, d, F, k);
  CU_LAUNCHED(k_element);
}

template void launch_element<float>(cudaStream_t, ElementArgs<float>, const DetectArgs<float>&, const FingersArg&,
                                    const StepConsts&, bool);
template void launch_element<double>(cudaStream_t, ElementArgs<double>, const DetectArgs<double>&, const FingersArg&,
                                     const StepConsts&, bool);

}  // namespace palpation::sim::cuda
