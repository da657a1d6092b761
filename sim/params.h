// Run-time parameters of the simulation (what a scenario's tissue/solver/contact set).
#pragma once

#include <algorithm>

#include <string>
#include <vector>

#include <Eigen/Core>

namespace palpation::sim {

enum class Precision { Double, Float };

/// The CG preconditioner. BlockJacobi: the inverse of each node's 3x3 diagonal block,
/// cheap per iteration, but the iterations grow with the mesh and with Poisson's ratio.
/// Multigrid: smoothed aggregation (amg.h), 3-4x fewer iterations that grow less with the
/// mesh, each about five block-Jacobi iterations' time on the CPU (docs/simulation.md);
/// CPU and CUDA backends. Its finest level is smoothed by one block-Jacobi sweep, or by a
/// Chebyshev polynomial of degree 2 where the nodal-pressure term holds half the system's
/// trace or more (multigrid_keeper.h): the Hertz scene's iterations then go 101 -> 94 from
/// Poisson's ratio 0.40 to 0.49 where one sweep's go 103 -> 219. MultigridChebyshev: the
/// same levels, Chebyshev on the finest one always (on the breast at 1 ms steps and 0.45 it
/// costs more time than it saves). MultigridJacobi: the same levels, one Jacobi sweep on the
/// finest one always (what Multigrid does below the share; to measure where the two cross).
/// Auto (the default): the one default_preconditioner picks for the backend and the mesh,
/// resolved where a backend is made (resolved_for in model.h), as Element::Auto is.
/// Where the error controller's converged check solves its reference (SolverParams::check).
enum class CheckPlace { Auto, InStep, Beside };
inline const char* check_place_name(CheckPlace c) {
  return c == CheckPlace::InStep ? "in-step" : c == CheckPlace::Beside ? "beside" : "auto";
}
inline std::vector<std::string> check_place_names() { return {"auto", "in-step", "beside"}; }
/// The place named (one of check_place_names(); any other name: Auto).
inline CheckPlace parse_check_place(const std::string& name) {
  return name == "in-step" ? CheckPlace::InStep : name == "beside" ? CheckPlace::Beside : CheckPlace::Auto;
}

/// How a step's CG solve starts, from the velocity changes dv of the last solves (both
/// backends; SolverParams::warm_start). Extrapolated: after a converged solve the last two
/// extrapolated, 2 dv_n - dv_n-1, else dv_n. Last (what Auto means): dv_n, the last two
/// extrapolated only after two solves in a row to kExtrapolateBelow or tighter. The
/// extrapolation doubles the error of the solves it extrapolates: under the error
/// controller's tolerances (1e-2 to 0.1) the guess then lands far off (on the paper sweep
/// held at 1 % the warm start's residual was 0.2-5.5 |b|, where a zero start's is |b|), and
/// the loose steps' errors add up in the force series. On the CPU, held at 1 %, 1,000 steps
/// of the paper sweep, CG iterations a step on average: paper float 12.7 -> 9.6, paper
/// double 11.2 -> 11.1, coarse 5.2 -> 5.6 (the coarse breast's controller sits at 5e-2,
/// where neither start is close); the error controller's test box: the median step's
/// force error 3.6e-4 -> 2.7e-4 of the converged run (docs/benchmarks.md). At a fixed tolerance
/// of 1e-3 both extrapolate after every solve but the first. Tried and not kept: the
/// start scaled by its energy-optimal factor (x . b) / (x . A x), 5 iterations a step on
/// the paper sweep but a force series 1.2 % off on the test box at a 1 % target (the
/// scale shrinks every start towards zero, the same way each step).
enum class WarmStart { Auto, Extrapolated, Last };
inline const char* warm_start_name(WarmStart w) {
  return w == WarmStart::Extrapolated ? "extrapolated" : w == WarmStart::Last ? "last" : "auto";
}
inline std::vector<std::string> warm_start_names() { return {"auto", "extrapolated", "last"}; }
/// The warm start named (one of warm_start_names(); any other name: Auto).
inline WarmStart parse_warm_start(const std::string& name) {
  return name == "extrapolated" ? WarmStart::Extrapolated : name == "last" ? WarmStart::Last : WarmStart::Auto;
}
inline WarmStart resolve_warm_start(WarmStart w) { return w == WarmStart::Auto ? WarmStart::Last : w; }
/// The relative residual at or below which WarmStart::Last extrapolates (after two such
/// solves in a row): at CG 1e-3 the extrapolation takes 13 % fewer iterations than the last
/// solution (paper sweep, CPU, float: 26 against 30), from 1e-2 on more (above). Tried
/// higher: at 8e-3 to 1.2e-2 the paper sweep in double took 9.4 iterations a step (11.1
/// here) and in float 9.4 (9.6), but the test box's series, whose controller sits at 8e-3
/// and 1.6e-2, went 1.13 % off against its 1 % target.
inline constexpr double kExtrapolateBelow = 3e-3;
/// The solves in a row to kExtrapolateBelow, counted up to the two that WarmStart::Last
/// asks, after one that reached `relative_residual`.
inline int count_tight_solves(int before, double relative_residual) {
  return relative_residual <= kExtrapolateBelow ? std::min(before + 1, 2) : 0;
}
/// Whether the next warm start extrapolates: after a converged solve (Extrapolated), or
/// two tight ones (Last).
inline bool warm_start_extrapolates(WarmStart w, bool last_converged, int tight_solves) {
  return w == WarmStart::Extrapolated ? last_converged : tight_solves >= 2;
}

enum class Preconditioner { Auto, BlockJacobi, Multigrid, MultigridChebyshev, MultigridJacobi };
inline bool is_multigrid(Preconditioner p) { return p != Preconditioner::BlockJacobi && p != Preconditioner::Auto; }

/// Nodes from which Auto means Multigrid on the GPU's persistent solver. Measured on an H200
/// (docs/simulation.md, "Which preconditioner runs"; CUDA, double, the paper sweep, 1,000
/// steps; block-Jacobi -> multigrid): the paper breast (8,445 nodes) is quicker with
/// block-Jacobi (0.77-0.85x), whose few iterations are nearly all barriers; from the fine
/// breast (24,982 nodes) the multigrid is as quick or quicker (1.08x at CG 1e-3, level held
/// at 1 % with the p99 4.33 -> 3.58 ms), at 42,967 nodes 1.05-1.20x, on xfine 1.27-1.42x and
/// on the 800k-tetrahedron breast 1.36-1.69x. On the CPU block-Jacobi's step is the shorter
/// on every mesh measured, coarse to xfine (paper: 30 -> 7 iterations at CG 1e-3 but 32 ->
/// 47 ms a step; xfine on 16 cores 258 -> 592 ms), so Auto is block-Jacobi there at any size.
inline constexpr int kGpuMultigridFromNodes = 20000;
inline Preconditioner default_preconditioner(bool gpu, int nodes) {
  return gpu && nodes >= kGpuMultigridFromNodes ? Preconditioner::Multigrid : Preconditioner::BlockJacobi;
}
/// The preconditioner that runs: p itself unless it is Auto.
inline Preconditioner resolve_preconditioner(Preconditioner p, bool gpu, int nodes) {
  return p == Preconditioner::Auto ? default_preconditioner(gpu, nodes) : p;
}
inline const char* preconditioner_name(Preconditioner p) {
  switch (p) {
    case Preconditioner::Auto: return "auto";
    case Preconditioner::Multigrid: return "multigrid";
    case Preconditioner::MultigridChebyshev: return "multigrid-chebyshev";
    case Preconditioner::MultigridJacobi: return "multigrid-jacobi";
    case Preconditioner::BlockJacobi: break;
  }
  return "block-jacobi";
}
inline constexpr Preconditioner kPreconditioners[] = {Preconditioner::Auto, Preconditioner::BlockJacobi,
                                                     Preconditioner::Multigrid, Preconditioner::MultigridChebyshev,
                                                     Preconditioner::MultigridJacobi};
inline std::vector<std::string> preconditioner_names() {
  std::vector<std::string> names;
  for (Preconditioner p : kPreconditioners) names.emplace_back(preconditioner_name(p));
  return names;
}
/// The preconditioner named (one of preconditioner_names(); any other name: BlockJacobi).
inline Preconditioner parse_preconditioner(const std::string& name) {
  for (Preconditioner p : kPreconditioners)
    if (name == preconditioner_name(p)) return p;
  return Preconditioner::BlockJacobi;
}

struct SolverParams {
  double dt = 0.001;               // s, time step (backward Euler)
  double cg_tolerance = 1e-3;      // relative residual ||r|| / ||b||; force error 2.5e-6 on coarse (docs/benchmarks.md)
  int cg_max_iterations = 200;
  // A solve that reaches cg_max_iterations with its relative residual still above
  // cg_rescue_tolerance goes on, up to cg_rescue_iterations in all, until it is below: a cap
  // chosen for speed never leaves a step far from its solution (such steps drift and, on
  // the large meshes, diverge within a few steps; stiff inclusions and sliver elements need
  // more iterations than the cap: docs/stability.md). cg_rescue_iterations <= the cap: no
  // rescue (a fixed-iteration solver, what the bench's capped points measure).
  double cg_rescue_tolerance = 1e-3;
  int cg_rescue_iterations = 2000;
  Precision precision = Precision::Double;
  int threads = 0;                 // CPU threads, 0 = all cores where it pays
  // CPU backend: an element keeps its rotation and stiffness blocks while no entry of its
  // deformation gradient F moved more than this since its last update (0: every element
  // every step, as the CUDA backend does). backend_cpu.cpp says why this is safe;
  // docs/benchmarks.md has the step time against force error. Under a force-error target
  // a positive tolerance is chosen from the target (resolve_corotation_tolerance).
  double corotation_tolerance = 1e-3;
  Preconditioner preconditioner = Preconditioner::Auto;
  // > 0: the finger-force error to hold (a fraction of the converged force); the CG
  // tolerance is then chosen and adapted by Simulation (error_control.h), cg_tolerance its
  // start. 0: cg_tolerance as given, fixed. Scenario files that name no cg_tolerance and
  // the workstation's patients hold kDefaultForceError; scenarios built in code (the
  // built-in ones included) get a fixed tolerance unless they ask (--force-error).
  double force_error = 0;
  // Where the converged check of the error controller solves its reference
  // (error_control.h). InStep: within the check's step, which then keeps the reference
  // (that step takes both solves). Beside: on a second backend of the same kind, beside the
  // steps (on CUDA a low-priority stream of its own: no step waits for it), the loose step
  // kept and its error known some steps later; where the backend cannot fork
  // (Backend::make_shadow), in the step. Auto: Beside on the fast CUDA backend (on the
  // multiprocessors the steps' solve leaves, as on the paper mesh; where it leaves none, as
  // on xfine, on the whole device a slice at a time after each step, so that a check holds
  // a step up by a slice rather than by a whole reference solve), InStep elsewhere (on the
  // CPU a second solve would take the same cores).
  CheckPlace check = CheckPlace::Auto;
  WarmStart warm_start = WarmStart::Auto;
};

/// The force error a scenario holds when it names neither solver.force_error nor
/// solver.cg_tolerance: 1 % of the converged force, under the 15 % that a trainee can
/// tell apart (facts.md: Weber fraction of compliance).
inline constexpr double kDefaultForceError = 0.01;

/// The CPU's corotation tolerance under a force-error target: this times the target. A
/// rotation kept off by at most tol moves the finger force by C tol; on the breast at the
/// paper sweep's first push C measured 0.2-0.45 (coarse and paper meshes, tol 1e-3 to
/// 1e-2, docs/benchmarks.md), and at most 1.1 on the meshes Gmsh made before they were the
/// same on every machine (tst_backend_agreement). So the kept rotations take at most a
/// third of the target, the rest is left to the CG error the controller holds
/// (error_control.h). At 1 % the tolerance is 3e-3, where the coarse breast's element pass
/// extracts 2.5x and re-rotates 3x fewer elements than at 1e-3.
inline constexpr double kCorotationPerForceError = 0.3;

/// The corotation tolerance a CPU backend runs: 0 (every element every step) and any
/// tolerance at a fixed CG tolerance (force_error 0) as given; under a force-error target,
/// kCorotationPerForceError x the target, at most 1e-2 (the scenario's bound).
inline double resolve_corotation_tolerance(const SolverParams& s) {
  if (!(s.corotation_tolerance > 0) || !(s.force_error > 0)) return s.corotation_tolerance;
  return std::min(kCorotationPerForceError * s.force_error, 1e-2);
}

/// Rayleigh damping C = alpha M + beta K.
struct DampingParams {
  double mass = 1.0;               // alpha, 1/s
  double stiffness = 0.01;         // beta, s
};

/// Penalty contact between a fingertip sphere and the surface (paper eq. 1):
///   F = -(A / (pi r^2)) (k_s d + k_e v)   per surface triangle in contact,
/// d the penetration depth, v its rate, A the triangle's area, r the finger's radius
/// (contact_sphere.h says why the area weight). Enters the implicit system as k_s n n^T.
struct ContactParams {
  double stiffness = 5000.0;       // k_s, N/m for a contact patch of the fingertip's cross-section
  double damping = 5.0;            // k_e, N s/m for the same patch
  double force_filter_hz = 100.0;  // first-order low-pass cutoff of the finger force
};

/// Tetrahedral formulation. Linear: the constant-strain corotational tetrahedron, one
/// volumetric strain per element, which locks as Poisson's ratio approaches 0.5 (too
/// stiff). NodalPressure: the same element with its volumetric term lambda tr(eps)
/// averaged over each node's elements (average nodal pressure, nodal_pressure.h), which
/// does not lock; on the cpu and cuda backends (not the cuda-csr baseline). Auto: the one
/// default_element picks for the model's tissue, resolved where a backend is made, so a
/// scenario built in code gets the same element as one parsed from a file.
enum class Element { Auto, Linear, NodalPressure };

/// Poisson's ratio from which Auto means NodalPressure: at 0.45 the linear element is
/// already 14 % too stiff in the Hertz indentation (28 across; docs/simulation.md) against
/// 2.5 % for the nodal one, and breast tissue lies at 0.45-0.499.
inline constexpr double kNodalPressureFromPoisson = 0.45;
inline Element default_element(double poisson_ratio) {
  return poisson_ratio >= kNodalPressureFromPoisson ? Element::NodalPressure : Element::Linear;
}
/// The element that runs for tissue of this Poisson's ratio: e itself unless it is Auto.
inline Element resolve_element(Element e, double poisson_ratio) {
  return e == Element::Auto ? default_element(poisson_ratio) : e;
}

/// The names of the elements in scenarios (tissue.element) and on the command line.
inline const char* element_name(Element e) {
  return e == Element::NodalPressure ? "nodal-pressure" : e == Element::Linear ? "linear" : "auto";
}
/// The element a name means; Auto for a name that is not one (callers validate against
/// element_names()).
inline Element parse_element(const std::string& name) {
  return name == "nodal-pressure" ? Element::NodalPressure : name == "linear" ? Element::Linear : Element::Auto;
}
/// The names a scenario or a command may give (Auto is never written: a scenario names
/// the element it resolved to).
inline std::vector<std::string> element_names() { return {"linear", "nodal-pressure"}; }

/// One band of tissue below the skin (tissue_layers.h). Layers are listed from the skin
/// inward; the last one (the core) takes everything deeper and has no thickness.
struct TissueLayer {
  std::string name;                // "skin", "fat", "glandular": reports and messages
  double thickness = 0.0;          // m, > 0; 0 for the last layer
  double young_modulus = 19000.0;  // Pa
};

/// The skin as a membrane on the surface triangles (fem_membrane.h): its thickness and
/// modulus give the in-plane stiffness E t; its Poisson's ratio is the tissue's.
/// Thickness 0: no skin.
struct SkinSpec {
  double thickness = 0.0;          // m
  double young_modulus = 56000.0;  // Pa
  bool present() const { return thickness > 0.0; }
};

struct SimParams {
  Element element = Element::Auto;
  SolverParams solver;
  DampingParams damping;
  ContactParams contact;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // m/s^2
};

/// True when a and b differ in more than the time step and the CPU thread count. Those
/// two the real-time loop changes between steps, and a body at rest stays at rest under
/// them; any other change (gravity above all) must wake a resting body.
inline bool differ_beyond_step(const SimParams& a, const SimParams& b) {
  const SolverParams &s = a.solver, &t = b.solver;
  return a.element != b.element || s.cg_tolerance != t.cg_tolerance || s.cg_max_iterations != t.cg_max_iterations ||
         s.cg_rescue_tolerance != t.cg_rescue_tolerance || s.cg_rescue_iterations != t.cg_rescue_iterations ||
         s.precision != t.precision || s.corotation_tolerance != t.corotation_tolerance || s.preconditioner != t.preconditioner ||
         a.damping.mass != b.damping.mass || a.damping.stiffness != b.damping.stiffness ||
         a.contact.stiffness != b.contact.stiffness || a.contact.damping != b.contact.damping ||
         a.contact.force_filter_hz != b.contact.force_filter_hz || a.gravity != b.gravity;
}

/// One fingertip as the simulation sees it: a rigid sphere.
struct FingerInput {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // sphere centre, m, world
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
  double radius = 0.008;                               // m
  bool active = true;
};

/// What a step yields per finger: the force and a local contact model that the 1 kHz
/// haptic loop re-evaluates between simulation updates.
struct FingerOutput {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();      // filtered, on the finger, N
  Eigen::Vector3d force_raw = Eigen::Vector3d::Zero();  // unfiltered sum, N
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  // d(force)/d(finger position), N/m
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();  // mean contact vertex, m
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();     // unit, from surface to finger
  int contacts = 0;                                     // vertices in contact
};

struct StepStats {
  int cg_iterations = 0;
  double cg_residual = 0.0;        // relative, at exit
  bool rescued = false;            // the solve went past cg_max_iterations (SolverParams)
  // The state's summary for the divergence guard, formed within the step so that the guard
  // needs no read-back of the state: the largest node speed (m/s) and displacement from
  // rest (m), the kinetic energy (J), all +inf when a velocity is not finite. Negative:
  // not formed (a skipped step; Simulation then reads the state back).
  double max_speed = -1, max_displacement = -1, kinetic_energy = -1;
  bool solved = false;             // false when the step was skipped (body at rest)
  bool finite = true;
  int contacts = 0;
};

}  // namespace palpation::sim
