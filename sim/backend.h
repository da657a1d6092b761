// The backend interface: one synchronous step of the whole simulation on one device.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "levels_job.h"
#include "model.h"
#include "params.h"

namespace palpation::sim {

/// A backend owns the mutable state (positions, velocities, rotations, solver workspace)
/// of one Model. It never owns a thread; callers serialise calls.
class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;         // "cpu" or "cuda"
  virtual std::string device_name() const = 0;  // CPU model or GPU name
  virtual Precision precision() const = 0;

  /// Puts the body at rest in its reference shape, velocities and filters zeroed.
  virtual void reset() = 0;
  /// Advances one time step dt with the fingers at their end-of-step poses.
  /// `out` receives one FingerOutput per input finger.
  virtual StepStats step(std::span<const FingerInput> fingers, std::span<FingerOutput> out) = 0;
  /// All node positions (nnode x 3, m). Copies from the device: call at display rate.
  virtual void positions(std::vector<double>& xyz) const = 0;
  /// All node velocities (nnode x 3, m/s).
  virtual void velocities(std::vector<double>& xyz) const = 0;
  /// Takes new per-element materials (painting a tumour): the Lame parameters of every
  /// element, as many as the model has elements. The backend starts with the model's.
  virtual void set_materials(const Materials& m) = 0;
  /// Changes solver/contact/damping parameters between steps.
  virtual void set_params(const SimParams& p) = 0;
  virtual const SimParams& params() const = 0;
  /// Keeps aside what a step changes (positions, velocities, the warm start, the force
  /// filters, the rest flag; rotations where a take would change them), so that
  /// rollback() can take the same step again
  /// (the converged check of error_control.h). False: this backend cannot.
  virtual bool checkpoint() { return false; }
  /// Back to the state of the last checkpoint() (none since the last reset: nothing).
  virtual void rollback() {}
  /// rollback(), and the next take's CG starts from the solution of the take just undone
  /// instead of the warm start's extrapolation: the same step's system solved again, to a
  /// tighter tolerance (the converged check's reference), goes on from where the first
  /// take stopped. The steps after it extrapolate as after any take. By default: rollback().
  virtual void rollback_for_reference() { rollback(); }
  /// The converged check beside the steps (SolverParams::check): a second backend of this
  /// kind, for this model, that takes the check's reference while this one goes on. On CUDA
  /// it works in a stream of its own, below this one's priority. Null: this backend cannot
  /// (the check is then taken in the step). Under CheckPlace::Auto (params.solver.check)
  /// the backend decides: null where the check beside would not shorten the steps.
  virtual std::unique_ptr<Backend> make_shadow(const SimParams& /*params*/) const { return nullptr; }
  /// After checkpoint() and a take: puts `shadow` (of make_shadow(), idle) where
  /// rollback_for_reference() would put this backend: the checkpoint's state, its next take
  /// starting from this take's solution. The copies are ordered before anything either
  /// backend does next. False, and `shadow` untouched, when it cannot.
  virtual bool fork_reference(Backend& /*shadow*/) { return false; }
  /// A take in two halves, for a backend stepped beside another: begin_step() starts it,
  /// step_ready() says whether it has finished (never waits), finish_step() waits for it
  /// and gives what step() would have. By default begin_step() takes the whole step.
  virtual void begin_step(std::span<const FingerInput> fingers);
  virtual bool step_ready() const { return true; }
  /// A take begun in slices (a backend that shares its device with the steps, a slice of
  /// the solve at a time): queues the next slice where the last one has finished and more
  /// remain; never waits. The owner calls it after each of its own steps, so that a slice
  /// runs where the device would otherwise be idle or holds one step up by one slice only.
  /// finish_step() runs whatever slices remain. By default a take is one piece: nothing.
  virtual void step_on() {}
  virtual StepStats finish_step(std::span<FingerOutput> out);
  /// The multigrid levels this backend built since it was made (solver.preconditioner
  /// multigrid or multigrid-chebyshev), and the builds that threw: their step and the next
  /// 1,000 ran block-Jacobi (multigrid_keeper.h). Zeros for a backend without a multigrid.
  struct MultigridCounts {
    long builds = 0;
    long failures = 0;
    // The levels in use: their finest level smoothed by Chebyshev (multigrid_keeper.h:
    // where the nodal-pressure term holds a large share of the system), and that share.
    bool chebyshev = false;
    double pressure_share = 0;
    /// For reports: "none" before the first build, else "chebyshev" or "jacobi".
    const char* smoother() const { return builds == 0 ? "none" : chebyshev ? "chebyshev" : "jacobi"; }
  };
  virtual MultigridCounts multigrid_counts() const { return {}; }
  /// After reset(), with a multigrid preconditioner and the body at rest (no solve until
  /// something touches it): builds the levels now, from the system at rest, rather than in
  /// the first touch's step (0.3-1 s on the paper mesh, 11 s on xfine). The state is
  /// unchanged. Nothing otherwise; a build that throws leaves the first steps to
  /// block-Jacobi, as in a step.
  virtual void prepare_solver() {}
  /// Deferred multigrid builds (off by default): with levels already built, a rebuild that
  /// falls due in a step (the system drifted, dt moved, materials changed) is not done in
  /// it; the step and those after it keep the present levels, and take_levels_job() hands
  /// the build out, for another thread to run (LevelsJob::run) and install_levels() to put
  /// in use between steps. A build at a reset (prepare_solver) is never deferred. Off
  /// drops a job not yet installed. Nothing for a backend without a multigrid.
  virtual void set_deferred_levels(bool /*on*/) {}
  /// The deferred build that fell due and was not yet handed out, or null.
  virtual std::shared_ptr<LevelsJob> take_levels_job() { return nullptr; }
  /// Between steps, after `job`'s run() returned: its levels in use from the next step on.
  /// False, and nothing changes, for a job of another backend or of a system changed since
  /// it was taken (reset, materials, element or preconditioner), or not done; false, counted
  /// as a failed build (multigrid_counts), for one whose run() threw.
  virtual bool install_levels(const std::shared_ptr<LevelsJob>& /*job*/) { return false; }

