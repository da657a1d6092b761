#include "live/haptic_thread.h"

namespace palpation::app::live {

void PeriodicThread::start(std::int64_t period_ns, int priority, Tick tick, Overrun overrun, Done done) {
  stop();
  stop_.store(false);
  started_.store(false);
  thread_ = std::thread([this, period_ns, priority, tick = std::move(tick), overrun = std::move(overrun),
                         done = std::move(done)]() {
    if (priority > 0) rt_ = device::try_realtime(priority);
    else rt_ = {false, "SCHED_OTHER", "normal priority requested"};
    started_.store(true, std::memory_order_release);
    std::int64_t deadline = device::monotonic_ns() + period_ns;
    while (!stop_.load(std::memory_order_acquire)) {
      device::sleep_until_ns(deadline);
      const std::int64_t now = device::monotonic_ns();
      tick(now, deadline);
      const std::int64_t end = device::monotonic_ns();
      std::int64_t next = deadline + period_ns;
      if (end > next) {
        const auto missed = std::uint64_t((end - next) / period_ns + 1);
        next += std::int64_t(missed) * period_ns;
        overruns_.fetch_add(1, std::memory_order_relaxed);
        if (overrun) overrun(missed);
      }
      deadline = next;
    }
    if (done) done(device::monotonic_ns());
  });
}

void PeriodicThread::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true, std::memory_order_release);
  thread_.join();
}

device::RealtimeResult PeriodicThread::realtime() const {
  if (!started_.load(std::memory_order_acquire)) return {};
  return rt_;
}

void HapticThread::start(int priority) {
  const auto period_ns = std::int64_t(loop_.params().period * 1e9 + 0.5);
  thread_.start(
      period_ns, priority,
      [this](std::int64_t now, std::int64_t deadline) {
        loop_.tick(now, deadline);
        loop_.note_compute(double(device::monotonic_ns() - now) * 1e-3);
      },
      [this](std::uint64_t missed) { loop_.note_overrun(missed); },
      [this](std::int64_t now) { loop_.stop(now); });
}

}  // namespace palpation::app::live
