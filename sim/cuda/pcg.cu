// PCG stage: the persistent cooperative kernel and its launch plan (see pcg.cuh).
#include "cuda/pcg.cuh"

#include <climits>
#include <cooperative_groups.h>

#include "cuda/device_info.h"
#include "cuda/multigrid.cuh"

namespace palpation::sim::cuda {

static_assert(CudaTuning{}.pcg_block == kPcgMaxBlock, "the default PCG block is the kernel's launch bound");

namespace {

namespace coop = cooperative_groups;

constexpr int kCacheBlocks = 3;  // blocks per lane held in registers: rows of up to 24 blocks

/// The first block row of each lane group, held in registers for the whole solve: lane gl
/// keeps blocks gl, gl + G, ..., gl + (B - 1) G of it (9 values and the column each). When
/// every row fits (the paper mesh: rows of at most 24 blocks, one row per group) the
/// iterations read no matrix data from memory at all.
template <class T, int B>
struct RowCache {
  T v[B > 0 ? B : 1][9];
  int j[B > 0 ? B : 1];
  int k0 = 0, len = 0;
};

template <class T, int B>
__device__ void load_row_cache(const PcgArgs<T>& a, RowCache<T, B>& rc) {
  constexpr int G = kGroup, RPW = 32 / G;
  const int lane = threadIdx.x & 31, gl = lane % G, gw = lane / G;
  const int i = ((blockIdx.x * blockDim.x + threadIdx.x) >> 5) * RPW + gw;
  if constexpr (B > 0) {
    if (i < a.n) {
      rc.k0 = a.row_ptr[i];
      rc.len = a.row_ptr[i + 1] - rc.k0;
      const int len3 = 3 * rc.len;
      const T* rv = a.vals + 9 * std::size_t(rc.k0);
#pragma unroll
      for (int b = 0; b < B; ++b) {
        const int kk = gl + b * G;
        rc.j[b] = 0;
#pragma unroll
        for (int c = 0; c < 9; ++c) rc.v[b][c] = T(0);
        if (kk < rc.len) {
          rc.j[b] = a.col[rc.k0 + kk];
          const T* bv = rv + 3 * kk;
#pragma unroll
          for (int r = 0; r < 3; ++r)
#pragma unroll
            for (int c = 0; c < 3; ++c) rc.v[b][3 * r + c] = bv[r * len3 + c];
        }
      }
    }
  }
}

/// y_i = sum_k A_k u_col(k) for the block rows of this thread's group, then
/// emit(i, c, y0, y1, y2) on lanes c = 0..2 of the group (each holds all of y_i).
/// `fetch(j, c)` reads the input vector.
/// The first pass takes its row from the register cache; other passes (rows beyond one
/// per group, on large meshes) stream the matrix. Warp-uniform loop bounds: every lane of
/// a warp takes part in every shuffle.
template <class T, int B, class Fetch, class Emit3>
__device__ __forceinline__ void spmv_groups3(const PcgArgs<T>& a, const RowCache<T, B>& rc, Fetch fetch, Emit3 emit) {
  constexpr int G = kGroup, RPW = 32 / G;
  const int lane = threadIdx.x & 31;
  const int gl = lane % G, gw = lane / G;
  const int warp = (blockIdx.x * blockDim.x + threadIdx.x) >> 5;
  const int nwarps = (gridDim.x * blockDim.x) >> 5;
  bool first_pass = true;
  for (int base = warp * RPW; base < a.n; base += nwarps * RPW) {
    const int i = base + gw;
    T y0 = 0, y1 = 0, y2 = 0;
    if (i < a.n) {
      int k0, len, kstart = gl;
      if (B > 0 && first_pass) {
        k0 = rc.k0;
        len = rc.len;
#pragma unroll
        for (int b = 0; b < (B > 0 ? B : 1); ++b) {
          if (gl + b * G < len) {
            const int jj = rc.j[b];
            const T u0 = fetch(jj, 0), u1 = fetch(jj, 1), u2 = fetch(jj, 2);
            const T* m = rc.v[b];
            y0 += m[0] * u0 + m[1] * u1 + m[2] * u2;
            y1 += m[3] * u0 + m[4] * u1 + m[5] * u2;
            y2 += m[6] * u0 + m[7] * u1 + m[8] * u2;
          }
        }
        kstart = gl + B * G;
      } else {
        k0 = a.row_ptr[i];
        len = a.row_ptr[i + 1] - k0;
      }
      const int len3 = 3 * len;
      const T* rv = a.vals + 9 * std::size_t(k0);
      for (int kk = kstart; kk < len; kk += G) {
        const int j = __ldg(a.col + k0 + kk);
        const T u0 = fetch(j, 0), u1 = fetch(j, 1), u2 = fetch(j, 2);
        const T* bv = rv + 3 * kk;
        y0 += __ldg(bv) * u0 + __ldg(bv + 1) * u1 + __ldg(bv + 2) * u2;
        y1 += __ldg(bv + len3) * u0 + __ldg(bv + len3 + 1) * u1 + __ldg(bv + len3 + 2) * u2;
        y2 += __ldg(bv + 2 * len3) * u0 + __ldg(bv + 2 * len3 + 1) * u1 + __ldg(bv + 2 * len3 + 2) * u2;
      }
      if (a.pres.b) pressure_gather<T, G>(a.pres, i, gl, y0, y1, y2);  // + kscale B^T W B u, pressures formed before
    }
    first_pass = false;
    y0 = group_sum<G>(y0);
    y1 = group_sum<G>(y1);
    y2 = group_sum<G>(y2);
    if (i < a.n && gl < 3) emit(i, gl, y0, y1, y2);
  }
}

/// spmv_groups3 with emit(i, c, y_c): lane c of the group emits component c.
template <class T, int B, class Fetch, class Emit>
__device__ __forceinline__ void spmv_groups(const PcgArgs<T>& a, const RowCache<T, B>& rc, Fetch fetch, Emit emit) {
  spmv_groups3<T, B>(a, rc, fetch, [&](int i, int c, T y0, T y1, T y2) { emit(i, c, c == 0 ? y0 : (c == 1 ? y1 : y2)); });
}

/// Reduction ring: the values reduced before barrier m live in slot m % 4.
struct Ring {
  int m = 0;
  __device__ double* slot(DevScratch* s) const { return s->red[m & 3]; }
  /// After the barrier: read slot m % 4, zero slot (m + 2) % 4, advance. One thread per
  /// block reads the slot and shares it: every thread of the grid reading one L2 line is a
  /// hot spot (docs/gpu-notes.md).
  template <int K>
  __device__ void take(DevScratch* s, double (&out)[K]) {
    __shared__ double sh[K];
    if (threadIdx.x == 0) {
#pragma unroll
      for (int k = 0; k < K; ++k) sh[k] = __ldcg(&s->red[m & 3][k]);
      if (blockIdx.x == 0)
        for (int k = 0; k < 4; ++k) s->red[(m + 2) & 3][k] = 0.0;
    }
    __syncthreads();
#pragma unroll
    for (int k = 0; k < K; ++k) out[k] = sh[k];
    ++m;
  }
  /// The grid-wide sums of v (each thread's share on entry, the totals on every thread on
  /// return): reduced into this barrier's slot, the barrier, the slot read.
  template <int K>
  __device__ void sum(coop::grid_group& grid, DevScratch* s, double (&v)[K]) {
    block_sum_atomic<K>(v, slot(s));
    grid.sync();
    take<K>(s, v);
  }
  /// A barrier that carries no reduction still advances the ring (and zeroes ahead).
  __device__ void skip(DevScratch* s) {
    if (blockIdx.x == 0 && threadIdx.x == 0)
      for (int k = 0; k < 4; ++k) s->red[(m + 2) & 3][k] = 0.0;
    ++m;
  }
};

/// The persistent kernel's phases timed on one thread (CudaTuning::phases, a measurement
/// switch): block 0's thread 0 reads its multiprocessor's cycle counter after each grid
/// barrier and adds the cycles since the last one to the phase that barrier ends
/// (PcgPhase); the launch's globaltimer span beside its cycles converts them to time.
/// Every block leaves a barrier about together, so a phase's figure is its slowest block's
/// work plus the barrier. Its state is in shared memory and its switch the kernel's
/// argument, so that it holds no register across the solve; off (`acc` null): one untaken
/// branch per barrier.
struct PhaseClock {
  unsigned long long* const& acc;  // PcgArgs::phase
  __device__ static unsigned long long globaltimer() {
    unsigned long long t;
    asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(t));
    return t;
  }
  __device__ static long long* state() {
    __shared__ long long s[3];  // last mark's cycles, the launch's first cycles and ns
    return s;
  }
  __device__ bool on() const { return acc && blockIdx.x == 0 && threadIdx.x == 0; }
  __device__ void start() const {
    if (!on()) return;
    long long* s = state();
    s[0] = s[1] = clock64();
    s[2] = static_cast<long long>(globaltimer());
  }
  __device__ void mark(int id) const {
    if (!on()) return;
    long long* s = state();
    const long long t = clock64();
    acc[id] += static_cast<unsigned long long>(t - s[0]);
    acc[kPhases + id] += 1;
    s[0] = t;
  }
  __device__ void stop() const {
    if (!on()) return;
    const long long* s = state();
    acc[2 * kPhases] += globaltimer() - static_cast<unsigned long long>(s[2]);
    acc[2 * kPhases + 1] += static_cast<unsigned long long>(clock64() - s[1]);
  }
};

/// y = A u on the finest level: the kernel's own operator, the nodal-pressure term's
/// pressures of u formed first (one barrier more); emit(i, c, y) as spmv_groups.
template <class T, int B, class Fetch, class Emit, class Bar>
__device__ __forceinline__ void fine_product(const PcgArgs<T>& a, const RowCache<T, B>& rc, Fetch fetch, Emit emit, Bar bar,
                                             int tid, int nthreads) {
  if (a.pres.b) {
    pressure_rows<T, kGroup>(a.pres, a.nnode, fetch, tid, nthreads);
    bar(kPhMgPressure);
  }
  spmv_groups<T, B>(a, rc, fetch, emit);
}

/// z += P A_1^{-1} R res: the V-cycle's coarse correction (restrict, cycle the coarse levels,
/// prolong and add), ending on a barrier. Inlined: as a call (its products' several row
/// widths kept out of the kernel's registers) the xfine step was 19 % slower (H200).
template <class T, class Bar>
__device__ __forceinline__ void mg_coarse_correction(const MgDev& M, const T* res, T* z, Bar bar) {
  const MgLevelDev& F = M.lv[0];
  const MgLevelDev& L1 = M.lv[1];
  csr_rows<T>(F.R, [&](int j) { return res[j]; }, [&](int i, double y) { L1.b[i] = y; });
  bar(kPhMgRestrict);
  mg_coarse_cycle<T>(M, bar);
  csr_rows<T>(F.P, [&](int j) { return L1.x[j]; }, [&](int i, double y) { z[i] += T(y); });
  bar(kPhMgProlong);
}

/// The finest level's pre-smoothing from zero at block row i (amg::smooth's first pass):
/// the residual copy res = r and d = z = c0 D^-1 r, from row i of r alone. The CG's update
/// calls it on each row it has just updated, so that the V-cycle does not need a pass and
/// a barrier of its own for it.
template <class T>
__device__ __forceinline__ void mg_presmooth_row(const PcgArgs<T>& a, T c0, int i) {
  T t[3];
  block_jacobi_row(a.P, a.r, i, t);
#pragma unroll
  for (int c = 0; c < 3; ++c) {
    a.mg_r[3 * i + c] = a.r[3 * i + c];
    a.mg_d[3 * i + c] = c0 * t[c];
    a.z[3 * i + c] = c0 * t[c];
  }
}

/// z = M r for the multigrid preconditioner: solve_cg.h's multigrid_cycle (the finest
/// level's smoothing on this operator with its block-Jacobi before and after the coarse
/// correction of multigrid.cuh). r's rows of this thread (block rows tid, tid + nthreads,
/// ...) complete on entry, every other row after a barrier; `presmoothed`: every row's
/// mg_presmooth_row is done and a barrier passed since. Returns this thread's share of
/// r . z, summed over the rows it wrote last (no barrier at the end).
template <class T, int B, class Bar>
__device__ double mg_precondition(const PcgArgs<T>& a, const RowCache<T, B>& rc, Bar bar, int tid, int nthreads,
                                  bool presmoothed) {
  const MgDev& M = *a.mg;
  const MgLevelDev& F = M.lv[0];
  const T* __restrict r = a.r;
  T* z = a.z;
  T* res = a.mg_r;
  T* d = a.mg_d;
  const int steps = F.steps;
  auto of = [](const T* v) { return [v](int j, int c) { return v[3 * j + c]; }; };
  // Pre-smoothing from zero, the residual after it (amg::smooth).
  if (!presmoothed) {
    const T c0 = T(F.c[0]);
    for (int i = tid; i < a.n; i += nthreads) mg_presmooth_row(a, c0, i);
    bar(kPhMgJacobi);
  }
  for (int k = 1; k < steps; ++k) {
    fine_product(a, rc, of(d), [&](int i, int c, T y) { res[3 * i + c] -= y; }, bar, tid, nthreads);
    bar(kPhMgProduct);
    const T ak = T(F.a[k]), ck = T(F.c[k]);
    for (int i = tid; i < a.n; i += nthreads) {
      T t[3];
      block_jacobi_row(a.P, res, i, t);
#pragma unroll
      for (int c = 0; c < 3; ++c) {
        const T dn = ak * d[3 * i + c] + ck * t[c];
        d[3 * i + c] = dn;
        z[3 * i + c] += dn;
      }
    }
    bar(kPhMgJacobi);
  }
  fine_product(a, rc, of(d), [&](int i, int c, T y) { res[3 * i + c] -= y; }, bar, tid, nthreads);
  bar(kPhMgProduct);
  mg_coarse_correction(M, res, z, bar);
  // Post-smoothing from z, and r . z over the rows this thread wrote last.
  fine_product(a, rc, of(z), [&](int i, int c, T y) { res[3 * i + c] = r[3 * i + c] - y; }, bar, tid, nthreads);
  bar(kPhMgProduct);
  double rz = 0;
  for (int k = 0; k < steps; ++k) {
    if (k > 0) {
      fine_product(a, rc, of(d), [&](int i, int c, T y) { res[3 * i + c] -= y; }, bar, tid, nthreads);
      bar(kPhMgProduct);
    }
    const T ak = T(F.a[k]), ck = T(F.c[k]);
    const bool last = k + 1 == steps;
    for (int i = tid; i < a.n; i += nthreads) {
      T t[3];
      block_jacobi_row(a.P, res, i, t);
#pragma unroll
      for (int c = 0; c < 3; ++c) {
        const T dn = k == 0 ? ck * t[c] : ak * d[3 * i + c] + ck * t[c];
        d[3 * i + c] = dn;
        const T zn = z[3 * i + c] + dn;
        z[3 * i + c] = zn;
        if (last) rz += double(r[3 * i + c]) * double(zn);
      }
    }
    if (!last) bar(kPhMgJacobi);
  }
  return rz;
}

/// Block-Jacobi PCG by the Chronopoulos-Gear recurrences, from r = b - A x (the warm
/// start's, or b after a restart: `restart`), rnorm = ||r||: solve_cg.h's iterates in exact
/// arithmetic, with its stopping rule and a breakdown test on the same quantity (p . A p,
/// here gamma / alpha), but one grid barrier per iteration where the textbook form needs
/// two (alpha needs p . A p before the update, beta needs r . z after it). With u = P r,
/// w = A u, s = A p and m = P s:
///   p = u + beta p,  s = w + beta s,  m = P w + beta m,  x += alpha p,  r -= alpha s,
///   u -= alpha m,  w = A u,  gamma = r . u,  delta = u . w,  beta' = gamma' / gamma,
///   alpha' = gamma' / (delta' - beta' gamma' / alpha).
/// A pass updates its own rows and forms w = A u of the new u in the same sweep: a
/// neighbour's new u is formed on the fly from its u, P w and m, which stay untouched until
/// the barrier (the three are double-buffered; x, r, p, s and w are read by their own rows
/// only). Returns the iterations taken; rnorm is the last residual's norm.
template <class T, int B, class Bar, class Sum>
__device__ int cg_one_reduction(const PcgArgs<T>& a, const RowCache<T, B>& rc, Bar bar, Sum sum, bool restart, T bnorm,
                                T& rnorm, int tid, int nthreads) {
  const T* __restrict P = a.P;
  T* ub[2] = {a.z, a.ext[0]};
  T* pwb[2] = {a.q, a.ext[1]};
  T* mb[2] = {a.p1, a.ext[2]};
  T* r = a.r;
  T* p = a.p0;
  T* sv = a.ext[3];
  T* w = a.ext[4];
  auto prow = [P](int i, int c, T v0, T v1, T v2) { return block_jacobi_entry(P, i, c, v0, v1, v2); };
  // u = P r of the start, and w = A u with its dots (restart: r = b, x = 0).
  T gamma, delta;
  {
    const T* r0 = restart ? a.b : a.r;
    auto u0 = [=](int j, int c) { return prow(j, c, r0[3 * j], r0[3 * j + 1], r0[3 * j + 2]); };
    if (a.pres.b) {
      pressure_rows<T, kGroup>(a.pres, a.nnode, u0, tid, nthreads);
      bar(kPhStart);
    }
    double acc[2] = {0, 0};
    spmv_groups3<T, B>(a, rc, u0, [&](int i, int c, T y0, T y1, T y2) {
      if (restart) {
        a.x[3 * i + c] = T(0);
        r[3 * i + c] = a.b[3 * i + c];
      }
      const T u = u0(i, c), y = c == 0 ? y0 : (c == 1 ? y1 : y2);
      ub[0][3 * i + c] = u;
      w[3 * i + c] = y;
      pwb[0][3 * i + c] = prow(i, c, y0, y1, y2);
      acc[0] += double(r0[3 * i + c]) * double(u);
      acc[1] += double(u) * double(y);
    });
    sum(acc, kPhStart);
    gamma = T(acc[0]);
    delta = T(acc[1]);
  }
  int it = 0;
  if (!(delta > T(0))) return it;  // not positive definite along u (or NaN): as pq <= 0
  T alpha = gamma / delta, beta = 0;
  bool first = true;
  int cur = 0;
  while (pcg_goes_on(a, it, rnorm, bnorm)) {
    const T* uo = ub[cur];
    const T* pwo = pwb[cur];
    const T* mo = mb[cur];
    T* un = ub[cur ^ 1];
    T* pwn = pwb[cur ^ 1];
    T* mn = mb[cur ^ 1];
    const bool fst = first;
    const T al = alpha, bt = beta;
    auto m_of = [=](int j, int c) { return fst ? pwo[3 * j + c] : fma(bt, mo[3 * j + c], pwo[3 * j + c]); };
    auto u_next = [=](int j, int c) { return fma(-al, m_of(j, c), uo[3 * j + c]); };
    if (a.pres.b) {
      pressure_rows<T, kGroup>(a.pres, a.nnode, u_next, tid, nthreads);
      bar(kPhCgPressure);
    }
    double acc[3] = {0, 0, 0};
    spmv_groups3<T, B>(a, rc, u_next, [&](int i, int c, T y0, T y1, T y2) {
      const int k = 3 * i + c;
      const T u = uo[k];
      const T pi = fst ? u : fma(bt, p[k], u);
      p[k] = pi;
      a.x[k] += al * pi;
      const T si = fst ? w[k] : fma(bt, sv[k], w[k]);
      sv[k] = si;
      const T rnew = fma(-al, si, r[k]);
      r[k] = rnew;
      mn[k] = m_of(i, c);
      const T unew = u_next(i, c), y = c == 0 ? y0 : (c == 1 ? y1 : y2);
      un[k] = unew;
      w[k] = y;
      pwn[k] = prow(i, c, y0, y1, y2);
      acc[0] += double(rnew) * double(unew);
      acc[1] += double(unew) * double(y);
      acc[2] += double(rnew) * double(rnew);
    });
    sum(acc, kPhCgProduct);
    ++it;
    rnorm = sqrt(T(acc[2]));
    const T gamma_new = T(acc[0]);
    beta = gamma_new / gamma;
    const T pap = T(acc[1]) - beta * gamma_new / alpha;  // p' . A p' = gamma' / alpha'
    gamma = gamma_new;
    cur ^= 1;
    first = false;
    if (!(pap > T(0))) break;
    alpha = gamma_new / pap;
  }
  return it;
}

/// The whole PCG of solve_cg.h (same warm start, restart rule, stopping rule and
/// breakdown test) in one persistent cooperative kernel, then the state update, the rest
/// rule and the finger outputs. Per iteration two grid barriers: the search direction
/// p = z + beta p is formed inside the SpMV from z and the previous p (double-buffered),
/// so its own barrier disappears. With the nodal-pressure term one more: the pressures of
/// p over every node, before the SpMV adds B^T of them to each row. B > 0: the first row
/// of each lane group is held in registers (k_pcg is then launched with at most two
/// blocks per multiprocessor).
template <class T, int B, bool MG>
__global__ void __launch_bounds__(kPcgMaxBlock, B > 0 ? 1 : 2) k_pcg(PcgArgs<T> a, DetectArgs<T> d, FingersArg F, StepConsts k) {
  coop::grid_group grid = coop::this_grid();
  const int tid = blockIdx.x * blockDim.x + threadIdx.x, nthreads = gridDim.x * blockDim.x;
  Ring ring;
  const PhaseClock clk{a.phase};
  clk.start();
  auto bar = [&](int phase) {
    grid.sync();
    ring.skip(a.scr);
    clk.mark(phase);
  };
  // The grid's sums of this thread's shares acc[] (a barrier of its own), then the phase.
  auto sum = [&](auto& acc, int phase) {
    ring.sum(grid, a.scr, acc);
    clk.mark(phase);
  };
  RowCache<T, B> rc;
  load_row_cache(a, rc);
  if (a.slice > 0 && tid == 0) a.res->unfinished = 0;  // read only for solves in slices

  T bnorm = 0, rnorm = 0;
  int it = 0;
  bool restart = false;
  if (a.resume) {
    // The next slice of a solve in slices: x, r, z and the directions are where the last
    // slice left them, the scalars in the scratch.
    bnorm = T(a.scr->cg_bnorm);
    rnorm = T(a.scr->cg_rnorm);
    it = a.scr->cg_it;
  } else {
    // The nodal pressures of x (pressure.cuh) for its product below.
    if (a.pres.b) {
      pressure_rows<T, kGroup>(a.pres, a.nnode, [&](int j, int c) { return a.x[3 * j + c]; }, tid, nthreads);
      bar(kPhStart);
    }
    // r = b - A x (warm start), ||b||^2, ||r||^2.
    double br[2] = {0, 0};
    spmv_groups<T, B>(
        a, rc, [&](int j, int c) { return a.x[3 * j + c]; },
        [&](int i, int c, T y) {
          const T bi = a.b[3 * i + c];
          const T ri = bi - y;
          a.r[3 * i + c] = ri;
          br[0] += double(bi) * double(bi);
          br[1] += double(ri) * double(ri);
        });
    sum(br, kPhStart);
    bnorm = sqrt(T(br[0]));
    rnorm = sqrt(T(br[1]));
    // A warm start far worse than zero (or not finite) restarts from x = 0, r = b.
    restart = !isfinite(rnorm) || rnorm > T(1e3) * bnorm;
    if (restart) rnorm = bnorm;
  }
  if (bnorm > T(0) && !MG && a.form == kOneReduction) {
    it = cg_one_reduction<T, B>(a, rc, bar, sum, restart, bnorm, rnorm, tid, nthreads);
  } else if (bnorm > T(0)) {
    T rz = 0;
    T beta = 0;
    bool first = true;
    T* pold = a.p0;
    T* pnew = a.p1;
    if (a.resume) {
      rz = T(a.scr->cg_rz);
      beta = T(a.scr->cg_beta);
      first = a.scr->cg_first != 0;
      if (a.scr->cg_p1) {
        pold = a.p1;
        pnew = a.p0;
      }
    } else {
      double rz1[1] = {0};
      for (int i = tid; i < a.n; i += nthreads) {
        if (restart)
          for (int c = 0; c < 3; ++c) {
            a.x[3 * i + c] = T(0);
            a.r[3 * i + c] = a.b[3 * i + c];
          }
        if constexpr (!MG) {
          precondition_row(a.P, a.r, a.z, i);
          for (int c = 0; c < 3; ++c) rz1[0] += double(a.r[3 * i + c]) * double(a.z[3 * i + c]);
        }
      }
      if constexpr (MG) rz1[0] = mg_precondition(a, rc, bar, tid, nthreads, false);
      sum(rz1, MG ? kPhMgDot : kPhStart);
      rz = T(rz1[0]);
    }
    const int stop = a.slice > 0 ? it + a.slice : INT_MAX;
    const T c0 = MG ? T(a.mg->lv[0].c[0]) : T(0);  // the finest smoothing's first coefficient
    while (it < stop && pcg_goes_on(a, it, rnorm, bnorm)) {
      // Search direction p = z + beta p (first: p = z) and q = A p.
      if (a.form == kThreeBarriers) {
        for (int j = tid; j < 3 * a.n; j += nthreads) pnew[j] = first ? a.z[j] : a.z[j] + beta * pold[j];
        bar(kPhCgUpdate);
      }
      double acc[1] = {0};
      if (a.form != kThreeBarriers) {
        const T* z = a.z;
        const T* po = pold;
        T* pn = pnew;
        const bool fst = first;
        const T bt = beta;
        auto pfly = [=](int j, int c) { return fst ? z[3 * j + c] : fma(bt, po[3 * j + c], z[3 * j + c]); };
        if (a.pres.b) {  // the pressures of p, from z and the previous p as the SpMV forms it
          pressure_rows<T, kGroup>(a.pres, a.nnode, pfly, tid, nthreads);
          bar(kPhCgPressure);
        }
        spmv_groups<T, B>(a, rc, pfly, [&](int i, int c, T y) {
          const T pi = pfly(i, c);
          pn[3 * i + c] = pi;
          a.q[3 * i + c] = y;
          acc[0] += double(pi) * double(y);
        });
      } else {
        const T* pn = pnew;
        if (a.pres.b) {
          pressure_rows<T, kGroup>(a.pres, a.nnode, [=](int j, int c) { return pn[3 * j + c]; }, tid, nthreads);
          bar(kPhCgPressure);
        }
        spmv_groups<T, B>(
            a, rc, [=](int j, int c) { return pn[3 * j + c]; },
            [&](int i, int c, T y) {
              a.q[3 * i + c] = y;
              acc[0] += double(pn[3 * i + c]) * double(y);
            });
      }
      sum(acc, kPhCgProduct);
      const T pq = T(acc[0]);
      if (!(pq > T(0))) break;
      const T alpha = rz / pq;
      double rr2[2] = {0, 0};
      // With the multigrid, its pre-smoothing's pass here, on the rows just updated (wasted
      // on the last iteration only).
      for (int i = tid; i < a.n; i += nthreads) {
        for (int c = 0; c < 3; ++c) {
          a.x[3 * i + c] += alpha * pnew[3 * i + c];
          a.r[3 * i + c] -= alpha * a.q[3 * i + c];
        }
        if constexpr (MG) mg_presmooth_row(a, c0, i);
        if constexpr (!MG) precondition_row(a.P, a.r, a.z, i);
        for (int c = 0; c < 3; ++c) {
          const double rr = double(a.r[3 * i + c]);
          if constexpr (!MG) rr2[0] += rr * double(a.z[3 * i + c]);
          rr2[1] += rr * rr;
        }
      }
      sum(rr2, kPhCgUpdate);
      T rz_new = T(rr2[0]);
      rnorm = sqrt(T(rr2[1]));
      if constexpr (MG) {
        // The V-cycle only where the loop goes on (its z would not be used).
        if (pcg_goes_on(a, it + 1, rnorm, bnorm)) {
          double rz1[1] = {mg_precondition(a, rc, bar, tid, nthreads, true)};
          sum(rz1, kPhMgDot);
          rz_new = T(rz1[0]);
        }
      }
      beta = rz_new / rz;
      rz = rz_new;
      T* tmp = pold;
      pold = pnew;
      pnew = tmp;
      first = false;
      ++it;
    }
    if (it == stop && pcg_goes_on(a, it, rnorm, bnorm)) {
      // The slice ends here (not a breakdown's break, which leaves it below stop) (every thread decides alike: the values are the grid's sums).
      // Its state goes to the scratch, and the reduction ring is left zeroed, as a whole
      // step leaves it, once every block has read its last slot.
      grid.sync();
      if (tid == 0) {
        a.scr->cg_rz = double(rz);
        a.scr->cg_beta = double(beta);
        a.scr->cg_bnorm = double(bnorm);
        a.scr->cg_rnorm = double(rnorm);
        a.scr->cg_it = it;
        a.scr->cg_first = first ? 1 : 0;
        a.scr->cg_p1 = pold == a.p1 ? 1 : 0;
        for (int m = 0; m < 4; ++m)
          for (int k = 0; k < 4; ++k) a.scr->red[m][k] = 0.0;
        a.res->cg_iterations = it;
        a.res->cg_residual = double(rnorm / bnorm);
        a.res->unfinished = 1;
      }
      clk.mark(kPhFinish);
      clk.stop();
      return;
    }
  } else {
    for (int j = tid; j < 3 * a.n; j += nthreads) a.x[j] = T(0);
    bar(kPhFinish);
  }
  if (tid == 0) {
    a.res->cg_iterations = it;
    a.res->cg_residual = bnorm > T(0) ? double(rnorm / bnorm) : 0.0;
  }
  update_state(a);
  grid.sync();
  rest_rule(a);
  grid.sync();
  // Finger outputs at the end state (v already zeroed when the body came to rest).
  __shared__ double sacc[kMaxFingers * kFingerVals];
  for (int t = threadIdx.x; t < kMaxFingers * kFingerVals; t += blockDim.x) sacc[t] = 0.0;
  __syncthreads();
  detect_nodes(d, F, k, false, sacc, nullptr, tid, nthreads);
  zero_contact_terms(d, tid, nthreads);
  __syncthreads();
  for (int t = threadIdx.x; t < F.n * kFingerVals; t += blockDim.x)
    if (sacc[t] != 0.0) atomicAdd(&a.scr->facc[0][0] + t, sacc[t]);
  grid.sync();
  if (blockIdx.x == 0) finalize_result(a.scr, a.res, true);
  clk.mark(kPhFinish);
  clk.stop();
}

template <class T, bool MG>
PcgLaunch pcg_launch_of(int n, const CudaTuning& tuning) {
  const DeviceInfo& d = device_info();
  // The multiprocessors the steps' solve may take: those kept for a solve beside it left out.
  const int sms = std::max(1, d.sms - std::max(tuning.shadow_sms, 0));
  PcgLaunch L;
  L.block = tuning.pcg_block;
  const int rows_per_block = L.block / kGroup;
  const int forced = tuning.pcg_grid;
  const int cap_per_sm = tuning.pcg_blocks_per_sm;
  auto occupying = [&](int per_sm) { L.sms = std::min(sms, (L.grid + per_sm - 1) / per_sm); };
  // Register-resident rows when one pass of lane groups covers every row.
  int per_sm_c = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm_c, k_pcg<T, kCacheBlocks, MG>, L.block, 0));
  if (cap_per_sm > 0) per_sm_c = std::min(per_sm_c, cap_per_sm);
  const int need = (n + rows_per_block - 1) / rows_per_block;
  if (tuning.rows_in_registers && per_sm_c > 0 && need <= per_sm_c * sms) {
    L.fn = reinterpret_cast<const void*>(&k_pcg<T, kCacheBlocks, MG>);
    L.cached = true;
    L.grid = std::max(need, 1);
    if (forced > 0) L.grid = std::min(forced, per_sm_c * sms);
    occupying(per_sm_c);
    return L;
  }
  int per_sm = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, k_pcg<T, 0, MG>, L.block, 0));
  per_sm = std::max(per_sm, 1);
  if (cap_per_sm > 0) per_sm = std::min(per_sm, cap_per_sm);
  const int max_blocks = per_sm * sms;
  // Enough blocks that each lane group gets about one block row per SpMV pass; more only
  // makes the barriers dearer.
  L.fn = reinterpret_cast<const void*>(&k_pcg<T, 0, MG>);
  L.grid = std::clamp(need, 1, max_blocks);
  if (forced > 0) L.grid = std::min(forced, max_blocks);
  occupying(per_sm);
  return L;
}

