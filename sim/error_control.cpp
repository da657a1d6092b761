#include "error_control.h"

#include <algorithm>
#include <cmath>

namespace palpation::sim {

double finger_force_error(std::span<const FingerOutput> loose, std::span<const FingerOutput> reference) {
  double diff = 0, scale = 0;
  bool contact = false;
  const std::size_t n = std::min(loose.size(), reference.size());
  for (std::size_t f = 0; f < n; ++f) {
    contact = contact || loose[f].contacts > 0 || reference[f].contacts > 0;
    const double d = (loose[f].force_raw - reference[f].force_raw).norm(), r = reference[f].force_raw.norm();
    if (!std::isfinite(d) || !std::isfinite(r)) return INFINITY;
    diff = std::max(diff, d);
    scale = std::max(scale, r);
  }
  if (!contact) return 0;
  return diff / std::max(scale, kForceErrorFloor);
}

void ToleranceController::start(double target, double tolerance, Precision precision) {
  stats_ = ErrorControlStats{};
  stats_.target = std::isfinite(target) && target > 0 ? target : 0;
  // The reference solve is a hundred times tighter: float's reaches 1e-5 at best.
  min_tol_ = precision == Precision::Float ? 1e-3 : 1e-7;
  stats_.tolerance = std::clamp(std::isfinite(tolerance) ? tolerance : 1e-3, min_tol_, kMaxTolerance);
  interval_ = kMinInterval;
  since_check_ = kMinInterval;
}

void ToleranceController::checked(double error) {
  since_check_ = 0;
  ++stats_.checks;
  stats_.last_error = error;
  stats_.worst_error = std::max(stats_.worst_error, error);
  const double aim = kCheckShare * stats_.target;
  if (!(error <= 2 * aim)) {  // NaN too
    ++stats_.over_target;
    const double f = std::isfinite(error) && error > 0 ? std::max(1.0 / 20, aim / error) : 1.0 / 20;
    stats_.tolerance = std::max(min_tol_, stats_.tolerance * f);
    interval_ = kMinInterval;
    return;
  }
  if (error < 0.5 * aim && stats_.tolerance < kMaxTolerance) {
    // Still finding the level: the next check as soon as this one.
    const double f = error > 0 ? std::min(4.0, aim / error) : 4.0;
    stats_.tolerance = std::min(kMaxTolerance, stats_.tolerance * f);
    return;
  }
  interval_ = std::min(kMaxInterval, 2 * interval_);
}

}  // namespace palpation::sim
