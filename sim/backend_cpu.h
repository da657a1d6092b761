// The CPU backend: corotational FEM, linearised backward Euler, block-Jacobi PCG.
#pragma once

#include <memory>

#include "backend.h"

namespace palpation::sim {

/// Full re-assemblies of the kept stiffness: one after this many assembling steps.
inline constexpr long kCpuReassembleSteps = 65536;

/// What the CPU backend's work skipping did since it was made (read-only, for tests and
/// reports): steps taken, steps skipped because the body rested untouched, and full
/// assemblies of K (the first, after a reset, material or tolerance change, at tolerance
/// 0 every step, and every kCpuReassembleSteps assembling steps), and the block-Jacobi
/// inverses taken (the rows whose diagonal block changed). Its multigrid builds:
/// Backend::multigrid_counts.
struct CpuWorkCounters {
  long steps = 0;
  long skipped_at_rest = 0;
  long full_assemblies = 0;
  long parallel_steps = 0;        // solved steps whose passes ran on OpenMP's threads
  long preconditioner_rows = 0;   // diagonal blocks inverted
};

/// The counters of a CPU backend; zeros for any other backend.
CpuWorkCounters cpu_work_counters(const Backend& b);

/// The largest difference between the block-Jacobi inverses a CPU backend kept for its last
/// solved system and those taken afresh from that system (still assembled after the step):
/// zero where every changed row was inverted again. -1 for any other backend, or before
/// a solve.
double cpu_preconditioner_staleness(const Backend& b);

/// Makes the CPU backend in the precision of params.solver.precision.
std::unique_ptr<Backend> make_cpu_backend(const Model& model, const SimParams& params);

/// Name of this machine's CPU (from /proc/cpuinfo), for reports.
std::string cpu_name();

}  // namespace palpation::sim
