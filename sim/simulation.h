// A scenario made into a running simulation: mesh -> model (tissue, inclusions, fixed
// chest wall) -> backend, and the finger paths sampled each step. Synchronous; owns no
// thread.
#pragma once

#include <exception>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "backend.h"
#include "error_control.h"
#include "model.h"
#include "phantom.h"
#include "scenario.h"

namespace palpation::sim {

/// Builds the model of a scenario from its mesh: bulk tissue, inclusions (elements whose
/// centroid lies inside), chest wall fixed (nodes at z <= 1e-6 m; for a mesh file the
/// lowest nodes within 1e-6 of the minimum z). A mesh file (patient.mesh) must have no
/// sliver: every element's quality >= kMinTetQuality, else ScenarioError naming the file,
/// the element and its quality (docs/stability.md: CG stops converging below).
Model build_scenario_model(const Scenario& s, TetMesh mesh);

/// Shape quality of a tetrahedron, 6 sqrt(2) |V| / l_rms^3 (l_rms: root mean square of the
/// six edge lengths): 1 for the regular tetrahedron, 0.66 for a cube's Kuhn tetrahedron,
/// about 2 x (height / edge) for a flat sliver, 0 when degenerate.
double tet_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);
/// The lowest element quality of a mesh; `worst` receives its element.
double min_tet_quality(const TetMesh& m, int* worst = nullptr);
/// Slivers below this make the CG solve of a step stall (stress case sliver-0.1%, quality
/// 0.0011: residual 6e-3 after 500 iterations; sliver-2%, quality 0.022, converges).
inline constexpr double kMinTetQuality = 0.001;

/// Applies inclusions to a model's elements (centroid test; the first that contains an
/// element's centroid gives it its material). An inclusion of the tissue's own material
/// leaves its elements' tissue as it is (their layer's in a layered tissue). Returns the
/// elements inside an inclusion.
int apply_inclusions(Model& m, const std::vector<Inclusion>& inclusions);

BackendKind parse_backend_kind(const std::string& name);

/// Divergence (design.md section 7): a step is divergent when anything it produced is not
/// finite, or the body moved further than physics allows: a node faster than `max_speed`
/// or displaced from rest by more than `max_displacement_factor` times the mesh's
/// bounding-box diagonal. Palpation moves fingers at most ~2 m/s; a stable step never
/// comes near these bounds (docs/stability.md).
struct DivergenceLimits {
  double max_speed = 50.0;               // m/s
  double max_displacement_factor = 1.0;  // x bounding-box diagonal
  bool enabled = true;
};

/// What the guard saw in one step (Simulation::last_check()).
struct DivergenceCheck {
  bool diverged = false;
  std::string reason;                    // "non-finite ...", "node speed ...", ...
  double max_speed = 0;                  // m/s, largest node speed
  double max_displacement = 0;           // m, largest |x - rest|
  double kinetic_energy = 0;             // J, lumped mass
};

class Simulation {
 public:
  /// Throws ScenarioError for a bad patient, std::runtime_error for an unavailable backend.
  Simulation(const Scenario& s, const LogFn& log = {});
  /// Uses an already built model (tests, benchmarks sharing one mesh).
  Simulation(const Scenario& s, Model model, const LogFn& log = {});

  const Scenario& scenario() const { return s_; }
  /// The body as built (mesh, rest state, the materials it was built with): never changed.
  const Model& model() const { return model_; }
  /// The elements' current materials (the model's, then each change applied).
  const Materials& materials() const { return materials_; }
  /// Changes elements' Young's modulus (Pa), their Poisson's ratio kept (painting a
  /// tumour). Elements out of range and moduli that are not positive and finite are
  /// ignored. Returns how many changed.
  int set_element_young(std::span<const std::pair<int, double>> changes);
  Backend& backend() { return *backend_; }
  const Backend& backend() const { return *backend_; }
  std::string backend_reason() const { return reason_; }

  /// Advances one step of the scenario: samples its finger paths at t + dt and takes the
  /// guarded step (advance) with them.
  StepStats step();

