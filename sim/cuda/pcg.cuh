// PCG stage of the CUDA backends: the PCG of solve_cg.h inside one persistent cooperative
// kernel (pcg.cu), then the state update, the rest rule and the finger outputs. Its
// iterates are solve_cg.h's; for the linear element with every row in registers they are
// formed by the one-barrier Chronopoulos-Gear recurrences (pcg.cu, CudaTuning::cg_form).
//
// Header-only here: the arguments, the launch plan, and the device pieces that the
// textbook baseline (baseline.cu) runs as separate kernels: the block-Jacobi
// preconditioner, the state update and the rest rule.
#pragma once

#include "cuda/common.cuh"
#include "cuda/contact.cuh"
#include "cuda/pressure.cuh"
#include "cuda/tuning.h"

namespace palpation::sim::cuda {

struct MgDev;  // multigrid.cuh

/// The PCG iteration's form in the persistent kernel (tuning.h, CudaTuning::CgForm, says
/// where each is chosen): the search direction formed in a phase of its own (three grid
/// barriers an iteration), inside the SpMV (two), or the Chronopoulos-Gear recurrences
/// (one; block-Jacobi only).
enum PcgForm : int { kThreeBarriers = 0, kTwoBarriers = 1, kOneReduction = 2 };

template <class T>
struct PcgArgs {
  int n;  // block rows (free nodes)
  const int* row_ptr;
  const int* col;
  const T* vals;
  const T* P;  // block-Jacobi inverse (n x 9)
  const T* b;
  T* x;  // dv: warm start in, solution out
  T* r;
  T* z;
  T* p0;
  T* p1;
  T* q;
  T* ext[5];  // the one-reduction form's further vectors (pcg.cu, cg_one_reduction)
  // State update and rest detection.
  int nnode;
  const int* free_nodes;
  T* xpos;
  T* vel;
  const T* rest;   // (3 nnode) rest positions, for the divergence guard's displacement
  const T* mass;   // (nnode) lumped masses, for its kinetic energy
  T h;
  T tol;
  int max_it;
  T rescue_tol;   // past max_it: on while above rescue_tol, up to rescue_it in all
  int rescue_it;
  int form;  // PcgForm: the iteration's form, resolved by the backend (tuning.h, CgForm)
  // A solve in slices: at most `slice` iterations a launch (0: the whole solve), the next
  // launch going on from where the last stopped (`resume`: the state kept in scr). Not
  // with the one-reduction form.
  int slice;
  int resume;
  PressureDev<T> pres;  // the nodal-pressure term (pressure.cuh); off when pres.b is null
  // The multigrid preconditioner (multigrid.cuh) in place of block-Jacobi, with its
  // finest level's scratch (3 n each); off when mg is null.
  const MgDev* mg;
  T* mg_r;
  T* mg_d;
  DevScratch* scr;
  DevResult* res;
  // CudaTuning::phases: per PcgPhase the clock64 cycles summed, then (at kPhases + id) how
  // often it ended, then the launches' globaltimer ns and clock64 cycles; null: off.
  unsigned long long* phase;
};

/// Entry c of P_i v for the three entries v0, v1, v2 of row i of a vector.
template <class T>
__device__ __forceinline__ T block_jacobi_entry(const T* P, int i, int c, T v0, T v1, T v2) {
  const T* Pi = P + 9 * i + 3 * c;
  return Pi[0] * v0 + Pi[1] * v1 + Pi[2] * v2;
}

/// Whether the PCG goes on after `it` iterations at residual norm rnorm (solve_cg.h's
/// rule): below max_it while above tol, then on to rescue_it while above rescue_tol.
template <class T>
__device__ __forceinline__ bool pcg_goes_on(const PcgArgs<T>& a, int it, T rnorm, T bnorm) {
  return (it < a.max_it && rnorm > a.tol * bnorm) || (it < a.rescue_it && rnorm > a.rescue_tol * bnorm);
}

/// t = P_i r_i: block row i of the block-Jacobi preconditioner (P: n x 9, row-major).
template <class T>
__device__ __forceinline__ void block_jacobi_row(const T* P, const T* r, int i, T (&t)[3]) {
  const T r0 = r[3 * i], r1 = r[3 * i + 1], r2 = r[3 * i + 2];
  for (int c = 0; c < 3; ++c) t[c] = block_jacobi_entry(P, i, c, r0, r1, r2);
}

/// z_i = P_i r_i.
template <class T>
__device__ __forceinline__ void precondition_row(const T* P, const T* r, T* z, int i) {
  T t[3];
  block_jacobi_row(P, r, i, t);
  z[3 * i] = t[0];
  z[3 * i + 1] = t[1];
  z[3 * i + 2] = t[2];
}

/// v += dv, x += h v over the free nodes; block maxima of |v| and |dv| into the scratch,
/// and the divergence guard's summary (largest |v|^2 and |x - X|^2, kinetic energy), so
/// that the host need not read the state back.
template <class T>
__device__ void update_state(const PcgArgs<T>& a) {
  double vmax = 0, dvmax = 0, v2max = 0, d2max = 0, ke = 0;
  bool bad = false;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < a.n; i += gridDim.x * blockDim.x) {
    const int node = a.free_nodes[i];
    double v2 = 0, d2 = 0;
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      const T dv = a.x[3 * i + c];
      const T v = a.vel[3 * node + c] + dv;
      a.vel[3 * node + c] = v;
      const T x = a.xpos[3 * node + c] + a.h * v;
      a.xpos[3 * node + c] = x;
      vmax = fmax(vmax, double(fabs(v)));
      dvmax = fmax(dvmax, double(fabs(dv)));
      bad = bad || !isfinite(v) || !isfinite(dv);
      v2 += double(v) * double(v);
      const double d = double(x) - double(a.rest[3 * node + c]);
      d2 += d * d;
    }
    v2max = fmax(v2max, v2);
    d2max = fmax(d2max, d2);
    ke += 0.5 * double(a.mass[node]) * v2;
  }
  // A non-finite velocity must reach the host (fmax drops NaN): report it as +inf.
  if (bad) vmax = dvmax = v2max = d2max = INFINITY;
  double m4[4] = {vmax, dvmax, v2max, d2max};
  unsigned long long* const dst[4] = {&a.scr->vmax_bits, &a.scr->dvmax_bits, &a.scr->v2max_bits, &a.scr->d2max_bits};
  block_max_atomic<4>(m4, dst);
  double s1[1] = {bad ? double(INFINITY) : ke};
  block_sum_atomic<1>(s1, &a.scr->ke);
}

