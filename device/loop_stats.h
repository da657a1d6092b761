// Statistics of a periodic loop, kept without allocation: histograms of 1 us bins up to
// 20 ms (an overflow bin above) with exact maxima, so percentiles come out of the loop
// thread with no sorting and no memory traffic.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace palpation::device {

class MicrosecondHistogram {
 public:
  static constexpr int kBins = 20000;  // 0 .. 19999 us, then overflow
  void add(double us) {
    if (!(us >= 0)) us = 0;
    const int b = us >= kBins ? kBins : int(us);
    ++bins_[b];
    ++count_;
    max_ = std::max(max_, us);
  }
  std::uint64_t count() const { return count_; }
  double max() const { return max_; }
  /// The p-th percentile (0..100), bin centre (or the maximum for the overflow bin).
  double percentile(double p) const {
    if (count_ == 0) return 0;
    const auto rank = std::uint64_t(std::max(1.0, p / 100.0 * double(count_) + 0.5));
    std::uint64_t acc = 0;
    for (int b = 0; b <= kBins; ++b) {
      acc += bins_[b];
      if (acc >= rank) return b == kBins ? max_ : std::min(max_, b + 0.5);
    }
    return max_;
  }
  void clear() { *this = MicrosecondHistogram{}; }

 private:
  std::array<std::uint32_t, kBins + 1> bins_{};
  std::uint64_t count_ = 0;
  double max_ = 0;
};

struct LoopStats {
  std::uint64_t ticks = 0;
  std::int64_t first_ns = 0, last_ns = 0;
  MicrosecondHistogram period_us;    // time between successive ticks
  MicrosecondHistogram jitter_us;    // |period - nominal|
  MicrosecondHistogram latency_us;   // wake-up after the deadline
  MicrosecondHistogram compute_us;   // tick duration (when the caller reports it)
  std::uint64_t overruns = 0;        // ticks that ended after the next deadline
  std::uint64_t missed = 0;          // deadlines skipped because of overruns
  std::uint64_t model_updates = 0;   // new contact frames taken
  std::uint64_t device_updates = 0;  // new device states read
  std::uint64_t telemetry_dropped = 0;
  double max_model_step = 0;         // N, largest per-tick change of the pre-safety force
  /// Ticks per second over the loop's lifetime.
  double rate_hz() const {
    return ticks > 1 && last_ns > first_ns ? double(ticks - 1) / (double(last_ns - first_ns) * 1e-9) : 0.0;
  }
};

}  // namespace palpation::device
