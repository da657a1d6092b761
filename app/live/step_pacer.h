// When the real-time simulation thread starts its next step, and what dt that step covers.
//
// The tissue keeps wall-clock time: steps start on a grid of dt (never faster than real
// time), and the simulation owes the wall time it has not yet simulated (its lag). A grid,
// not dt after the last start: a wake-up's lateness (tens of microseconds of timer slack)
// would otherwise add to every period (0.94 steps a millisecond measured at dt 1 ms). Covering
// all of an overrun in the next step, as a plain "dt = the time it took" does, has a second
// steady state where dt is large: a longer dt takes more CG iterations, so the step that
// covers a 2.5 ms overrun takes about 2.5 ms itself, and the loop never comes back to dt
// although a step of dt fits in dt (the coarse breast on the CPU of a 2-core machine:
// 0.95 ms steps at dt 1 ms, yet 417-497 steps a second at a 2.2-2.5 ms dt once a converged
// check had overrun). So the lag is paid back gradually: a step covers dt plus a share of
// the lag beyond ten periods (kLagAtDt), and steps follow one another at once until the
// lag is gone.
// Where a step of dt does not fit in dt the lag grows until the dt it buys makes the step
// fit (the steady state is a constant lag, not a drift); past max_dt the lag beyond what
// max_dt needs is dropped, as it cannot be paid back.
//
// A lag is a constant offset of the simulated clock from the wall clock, not a latency of
// what the hand feels: every step takes the newest device pose.
#pragma once

#include <cstdint>

namespace palpation::app::live {

class StepPacer {
 public:
  /// A step covers dt + kLagShare x (lag - kLagAtDt periods): a lag of up to kLagAtDt
  /// periods is paid back by steps of dt alone, since a dt that changes from step to step
  /// costs CG iterations itself (the warm start extrapolates the last step's).
  static constexpr double kLagShare = 0.25;
  static constexpr double kLagAtDt = 10;

  /// dt: the shortest step (s); max_dt: the longest (s, at least dt).
  StepPacer(double dt, double max_dt);

  /// What to do at `now_ns`: wait until `until_ns`, or step now over `h` seconds.
  struct Slot {
    bool wait = false;
    std::int64_t until_ns = 0;
    double h = 0;
  };
  Slot next(std::int64_t now_ns);
  /// The next step is a first step (a new simulation): it covers dt and starts the grid.
  void restart() { covered_ns_ = 0; }

  /// Wall time not yet simulated at the last step's start, after that step's h (s).
  double lag_s() const { return lag_s_; }
  /// The most lag kept (s): enough for max_dt, plus one longest step.
  double max_lag_s() const;

 private:
  double dt_, max_dt_;
  std::int64_t dt_ns_, keep_ns_;  // dt and max_lag_s() in ns
  std::int64_t covered_ns_ = 0;  // the wall-clock time simulated up to (0: before the first step)
  double lag_s_ = 0;
};

}  // namespace palpation::app::live
