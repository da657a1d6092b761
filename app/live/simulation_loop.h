// The simulation thread's body (design.md section 3), one for every real-time driver
// (`palpation session` and the workstation):
//
//   newest device poses -> simulated fingertips (app/live/sim_fingers.h) -> the guarded step
//   (sim::Simulation::advance) -> local contact models published to the haptic loop
//
// paced to the wall clock, with the recovery after a backend fallback or a divergence
// reset (the last good contact models held while the restarted body settles, then
// blended into the new ones). Drivers add their own work through hooks: queued commands
// between steps, telemetry and render snapshots after each step.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "contact_model.h"
#include "haptic_loop.h"
#include "live/levels_builder.h"
#include "live/step_pacer.h"
#include "params.h"
#include "simulation.h"
#include "triple_buffer.h"

namespace palpation::app::live {

/// The solver threads of a simulation that runs beside a haptic thread: solver.threads = 0
/// (automatic) becomes 1 on a machine of 3 hardware threads or fewer, where the haptic
/// (and emulator) threads need a core of their own and OpenMP teams that must all be
/// scheduled at every barrier cost far more than they save (docs/benchmarks.md).
void configure_realtime_threads(sim::Simulation& s);

struct SimulationLoopOptions {
  /// Simulated finger k is device finger finger_map[k], of radius radius[k] (m).
  std::vector<int> finger_map;
  std::vector<double> radius;
  device::RigidFrame registration;     // device frame <-> world frame
  double dt = 0.001;                   // s, the shortest step
  /// true: the tissue keeps wall-clock time (live/step_pacer.h): steps start on a grid of
  /// `dt` (never faster than real time); after an overrun they follow at once and each
  /// covers dt plus a share of the time owed, at most max_dt (implicit Euler is stable at
  /// any dt; the cap bounds the latency one step adds). false: fixed dt, paced to real
  /// time when the FEM is faster.
  bool realtime = true;
  double max_dt = 0.01;                // s
  /// > 0: virtual coupling (the simulated fingertip is the proxy, device/contact_model.h
  /// couple()); 0: the simulated fingertip is the device's.
  double coupling_stiffness = 0;
  /// The two-step minimum on the force sent (app/live/sim_fingers.h, guard_force_spike).
  bool spike_guard = false;
  /// Device force per simulated force (app/live/force_mapping.h): the contact models are
  /// published scaled by it; LoopStep::out stays in simulated units.
  double force_scale = 1.0;
  /// After a fallback or reset: hold the last good models at least recover_hold_s and
  /// until the new forces have changed by less than 100 % + 0.5 N per second for 0.1 s of
  /// simulated time (at most recover_hold_max_s), then blend over recover_blend_s. All
  /// zero: the new (or empty) models at once.
  double recover_hold_s = 0, recover_hold_max_s = 0, recover_blend_s = 0;
  /// A multigrid rebuild that falls due while stepping (drift, dt, new materials) runs on a
  /// thread of its own (live/levels_builder.h) while the steps keep the levels they have;
  /// false: in the step that finds it due, as `palpation run` and bench do.
  bool deferred_levels = true;
};

/// One step as the hooks see it (simulation thread).
struct LoopStep {
  std::int64_t start_ns = 0;           // monotonic clock at the step's start
  std::int64_t published_ns = 0;       // when its contact models were published
  double h = 0;                        // s, this step's dt
  double sim_time = 0;                 // s, simulated time after it
  double step_ms = 0;                  // wall time of the guarded step
  std::uint64_t sequence = 0;          // contact frames published so far
  const sim::Simulation::Outcome* outcome = nullptr;
  std::span<const sim::FingerInput> in;   // per simulated finger, world frame
  std::span<const sim::FingerOutput> out; // zero after a reset
  const device::PoseFrame* poses = nullptr;
};

class SimulationLoop {
 public:
  struct Hooks {
    /// Before each attempt to step (queued commands); may call restart().
    std::function<void()> between_steps;
    /// After a fallback or a divergence reset, before the contact models are published.
    std::function<void(const sim::Simulation::Outcome&)> on_fault;
    /// After each step's contact models are published.
    std::function<void(const LoopStep&)> after_step;
  };

  SimulationLoop(device::TripleBuffer<device::PoseFrame>& poses, device::TripleBuffer<device::ContactFrame>& contacts,
                 SimulationLoopOptions opt);

  /// Steps `simulation` until `stop` is set. A backend error the CPU fallback cannot
  /// absorb propagates (the caller publishes empty models and says why).
  void run(sim::Simulation& simulation, const std::atomic<bool>& stop, const Hooks& hooks);
  /// From a hook: continue with another simulation (a new patient) and, when given, other
  /// fingertip radii (m). The dt restarts, the published models and the recovery are
  /// forgotten.
  void restart(sim::Simulation& simulation, const std::vector<double>& radius = {});
  /// From a hook (or before run): the force scale of the models published from the next
  /// step on (a new patient's). Not finite or not positive: 1.
  void set_force_scale(double s) { opt_.force_scale = std::isfinite(s) && s > 0 ? s : 1.0; }
  /// Publishes empty contact models (forces fade to zero in the haptic loop).
  void publish_empty();

  const SimulationLoopOptions& options() const { return opt_; }
  bool recovering() const { return recovering_.load(std::memory_order_acquire); }
  double sim_time() const { return sim_time_; }
  /// The real-time pacing's longest dt now and its sweeps (step_pacer.h); read when the
  /// loop is not running.
  double dt_limit_s() const { return pacer_.limit_s(); }
  int dt_sweeps() const { return pacer_.sweeps(); }
  std::int64_t first_step_ns() const { return first_step_ns_; }

 private:
  void publish(const sim::Simulation::Outcome& r, std::int64_t now, double h);

  device::TripleBuffer<device::PoseFrame>& poses_;
  device::TripleBuffer<device::ContactFrame>& contacts_;
  SimulationLoopOptions opt_;
  LevelsBuilder levels_;
  sim::Simulation* sim_ = nullptr;
  std::vector<sim::FingerInput> in_;
  std::vector<sim::FingerOutput> out_;
  std::array<device::FingerContactModel, device::kMaxFingers> last_{};  // newest published, device frame
  std::vector<Eigen::Vector3d> prev_force_;  // previous step's simulated force per finger (spike guard, settling)
  std::int64_t prev_start_ = 0, first_step_ns_ = 0, published_ns_ = 0;
  StepPacer pacer_;  // real time: when steps start and what dt they cover (run())
  std::uint64_t seq_ = 0;
  double sim_time_ = 0;
  // The recovery after a fallback or reset.
  std::atomic<bool> recovering_{false};
  std::int64_t recover_start_ = 0;
  std::int64_t blend_start_ = 0;  // 0: still holding
  double settled_for_ = 0;        // simulated seconds the new forces have been steady
  std::array<device::FingerContactModel, device::kMaxFingers> good_{}, held_{};
};

}  // namespace palpation::app::live
