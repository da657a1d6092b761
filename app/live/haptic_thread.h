// The threads that run 1 kHz loops (design.md section 3: threads live in app/). A
// PeriodicThread calls its tick at absolute deadlines (clock_nanosleep TIMER_ABSTIME),
// at real-time priority where the system allows it (SCHED_FIFO; otherwise a note says
// why and the loop runs at normal priority). A tick that ends after the next deadline is
// an overrun: the missed deadlines are skipped, never caught up in a burst.
//
// HapticThread runs a device::HapticLoop this way; the emulator thread runs the robot
// side the same way.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "haptic_loop.h"
#include "rt_clock.h"

namespace palpation::app::live {

class PeriodicThread {
 public:
  /// tick(now_ns, deadline_ns) returns the compute time it wants recorded (or nothing).
  using Tick = std::function<void(std::int64_t now_ns, std::int64_t deadline_ns)>;
  using Overrun = std::function<void(std::uint64_t missed)>;
  using Done = std::function<void(std::int64_t now_ns)>;

  PeriodicThread() = default;
  ~PeriodicThread() { stop(); }
  PeriodicThread(const PeriodicThread&) = delete;
  PeriodicThread& operator=(const PeriodicThread&) = delete;

  /// Starts the thread. priority 0: normal scheduling; 1..99: try SCHED_FIFO.
  void start(std::int64_t period_ns, int priority, Tick tick, Overrun overrun = {}, Done done = {});
  /// Stops after the current tick, runs `done` on the thread, joins.
  void stop();
  bool running() const { return thread_.joinable(); }
  /// Valid once the thread has started its first tick.
  device::RealtimeResult realtime() const;
  bool started() const { return started_.load(std::memory_order_acquire); }
  std::uint64_t overruns() const { return overruns_.load(std::memory_order_relaxed); }

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false}, started_{false};
  std::atomic<std::uint64_t> overruns_{0};
  device::RealtimeResult rt_;
};

/// The haptic thread: a HapticLoop ticked at its period, highest priority.
class HapticThread {
 public:
  explicit HapticThread(device::HapticLoop& loop) : loop_(loop) {}
  void start(int priority = 80);
  void stop() { thread_.stop(); }
  device::RealtimeResult realtime() const { return thread_.realtime(); }
  bool started() const { return thread_.started(); }

 private:
  device::HapticLoop& loop_;
  PeriodicThread thread_;
};

}  // namespace palpation::app::live
