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
//
// Where no dt fits (the lag runs past what the longest dt needs: the tissue falls behind
// the wall clock whatever dt is), a longer dt buys some simulated time at the price of
// fewer updates of what the hand feels, and on the GPU's largest meshes little of it: a
// longer step takes more CG iterations (the xfine breast in double on an H200, 12 s
// sessions: 68 steps a second at 10 ms keeping 0.63 of the wall clock's pace, 185 at
// 2.96 ms keeping 0.54; docs/gpu-notes.md). So while saturated the pacer measures each
// shorter dt of a ladder (max_dt / 1.5^k down to dt) against max_dt, in blocks of steps
// taken in turn at one and the other (a step's cost moves with the contact and with the
// converged checks beside the steps, so the two are measured over the same seconds), and
// goes down the ladder while a dt's simulated seconds a wall second (sum h / sum of the
// steps' wall time) stay within kRateShare of max_dt's: at most a fifth of the pace given
// for the updates. The sweep is taken again after kHoldSteps saturated steps (the contact,
// and with it the step's cost, changes), and stops, keeping what it chose so far, when a
// step fits again.
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

  /// Where no dt fits: the shortest limit whose simulated rate is within this share of
  /// max_dt's, each measured in kPairs blocks of kBlock steps in turn with max_dt's (after
  /// kSettle steps at the block's dt, whose warm start pays for the change); taken again
  /// after kHoldSteps saturated steps.
  static constexpr double kRateShare = 0.8;
  static constexpr double kLadder = 1.5;
  static constexpr int kBlock = 10, kPairs = 4, kSettle = 2, kHoldSteps = 3000;

  /// dt: the shortest step (s); max_dt: the longest (s, at least dt).
  StepPacer(double dt, double max_dt);

  /// What to do at `now_ns`: wait until `until_ns`, or step now over `h` seconds.
  struct Slot {
    bool wait = false;
    std::int64_t until_ns = 0;
    double h = 0;
  };
  Slot next(std::int64_t now_ns);
  /// The next step is a first step (a new simulation): it covers dt and starts the grid,
  /// and the limit goes back to max_dt.
  void restart();

  /// Wall time not yet simulated at the last step's start, after that step's h (s).
  double lag_s() const { return lag_s_; }
  /// The most lag kept (s): enough for max_dt, plus one longest step.
  double max_lag_s() const;
  /// The longest dt a step may cover now (s): max_dt, or the sweep's choice (above).
  double limit_s() const { return limit(chosen_); }
  /// Sweeps taken (each: max_dt, then shorter dt while they keep the rate).
  int sweeps() const { return sweeps_; }

 private:
  double limit(int level) const;
  // The step that started at the last next(): its wall time is known at the next call.
  void observe(double h, double wall_s, bool saturated);
  void compare(int level);  // starts measuring this ladder level against max_dt

  double dt_, max_dt_;
  std::int64_t dt_ns_, keep_ns_;  // dt and max_lag_s() in ns
  std::int64_t covered_ns_ = 0;  // the wall-clock time simulated up to (0: before the first step)
  double lag_s_ = 0;
  // The limit where no dt fits: ladder levels (0: max_dt), the one in use and the sweep.
  int levels_ = 1;          // max_dt / kLadder^k down to dt: the last one is dt
  int chosen_ = 0;
  bool sweeping_ = false;
  int level_ = 0;           // the level compared with max_dt (sweeping_)
  bool at_max_ = true;      // this block's steps are max_dt's
  int block_n_ = 0, pairs_ = 0;
  double h_[2] = {}, wall_[2] = {};  // simulated and wall time measured: [0] max_dt, [1] the level
  int hold_ = kHoldSteps;   // saturated steps since the last sweep: the first saturation sweeps
  int sweeps_ = 0;
  std::int64_t step_start_ns_ = 0;  // 0: no step in flight
  double step_h_ = 0;
  bool step_saturated_ = false;
};

}  // namespace palpation::app::live
