#include "live/step_pacer.h"

#include <algorithm>
#include <cmath>

namespace palpation::app::live {

StepPacer::StepPacer(double dt, double max_dt)
    : dt_(dt), max_dt_(std::max(dt, max_dt)), dt_ns_(std::llround(dt * 1e9)), keep_ns_(std::llround(max_lag_s() * 1e9)) {}

double StepPacer::max_lag_s() const { return kLagAtDt * dt_ + (max_dt_ - dt_) / kLagShare + max_dt_; }

StepPacer::Slot StepPacer::next(std::int64_t now_ns) {
  Slot s;
  if (covered_ns_ == 0) {
    covered_ns_ = now_ns;
    lag_s_ = 0;
    s.h = dt_;
    return s;
  }
  if (now_ns < covered_ns_ + dt_ns_) {
    s.wait = true;
    s.until_ns = covered_ns_ + dt_ns_;
    return s;
  }
  // Owed up to kLagAtDt periods (a wake-up's slack, a converged check's overrun): dt, and
  // the next steps start that much sooner, on the same grid, until the lag is paid.
  const double lag = double(now_ns - covered_ns_) * 1e-9;
  s.h = std::min(max_dt_, dt_ + kLagShare * std::max(0.0, lag - kLagAtDt * dt_));
  covered_ns_ += std::llround(s.h * 1e9);
  if (now_ns - covered_ns_ > keep_ns_) covered_ns_ = now_ns - keep_ns_;
  lag_s_ = double(now_ns - covered_ns_) * 1e-9;
  return s;
}

}  // namespace palpation::app::live