  /// What one guarded step did (advance).
  struct Outcome {
    StepStats stats;        // stats.finite is false after a divergence reset
    bool ok = true;         // outputs usable: no divergence, finite forces and stiffness
    bool fell_back = false; // the backend threw and the step was taken on the CPU from rest
    std::string error;      // the backend's error when fell_back
  };
  /// The guarded step every driver takes (headless runs, the real-time simulation thread
  /// of sessions and the workstation, the review's re-simulation): steps the backend with
  /// these finger inputs at dt = h (set on the backend when it differs). A backend that
  /// throws (a CUDA error mid-session) is replaced by the CPU backend (fall_back_to_cpu)
  /// and the step is retried there; the CPU backend throwing is rethrown. Divergence
  /// (DivergenceLimits) or a non-finite contact output puts the body back at rest, counts
  /// and logs it, and zeroes the outputs (ok = false).
  Outcome advance(std::span<const FingerInput> in, std::span<FingerOutput> out, double h);
  /// Replaces the backend by a CPU one with the same parameters, at rest. Returns false
  /// (and changes nothing) when the backend already is the CPU one.
  bool fall_back_to_cpu(const std::string& why);
  /// Fault injection and tests: replaces the backend (reset first by the caller).
  void replace_backend(std::unique_ptr<Backend> b) {
    drop_shadow();
    backend_ = std::move(b);
    backend_->set_deferred_levels(deferred_levels_);
    prepare_shadow();
  }
  /// Deferred multigrid builds (Backend::set_deferred_levels) on this backend and on any
  /// that replaces it; the caller takes the jobs from backend() and runs them.
  void set_deferred_levels(bool on) {
    deferred_levels_ = on;
    backend_->set_deferred_levels(on);
  }
  /// Checks the backend's state after a step (used by step() and the session thread).
  DivergenceCheck check_divergence(const StepStats& st, std::span<const FingerOutput> out);
  void set_divergence_limits(const DivergenceLimits& l) { limits_ = l; }
  const DivergenceLimits& divergence_limits() const { return limits_; }
  const DivergenceCheck& last_check() const { return check_; }
  int divergences() const { return divergences_; }
  /// Steps whose divergence guard read the state back (a backend that forms the summary in
  /// its step, as both do, leaves this at 0).
  int readbacks() const { return readbacks_; }
  int fallbacks() const { return fallbacks_; }
  /// The error controller's record (solver.force_error > 0; error_control.h): the CG
  /// tolerance it holds now, its converged checks and the errors they measured.
  const ErrorControlStats& error_control() const { return control_.stats(); }
  /// Where the controller's checks are solved now: "beside" (the steps) or "in-step"; ""
  /// while the controller is off.
  const char* check_place() const {
    return !control_.on() ? "" : shadow_ ? "beside" : "in-step";
  }
  void set_log(const LogFn& log) { log_ = log; }
  double time() const { return t_; }
  int steps() const { return steps_; }
  const std::vector<FingerInput>& fingers() const { return fingers_; }
  const std::vector<FingerOutput>& outputs() const { return outputs_; }
  void reset();

 private:
  void init(const LogFn& log);
  /// The backend's step under the error controller: the tolerance it holds, and every so
  /// many steps in contact the converged check (the step taken again, a hundred times
  /// tighter, from a checkpoint; the tighter one is kept).
  StepStats controlled_step(std::span<const FingerInput> in, std::span<FingerOutput> out);
  /// Whether the converged check goes beside the steps (SolverParams::check).
  bool check_beside() const;
  /// After the check's loose take (kept in loose_) and checkpoint: the reference begun on
  /// the shadow backend. False (nothing begun): the check is taken in the step.
  bool start_check_beside(std::span<const FingerInput> in);
  /// Scores the check beside the steps if it has finished (never waits for it).
  void collect_check();
  /// After a step: the check beside the steps queues its next slice, where it takes the
  /// device a slice at a time (Backend::step_on; never waits).
  void step_check_on();
  /// The shadow's parameters: the backend's, solved as a check's reference is.
  SimParams shadow_params() const;
  /// Makes the shadow backend where the checks go beside the steps and there is none: when
  /// the patient loads and the backend changes, so that no step pays for making it.
  void prepare_shadow();
  /// The check in flight dropped unscored (the body it measured was reset or changed).
  void drop_check();
  /// The shadow dropped with its check (another backend): prepare_shadow() makes another.
  void drop_shadow();
  /// A shadow that failed (made, forked or stepped): dropped with any check in flight, the
  /// reason logged, and the checks taken in the step from then on.
  void shadow_off(const std::exception& e);
  Scenario s_;
  Model model_;                          // const after construction
  Materials materials_;
  std::unique_ptr<Backend> backend_;
  std::string reason_;
  std::vector<FingerInput> fingers_;
  std::vector<FingerOutput> outputs_;
  double t_ = 0.0;
  int steps_ = 0;
  DivergenceLimits limits_;
  DivergenceCheck check_;
  int divergences_ = 0, fallbacks_ = 0;
  bool deferred_levels_ = false;
  double diagonal_ = 0;                  // m, rest bounding-box diagonal
  std::vector<double> xyz_, vel_;        // scratch
  bool summary_known_ = false;           // check_ holds the state's summary (unchanged by a skipped step)
  int readbacks_ = 0;                    // steps whose guard read the state back
  ToleranceController control_;
  double control_set_tol_ = -1;          // the tolerance the controller last gave the backend
  double rescue_base_ = 1e-3;            // the rescue tolerance and the cap of the parameters it started from
  int cap_base_ = 200;
  bool last_contact_ = false;            // the last step touched: a check may follow
  std::vector<FingerOutput> loose_;      // the check's loose outputs
  // The check beside the steps: its backend, the check in flight, its loose outputs.
  std::unique_ptr<Backend> shadow_;
  bool shadow_failed_ = false;           // this backend cannot have one: checks in the step
  struct {
    bool on = false;
    double tolerance = 0;                // the reference's
  } pending_check_;
  std::vector<FingerOutput> pending_loose_, reference_;
  LogFn log_;
};

}  // namespace palpation::sim
