// When a backend's multigrid levels (amg.h) are built and rebuilt: one policy for the CPU
// and the CUDA backends, so that both precondition the same step with levels built from
// the same system.
//
// The levels are built from the system at rest when the patient loads (the backends'
// prepare_solver(), after a reset), else from a step's system the first time they are
// needed, and again: after invalidate() (a reset, a change of materials, element or
// preconditioner); when the stiffness's weight (from dt) has been more than twice or less
// than half the one they were built with for kMovedSteps steps in a row, at most once
// every 100 steps; and when a solve ended beyond its tolerance and the rescue tolerance
// (or not finite) or needed twice the iterations of the first solve after the build, and
// ten more (the system drifted: rotations, contact). A build that throws (a system that
// is not finite, a stalled coarsening) leaves this step and the next 1,000 to
// block-Jacobi.
//
// The real-time loop sets dt from the wall clock: a step that overran (a build's is one:
// 0.8-1 s on the paper mesh, 11-12 s on xfine, on the GPU machine's host) is followed by one
// step at the loop's largest dt, ten times the usual. That one step neither rebuilds nor
// counts against the levels: a solve at a weight outside [1/2, 2] of theirs is left out of
// the drift rules, since its poorer solve says nothing of the levels, and a rebuild for it
// would overrun again and set the next step's dt as large.
#pragma once

#include <exception>
#include <memory>
#include <vector>

#include "amg.h"
#include "levels_job.h"
#include "model.h"
#include "nodal_pressure.h"
#include "params.h"

namespace palpation::sim {

class MultigridKeeper {
 public:
  /// The options the levels of preconditioner `p` are built with. Multigrid: one Jacobi
  /// sweep, or Chebyshev of degree 2 where the nodal-pressure term holds at least
  /// kChebyshevShare of the system's trace at the build (nearly incompressible,
  /// stiffness-dominated systems, whose iterations one sweep lets grow with Poisson's
  /// ratio). MultigridChebyshev: Chebyshev of degree 2 always. MultigridJacobi: one Jacobi
  /// sweep always (amg::Options' default share, above 1, never switches).
  static amg::Options options(Preconditioner p) {
    amg::Options o;
    if (p == Preconditioner::MultigridChebyshev) {
      o.smoother = amg::Smoother::Chebyshev;
      o.degree = 2;
    } else if (p == Preconditioner::Multigrid) {
      o.chebyshev_share = kChebyshevShare;
    }
    return o;
  }
  /// amg::Options::chebyshev_share. The share where Chebyshev becomes the faster step moves
  /// with the scene and the mesh (docs/simulation.md, "Where the two cross"): from 0.32 or
  /// below on the Hertz probe, about 0.4 on the paper breast at 1 ms steps, above 0.69 on
  /// xfine. At 0.5 the Hertz probe at 0.49 keeps its Chebyshev (1.9x fewer iterations),
  /// the paper breast forgoes 3-5 % below it and xfine pays 8-9 % just above it.
  static constexpr double kChebyshevShare = 0.5;

  /// Before a solve preconditioned by `p` of a system whose stiffness weight is `scale`:
  /// when the levels are due, takes the system they are built from (snapshot(), a
  /// LevelsSystem) and builds them below `model`'s free nodes, then calls
  /// after_build(levels) (a copy of them elsewhere: what it throws goes to the caller); says
  /// whether this solve uses them. A build that throws (the snapshot's included): this step
  /// and the next 1,000 run block-Jacobi. With deferred builds (set_deferred) and levels
  /// already built, a rebuild that falls due is handed out as a job (take_job) instead,
  /// unless `may_defer` is false, and the solves keep the present levels until install():
  /// the step only takes the snapshot; the job makes the system and builds.
  /// `builds` and `failures` count the builds done and those that threw.
  template <class Snapshot, class AfterBuild>
  bool prepare(Preconditioner p, double scale, const Model& model, Snapshot&& snapshot, AfterBuild&& after_build,
               long& builds, long& failures, bool may_defer = true) {
    if (!is_multigrid(p)) return false;
    ++steps_;
    if (failed_at_ >= 0 && steps_ - failed_at_ < 1000) return false;
    const double ratio = scale / scale_;
    off_steps_ = (ratio <= 2.0 && ratio >= 0.5) ? 0 : off_steps_ + 1;
    const bool dt_moved = off_steps_ >= kMovedSteps && steps_ - built_at_ >= 100;
    if (levels_.built() && !stale_ && !dt_moved) return true;
    const bool defer = deferred_ && may_defer && levels_.built();
    if (defer && job_) return true;  // one job at a time; these levels until it is installed
    try {
      LevelsSystem system = snapshot();
      if (defer) {
        job_ = std::make_shared<LevelsJob>(std::move(system), rest_nodes(model), options(p), scale);
        job_taken_ = false;
        return true;
      }
      amg::SpMat stiffness, pressure;
      system(stiffness, pressure);
      LevelsJob::build(levels_, stiffness, pressure, rest_nodes(model), options(p));
    } catch (const std::exception&) {
      failed_at_ = steps_;
      ++failures;
      return false;
    }
    after_build(levels_);
    adopt(scale, builds);
    return true;
  }

