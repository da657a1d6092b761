// The CPU backend: corotational FEM, linearised backward Euler, block-Jacobi PCG.
#pragma once

#include <memory>

#include "backend.h"

namespace palpation::sim {

/// Makes the CPU backend in the precision of params.solver.precision.
std::unique_ptr<Backend> make_cpu_backend(const Model& model, const SimParams& params);

/// Name of this machine's CPU (from /proc/cpuinfo), for reports.
std::string cpu_name();

}  // namespace palpation::sim
