// Monotonic time and absolute-deadline sleeping for the 1 kHz loops (POSIX), and the
// attempt to run the calling thread with real-time priority.
#pragma once

#include <cstdint>
#include <string>

namespace palpation::device {

/// CLOCK_MONOTONIC in nanoseconds.
std::int64_t monotonic_ns();
/// Sleeps until the absolute CLOCK_MONOTONIC time (clock_nanosleep, TIMER_ABSTIME);
/// returns at once when it has passed. Restarts after signals.
void sleep_until_ns(std::int64_t deadline_ns);

struct RealtimeResult {
  bool granted = false;
  std::string policy;   // "SCHED_FIFO 80" or "SCHED_OTHER"
  std::string note;     // why not, and what that means
};
/// Tries SCHED_FIFO at `priority` (1..99) for the calling thread and locks memory
/// (mlockall) where allowed. Falls back to the normal scheduler with a note.
RealtimeResult try_realtime(int priority, bool lock_memory = false);

}  // namespace palpation::device
