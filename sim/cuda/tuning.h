// Tuning knobs of the CUDA backends: the switches for measurements that
// docs/gpu-notes.md (section 3) compares. Every one is read from the environment in one
// place, CudaTuning::from_environment(), when a backend is made (and when the floor is
// measured), and passed to the code that uses it. The defaults are the measured choices;
// none of the knobs changes the arithmetic of a step, only how the work is laid out on the
// GPU (CG iteration counts and results agree to rounding either way).
#pragma once

namespace palpation::sim::cuda {

struct CudaTuning {
  /// PALPATION_CUDA_PCG_BLOCK: threads per block of the persistent PCG kernel (k_pcg).
  /// 256 when the variable is 256, else 512 (default: one fat block per multiprocessor).
  int pcg_block = 512;
  /// PALPATION_CUDA_GRID: blocks of the persistent PCG kernel, capped at what can be
  /// resident at once. 0 (default, or any value <= 0): as many lane groups as block rows.
  int pcg_grid = 0;
  /// PALPATION_CUDA_BLOCKS_PER_SM: caps the resident PCG blocks per multiprocessor that the
  /// launch plans with. 0 (default, or any value <= 0): the occupancy calculator's figure.
  int pcg_blocks_per_sm = 0;
  /// PALPATION_CUDA_CACHE: 0 streams the matrix from memory in every CG iteration; any
  /// other value (default 1) holds each lane group's first block row in registers for the
  /// whole solve where one pass of lane groups covers every row.
  bool rows_in_registers = true;
  /// PALPATION_CUDA_CG, the PCG's form in the persistent kernel: "3sync" forms the search
  /// direction p = z + beta p in a phase of its own (three grid barriers per iteration);
  /// "fused" forms it inside the SpMV (two barriers: one before alpha, one before beta);
  /// "1sync" runs the Chronopoulos-Gear recurrences (pcg.cu, cg_one_reduction): the same
  /// iterates in exact arithmetic, both reductions in one barrier, three vectors read per
  /// neighbour where "fused" reads two. "1sync" is block-Jacobi's only: the multigrid runs
  /// "fused" under it. Anything else (default "auto"): "1sync" for the linear element with
  /// every row held in registers; "3sync" for the nodal-pressure term with the rows
  /// streamed; "fused" otherwise (measured, docs/benchmarks.md: 1sync is 13-15 % quicker
  /// there, 2-7 % slower with the nodal-pressure term, 33 % slower streaming the rows;
  /// 3sync a CG iteration 14 % quicker than fused with block-Jacobi on the xfine breast,
  /// 2.6-4.7 % less solve time with the multigrid on xfine and 800k).
  enum class CgForm { Auto, ThreeBarriers, Fused, OneReduction };
  CgForm cg_form = CgForm::Auto;
  /// PALPATION_CUDA_SHADOW_SMS: multiprocessors the steps' persistent solve leaves free for
  /// a converged check's solve beside it (Simulation's shadow). 0 (default, or any value
  /// <= 0): none kept; the shadow takes what the steps' launch leaves, if anything.
  int shadow_sms = 0;
  /// PALPATION_CUDA_SHADOW: where the shadow's solve runs.
  ///   "confined" (default): on the multiprocessors the steps' solve leaves; where it leaves
  ///     none, on the whole device in slices (below);
  ///   "sliced": on the whole device in slices wherever it runs;
  ///   "full": on the whole device in one launch (the two take turns: a check holds a step
  ///     up for its whole reference solve).
  enum class ShadowPlace { Confined, Sliced, Full };
  ShadowPlace shadow_place = ShadowPlace::Confined;
  /// PALPATION_CUDA_SHADOW_SLICE: CG iterations a slice of a sliced shadow's solve takes
  /// (the element pass and assembly are a slice of their own). Default 8; at least 1.
  int shadow_slice = 8;
  /// PALPATION_CUDA_SHADOW_SLICE_MG: the same for a shadow solving with the steps'
  /// multigrid levels (a V-cycle costs several block-Jacobi iterations). Default 2; at
  /// least 1.
  int shadow_slice_mg = 2;
  /// PALPATION_CUDA_MG_LANES: the lanes that read a row of the multigrid's coarse-level and
  /// transfer products (multigrid.cuh, CsrDev::lanes): "2", "8" or "block" (a block per
  /// row) for every matrix; anything else (default "auto"): by each matrix's rows
  /// (csr_lanes). -1 stands for auto, 0 for a block per row.
  int mg_lanes = -1;
  /// PALPATION_CUDA_PROFILE: non-zero times the stages of each solved step with events and
  /// prints their medians on stderr when the backend is destroyed. Default 0 (off).
  bool profile = false;
  /// PALPATION_CUDA_PHASES: non-zero times the persistent PCG kernel's phases (PcgPhase,
  /// common.cuh) on one thread between its grid barriers and prints their sums on stderr
  /// when the backend is destroyed. Default 0 (off).
  bool phases = false;

  /// Reads every knob above from the environment (unset or empty: the default).
  static CudaTuning from_environment();
};

}  // namespace palpation::sim::cuda
