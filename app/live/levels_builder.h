// Runs a simulation's deferred multigrid builds (sim/levels_job.h) on a thread of its own,
// one at a time, so that a rebuild (about a second on the paper mesh, ten on xfine) never
// stalls the simulation thread: the steps go on with the levels they have until the new
// ones are installed between two steps.
#pragma once

#include <memory>
#include <thread>
#include <vector>

#include "backend.h"

namespace palpation::app::live {

class LevelsBuilder {
 public:
  LevelsBuilder() = default;
  LevelsBuilder(const LevelsBuilder&) = delete;
  LevelsBuilder& operator=(const LevelsBuilder&) = delete;
  /// Waits for the builds under way (their levels are dropped).
  ~LevelsBuilder();

  /// Simulation thread, between steps: installs the job that finished into `backend`,
  /// then starts the next one it hands out. True when levels were installed.
  bool poll(sim::Backend& backend);
  /// Another simulation from now on: the job under way finishes on its thread and is
  /// dropped, never installed.
  void forget();
  /// Jobs started so far.
  long started() const { return started_; }

 private:
  struct Run {
    std::shared_ptr<sim::LevelsJob> job;
    std::thread thread;
  };
  void join_finished();

  Run current_;
  std::vector<Run> forgotten_;  // still running when forget() was called
  long started_ = 0;
};

}  // namespace palpation::app::live