/// Rest rule of backend_cpu.cpp: no contact at the start, |v| < 1e-6, |dv| < 1e-7 ->
/// v = 0. Every thread reads the same global values and takes the same branch.
template <class T>
__device__ void rest_rule(const PcgArgs<T>& a) {
  __shared__ bool sh_rested;
  if (threadIdx.x == 0) {
    const volatile DevScratch* sc = a.scr;
    const T vmax = T(bits_to_double(sc->vmax_bits)), dvmax = T(bits_to_double(sc->dvmax_bits));
    sh_rested = sc->start_contacts == 0 && vmax < T(1e-6) && dvmax < T(1e-7);
  }
  __syncthreads();
  const bool rested = sh_rested;
  if (rested)
    for (int j = blockIdx.x * blockDim.x + threadIdx.x; j < 3 * a.nnode; j += gridDim.x * blockDim.x) a.vel[j] = T(0);
  if (blockIdx.x == 0 && threadIdx.x == 0) a.scr->rested = rested ? 1 : 0;
}

/// Launch configuration of the persistent kernel for n block rows. Default: blocks of 512
/// threads, at most one per multiprocessor where the rows live in registers (fewer blocks
/// make the grid barriers and the reductions cheaper: measured, docs/gpu-notes.md).
struct PcgLaunch {
  const void* fn = nullptr;
  int grid = 1;
  int block = kPcgMaxBlock;
  bool cached = false;    // every row's matrix held in registers
  int sms = 1;            // multiprocessors its blocks occupy at most
  bool confined = false;  // a shadow's solve on the multiprocessors the steps' solve leaves
};

/// The launch configuration of k_pcg for n block rows on this device, with the knobs of
/// `tuning` (pcg_block, pcg_grid, pcg_blocks_per_sm, rows_in_registers); `multigrid`: the
/// kernel preconditioned by the multigrid (PcgArgs::mg) instead of block-Jacobi.
template <class T>
PcgLaunch pcg_launch(int n, const CudaTuning& tuning, bool multigrid = false);

/// The launch of a solve beside the steps (the converged check's shadow): the streaming
/// kernel (no rows in registers: any grid covers every row) on `sms` multiprocessors, one
/// block each, so that it never holds a block the steps' cooperative launch waits for.
template <class T>
PcgLaunch pcg_launch_confined(int sms, const CudaTuning& tuning, bool multigrid = false);

/// Launches the persistent kernel L.fn (cooperative) in stream s.
template <class T>
void launch_pcg(cudaStream_t s, const PcgLaunch& L, const PcgArgs<T>& a, const DetectArgs<T>& d, const FingersArg& F,
                const StepConsts& k);

}  // namespace palpation::sim::cuda
