// The Hertz indentation probe: a rigid sphere pressed slowly into a block bonded to a
// rigid base, through the whole dynamic step of a backend (penalty contact, implicit
// Euler, CG), against Hertz's law for a half-space corrected for the finite layer. The
// analytic check of the contact and of the element's (in)compressibility: tst_hertz runs
// it on the CPU, `palpation hertz` on any backend (tools/gpu-check.sh on the GPU).
#pragma once

#include <string>

#include "params.h"

namespace palpation::sim {

/// One indentation. The block is 10 x 10 x 5 cm, `cells` cells across x and y and
/// cells / 2 through z, graded (exponent 2) toward the contact; the sphere of radius R
/// comes down by `depth` in 20 steps of 10 ms and holds for 10 (quasi-static at this dt).
struct HertzCase {
  double young = 19000;  // Pa
  double nu = 0.45;
  double radius = 0.01;  // m
  double depth = 0.001;  // m, the sphere's travel from first touch
  int cells = 28;
  Element element = Element::Linear;
  Preconditioner preconditioner = Preconditioner::BlockJacobi;
  Precision precision = Precision::Double;
  double cg_tolerance = 1e-8;  // the solver's own error far below the mesh's
};

/// Hertz, F = 4/3 E/(1 - nu^2) sqrt(R) d^1.5, with the finite-layer correction of
/// Dimitriadis et al. 2002 (Biophys J 82:2798, eq. 12) for a layer of thickness 5 cm
/// bonded to its base: F (1 - 2 a0/pi chi + 4 a0^2/pi^2 chi^2), chi = sqrt(R d)/T,
/// a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu).
double hertz_force(const HertzCase& c, double depth);

struct HertzResult {
  bool ok = false;
  std::string why;          // when not ok: what went wrong
  double force = 0;         // N, along the press, at the end of the hold
  double depth = 0;         // m, the sphere's travel less the penalty penetration
  double reference = 0;     // N, hertz_force at that depth
  double error = 0;         // force / reference - 1
  int nodes = 0, tets = 0;
  int max_iterations = 0;   // CG iterations of the hardest step
  long total_iterations = 0;  // CG iterations of all the steps (a smoother's cost compares by it)
  std::string smoother = "none";  // the multigrid's finest smoothing at the end (Backend::MultigridCounts)
  double pressure_share = 0;      // the nodal-pressure term's share of the trace at the last level build
  double step_ms = 0;       // median wall time of the pressing steps
};

/// Runs the indentation on backend `backend` ("cpu", "cuda", ...). Throws what
/// make_named_backend throws for a backend this build or machine lacks.
HertzResult hertz_indent(const HertzCase& c, const std::string& backend = "cpu");

}  // namespace palpation::sim
