#include "live/step_pacer.h"

#include <algorithm>
#include <cmath>

namespace palpation::app::live {

StepPacer::StepPacer(double dt, double max_dt)
    : dt_(dt), max_dt_(std::max(dt, max_dt)), dt_ns_(std::llround(dt * 1e9)), keep_ns_(std::llround(max_lag_s() * 1e9)) {
  while (limit(levels_ - 1) > dt_) ++levels_;
}

double StepPacer::max_lag_s() const { return kLagAtDt * dt_ + (max_dt_ - dt_) / kLagShare + max_dt_; }

double StepPacer::limit(int level) const { return std::max(dt_, max_dt_ / std::pow(kLadder, level)); }

void StepPacer::restart() {
  covered_ns_ = 0;
  chosen_ = 0;
  sweeping_ = false;
  hold_ = kHoldSteps;
  step_start_ns_ = 0;
}

void StepPacer::compare(int level) {
  level_ = level;
  at_max_ = true;
  block_n_ = pairs_ = 0;
  h_[0] = h_[1] = wall_[0] = wall_[1] = 0;
}

void StepPacer::observe(double h, double wall_s, bool saturated) {
  if (!saturated) {
    sweeping_ = false;  // a step fits: nothing to weigh; what the sweep chose so far stays
    return;
  }
  if (!sweeping_) {
    if (++hold_ < kHoldSteps || levels_ < 2) return;
    hold_ = 0;
    sweeping_ = true;
    ++sweeps_;
    chosen_ = 0;
    compare(1);
    return;
  }
  if (++block_n_ > kSettle) {
    h_[at_max_ ? 0 : 1] += h;
    wall_[at_max_ ? 0 : 1] += wall_s;
  }
  if (block_n_ < kSettle + kBlock) return;
  block_n_ = 0;
  if (!at_max_) ++pairs_;
  at_max_ = !at_max_;
  if (pairs_ < kPairs) return;
  const double rate_max = h_[0] / wall_[0], rate = h_[1] / wall_[1];
  if (!(rate >= kRateShare * rate_max)) {
    sweeping_ = false;
    return;
  }
  chosen_ = level_;
  if (level_ + 1 < levels_)
    compare(level_ + 1);
  else
    sweeping_ = false;
}

StepPacer::Slot StepPacer::next(std::int64_t now_ns) {
  if (step_start_ns_ != 0) {
    observe(step_h_, double(now_ns - step_start_ns_) * 1e-9, step_saturated_);
    step_start_ns_ = 0;
  }
  Slot s;
  auto start = [&](double h, bool saturated) {
    s.h = step_h_ = h;
    step_start_ns_ = now_ns;
    step_saturated_ = saturated;
    return s;
  };
  if (covered_ns_ == 0) {
    covered_ns_ = now_ns;
    lag_s_ = 0;
    return start(dt_, false);
  }
  if (now_ns < covered_ns_ + dt_ns_) {
    s.wait = true;
    s.until_ns = covered_ns_ + dt_ns_;
    return s;
  }
  // Owed up to kLagAtDt periods (a wake-up's slack, a converged check's overrun): dt, and
  // the next steps start that much sooner, on the same grid, until the lag is paid.
  const double lag = double(now_ns - covered_ns_) * 1e-9;
  const double wanted = dt_ + kLagShare * std::max(0.0, lag - kLagAtDt * dt_);
  const double cap = limit(sweeping_ ? (at_max_ ? 0 : level_) : chosen_);
  const double h = std::min(cap, wanted);
  covered_ns_ += std::llround(h * 1e9);
  if (now_ns - covered_ns_ > keep_ns_) covered_ns_ = now_ns - keep_ns_;
  lag_s_ = double(now_ns - covered_ns_) * 1e-9;
  return start(h, wanted > cap);
}

}  // namespace palpation::app::live