template <class T, bool MG>
PcgLaunch pcg_launch_confined_of(int sms, const CudaTuning& tuning) {
  PcgLaunch L;
  L.block = tuning.pcg_block;
  L.fn = reinterpret_cast<const void*>(&k_pcg<T, 0, MG>);
  L.grid = L.sms = std::clamp(sms, 1, device_info().sms);
  L.confined = true;
  return L;
}

}  // namespace

template <class T>
PcgLaunch pcg_launch(int n, const CudaTuning& tuning, bool multigrid) {
  return multigrid ? pcg_launch_of<T, true>(n, tuning) : pcg_launch_of<T, false>(n, tuning);
}

template <class T>
void launch_pcg(cudaStream_t s, const PcgLaunch& L, const PcgArgs<T>& a, const DetectArgs<T>& d, const FingersArg& F,
                const StepConsts& k) {
  PcgArgs<T> aa = a;
  DetectArgs<T> dd = d;
  FingersArg f = F;
  StepConsts kk = k;
  void* args[] = {&aa, &dd, &f, &kk};
  CU(cudaLaunchCooperativeKernel(L.fn, dim3(L.grid), dim3(L.block), args, 0, s));
}

template <class T>
PcgLaunch pcg_launch_confined(int sms, const CudaTuning& tuning, bool multigrid) {
  return multigrid ? pcg_launch_confined_of<T, true>(sms, tuning) : pcg_launch_confined_of<T, false>(sms, tuning);
}

template PcgLaunch pcg_launch<float>(int, const CudaTuning&, bool);
template PcgLaunch pcg_launch<double>(int, const CudaTuning&, bool);
template PcgLaunch pcg_launch_confined<float>(int, const CudaTuning&, bool);
template PcgLaunch pcg_launch_confined<double>(int, const CudaTuning&, bool);
template void launch_pcg<float>(cudaStream_t, const PcgLaunch&, const PcgArgs<float>&, const DetectArgs<float>&,
                                const FingersArg&, const StepConsts&);
template void launch_pcg<double>(cudaStream_t, const PcgLaunch&, const PcgArgs<double>&, const DetectArgs<double>&,
                                 const FingersArg&, const StepConsts&);

}  // namespace palpation::sim::cuda