 private:
  // The default begin_step()'s result, until finish_step() hands it out.
  StepStats begun_stats_;
  std::vector<FingerOutput> begun_out_;
};

enum class BackendKind { Auto, Cpu, Cuda };

/// Makes a backend. `model` must outlive it. Throws std::runtime_error with a clear
/// message when the kind asked for is unavailable (cuda without a GPU).
std::unique_ptr<Backend> make_backend(BackendKind kind, const Model& model, const SimParams& params,
                                      std::string* chosen_reason = nullptr);

/// True when this build has the CUDA backend and a usable GPU is present.
bool cuda_available(std::string* why_not = nullptr);

/// Every backend this build and machine can run, by name: "cpu"; with a GPU also "cuda"
/// (the fast one), "cuda-csr" (the textbook baseline: assembled CSR, cuSPARSE SpMV,
/// cuBLAS dot/axpy, the host driving each CG iteration) and "cuda-bsr" (the good first
/// port: BSR SpMV, the CG scalars on the GPU, the iterations replayed from a CUDA graph).
std::vector<std::string> available_backends();
/// How every backend ends a finger's output once its contacts are summed: the contact point
/// averaged over them, the raw force's direction as the normal, and the force low-pass
/// filtered by one pole at contact.force_filter_hz (`filtered`: the filter's state, carried
/// from step to step; `filter_alpha`: force_filter_alpha of the step).
void finish_finger_output(FingerOutput& o, Eigen::Vector3d& filtered, double filter_alpha);
/// The one-pole filter's weight of a new sample for a cut-off of `hz` at steps of `dt` s.
double force_filter_alpha(double hz, double dt);

/// True for the GPU backends that exist to be measured against ("cuda-csr", "cuda-bsr"):
/// ports of the same step onto cuSPARSE and cuBLAS, with the linear element only.
bool is_library_baseline(const std::string& name);
/// Why backend `name` cannot run these parameters ("backend NAME: ..."), or empty: the
/// library baselines precondition with block-Jacobi only (the multigrid runs on the cpu and
/// cuda backends).
std::string library_baseline_refusal(const std::string& name, const SimParams& params);
/// Makes a backend by name. Throws std::runtime_error for an unknown/unavailable one.
std::unique_ptr<Backend> make_named_backend(const std::string& name, const Model& model, const SimParams& params);

/// The floor of one CG iteration on the GPU: the bytes it must move and the grid-wide
/// synchronisations it needs, turned into a time with the bandwidth and sync cost
/// measured on the device now.
struct FloorEstimate {
  double bytes_per_iteration = 0;      // B
  int syncs_per_iteration = 0;
  double bandwidth_gbs = 0;            // measured, GB/s (read + write)
  double sync_us = 0;                  // measured cost of one grid-wide sync, us
  double iteration_us = 0;             // bytes / bandwidth + syncs * sync_us
  double step_fixed_us = 0;            // per-step work outside CG (assembly etc.) floor
  std::string device;
};
/// Measures it (CUDA builds with a GPU); false otherwise.
bool cuda_floor(const Model& model, Precision precision, FloorEstimate& out);

}  // namespace palpation::sim
