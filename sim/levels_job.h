// A build of multigrid levels taken out of the step (Backend::set_deferred_levels): what
// the levels are built from, copied on the simulation's thread when the rebuild fell due,
// then built by run() on any other thread while the steps go on with the levels they had,
// and handed back to the backend between steps (Backend::install_levels). sim/ owns no
// thread: whoever takes a job runs it.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <span>
#include <vector>

#include "amg.h"

namespace palpation::sim {

/// Makes the system the levels are built from: the stiffness without the nodal-pressure
/// term and that term (left empty without one). It owns copies of what it reads, so that
/// it can run after the step, and the backend, are gone.
using LevelsSystem = std::function<void(amg::SpMat& stiffness, amg::SpMat& pressure)>;

class LevelsJob {
 public:
  /// The levels below the system `system` makes, over the free nodes at rest positions
  /// `nodes`, for a stiffness weight `scale` (multigrid_keeper.h).
  LevelsJob(LevelsSystem system, std::vector<Eigen::Vector3d> nodes, amg::Options options, double scale)
      : system_(std::move(system)), nodes_(std::move(nodes)), options_(options), scale_(scale) {}

  /// Makes the system and builds the levels (any thread, once). A throw is kept for the
  /// install, which counts it as a failed build.
  void run() {
    try {
      amg::SpMat stiffness, pressure;
      system_(stiffness, pressure);
      build(levels_, stiffness, pressure, nodes_, options_);
    } catch (...) {
      error_ = std::current_exception();
    }
    system_ = nullptr;  // its copies are no longer needed
    done_.store(true, std::memory_order_release);
  }
  /// run() has finished (its levels or its error are ready for the install).
  bool done() const { return done_.load(std::memory_order_acquire); }

  /// The levels below stiffness + pressure; the finest level aggregates over the stiffness
  /// alone (amg.h). The one build the keeper does in a step and a job does elsewhere.
  static void build(amg::Hierarchy& levels, const amg::SpMat& stiffness, const amg::SpMat& pressure,
                    std::span<const Eigen::Vector3d> nodes, const amg::Options& options) {
    if (pressure.nonZeros() > 0)
      levels.build(amg::SpMat(stiffness + pressure), nodes, options, &stiffness);
    else
      levels.build(stiffness, nodes, options);
  }

 private:
  friend class MultigridKeeper;
  LevelsSystem system_;
  std::vector<Eigen::Vector3d> nodes_;
  amg::Options options_;
  double scale_;
  amg::Hierarchy levels_;
  std::exception_ptr error_;
  std::atomic<bool> done_{false};
};

}  // namespace palpation::sim
