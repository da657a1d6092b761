#include "error_control.h"

#include <algorithm>
#include <cmath>

namespace palpation::sim {

std::optional<double> finger_force_error(std::span<const FingerOutput> loose, std::span<const FingerOutput> reference) {
  double diff = 0, scale = 0;
  bool contact = false;
  const std::size_t n = std::min(loose.size(), reference.size());
  for (std::size_t f = 0; f < n; ++f) {
    contact = contact || loose[f].contacts > 0 || reference[f].contacts > 0;
    const double d = (loose[f].force_raw - reference[f].force_raw).norm(), r = reference[f].force_raw.norm();
    if (!std::isfinite(d) || !std::isfinite(r)) return double(INFINITY);
    diff = std::max(diff, d);
    scale = std::max(scale, r);
  }
  if (!contact) return std::nullopt;
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
  ceiling_ = 2 * kMaxTolerance;
}

void ToleranceController::checked(double error) {
  since_check_ = 0;
  ++stats_.checks;
  stats_.last_error = error;
  stats_.worst_error = std::max(stats_.worst_error, error);
  const double aim = kCheckShare * stats_.target;
  if (!(error <= aim)) {  // NaN too
    ++stats_.over_target;
    // Not loosened to where this failed again until a long calm (below).
    ceiling_ = std::min(ceiling_, stats_.tolerance);
    const double f = std::isfinite(error) && error > 0 ? std::max(1.0 / 20, 0.5 * aim / error) : 1.0 / 20;
    stats_.tolerance = std::max(min_tol_, stats_.tolerance * f);
    interval_ = kMinInterval;
    return;
  }
  const double highest = std::min(kMaxTolerance, 0.5 * ceiling_);
  if (error < 0.25 * aim && stats_.tolerance < highest) {
    // Still finding the level: the next check as soon as this one.
    stats_.tolerance = std::max(stats_.tolerance, std::min(highest, 2 * stats_.tolerance));
    return;
  }
  // Held: checks twice as far apart; after a whole longest interval held, the tolerance
  // that once failed may be tried again (the contact that needed it may be gone).
  if (interval_ == kMaxInterval) ceiling_ = std::min(2 * ceiling_, 2 * kMaxTolerance);
  interval_ = std::min(kMaxInterval, 2 * interval_);
}

}  // namespace palpation::sim