  /// Deferred builds on or off (off: every build in the step that finds it due). Off drops
  /// a job not yet installed; its rebuild is then done in the next step that uses the levels.
  void set_deferred(bool on) {
    deferred_ = on;
    if (!on) job_.reset();
  }
  /// The job of a deferred rebuild not yet handed out, or null.
  std::shared_ptr<LevelsJob> take_job() {
    if (!job_ || job_taken_) return nullptr;
    job_taken_ = true;
    return job_;
  }
  /// Between steps: the levels of `job` (run() done) replace the present ones, after
  /// after_build(levels) as in prepare(). False, and nothing changes, for a job that is not
  /// this keeper's present one (another backend's, or one of a system changed since:
  /// invalidate()) or not done; false, counted as a failed build, for one whose run() threw.
  template <class AfterBuild>
  bool install(const std::shared_ptr<LevelsJob>& job, AfterBuild&& after_build, long& builds, long& failures) {
    if (!job || job != job_ || !job->done()) return false;
    job_.reset();
    if (job->error_) {
      failed_at_ = steps_;
      ++failures;
      return false;
    }
    levels_ = std::move(job->levels_);
    after_build(levels_);
    adopt(job->scale_, builds);
    return true;
  }

  /// Steps in a row at a weight outside [1/2, 2] of the levels' that make a rebuild due.
  static constexpr int kMovedSteps = 20;

  /// After a solve that used the levels: `solved` when it ended within its tolerance or
  /// the rescue tolerance, `tolerance` the one it was asked for. A solve at a weight
  /// outside [1/2, 2] of the levels' (the last prepare()'s) is not counted.
  void note(int iterations, bool solved, double tolerance) {
    if (off_steps_ > 0) return;  // a weight the levels were not built for: no sign of drift
    if (!solved) {
      stale_ = true;
    } else if (reference_iterations_ < 0) {
      reference_iterations_ = iterations;
      reference_tolerance_ = tolerance;
    } else if (tolerance == reference_tolerance_ && iterations > 2 * reference_iterations_ + 10) {
      // Only against solves to the tolerance of the first one: the error controller's
      // check solves a hundred times tighter, and its tolerance moves. Once the controller
      // has moved it, this rule waits for the next build (a solve beyond the rescue
      // tolerance still marks the levels stale).
      stale_ = true;
    }
  }

  /// Builds `levels` below a system of `model`'s free nodes (their rest positions): its
  /// part without the nodal-pressure term `stiffness` and that term `pressure` (empty
  /// without one). The finest level aggregates over the stiffness alone (amg.h).
  static void build(amg::Hierarchy& levels, const Model& model, const amg::SpMat& stiffness, const amg::SpMat& pressure,
                    const amg::Options& options) {
    LevelsJob::build(levels, stiffness, pressure, rest_nodes(model), options);
  }

  /// The levels are built again before the next solve that uses them (the system changed:
  /// a job of the old one is not installed).
  void invalidate() {
    stale_ = true;
    job_.reset();
  }

  const amg::Hierarchy& levels() const { return levels_; }
  /// `counts` (a Backend::MultigridCounts) with the smoother of the levels in use filled in.
  template <class Counts>
  Counts with_smoother(Counts counts) const {
    const amg::Stats st = levels_.stats();
    counts.chebyshev = st.finest_chebyshev;
    counts.pressure_share = st.sparser_share;
    return counts;
  }

 private:
  static std::vector<Eigen::Vector3d> rest_nodes(const Model& model) {
    std::vector<Eigen::Vector3d> nodes(model.num_free());
    for (int i = 0; i < model.num_free(); ++i) nodes[i] = model.rest[model.free_nodes[i]];
    return nodes;
  }
  // New levels in use, built at stiffness weight `scale`: the rules start over from them.
  void adopt(double scale, long& builds) {
    failed_at_ = -1;
    scale_ = scale;
    off_steps_ = 0;
    stale_ = false;
    reference_iterations_ = -1;
    built_at_ = steps_;
    ++builds;
  }

  amg::Hierarchy levels_;
  double scale_ = 0;               // the weight of K (from dt) they were built with
  bool stale_ = false;
  int off_steps_ = 0;              // prepare()s in a row at a weight outside [1/2, 2] of scale_
  int reference_iterations_ = -1;  // iterations of the first solve after a build
  double reference_tolerance_ = 0;  // ... and its tolerance
  long steps_ = 0;                 // steps that asked for the multigrid
  long built_at_ = 0;              // ... at the last build
  long failed_at_ = -1;            // ... at the last failed build, or -1
  bool deferred_ = false;          // set_deferred()
  std::shared_ptr<LevelsJob> job_; // the deferred rebuild under way, or null
  bool job_taken_ = false;         // ... handed out by take_job()
};

/// A system stored by block rows of three scalar rows each (the CUDA assembly's layout,
/// sim/cuda/assembly.cuh: block row i's nine values per block, row by row across its
/// blocks, at 9 row_ptr[i]) as the scalar matrix the levels are built from.
amg::SpMat block_rows_to_sparse(int n, const std::vector<int>& row_ptr, const std::vector<int>& col,
                                const std::vector<double>& vals);

/// scale * B^T W B of the nodal-pressure term (nodal_pressure.h) over `nfree` free nodes,
/// its couplings b (3 per pair) and weights w (per node) given: what the levels add to the
/// stiffness.
amg::SpMat nodal_pressure_to_sparse(const NodalPressurePattern& pattern, int nfree, const std::vector<double>& b,
                                    const std::vector<double>& w, double scale);

}  // namespace palpation::sim
