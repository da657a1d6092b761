#include "rt_clock.h"

#include <cerrno>
#include <cstring>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

namespace palpation::device {

std::int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = time_t(deadline_ns / 1000000000LL);
  ts.tv_nsec = long(deadline_ns % 1000000000LL);
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

RealtimeResult try_realtime(int priority, bool lock_memory) {
  RealtimeResult r;
  sched_param sp{};
  sp.sched_priority = priority;
  const int rc = ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &sp);
  if (rc == 0) {
    r.granted = true;
    r.policy = "SCHED_FIFO " + std::to_string(priority);
    if (lock_memory && ::mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
      r.note = std::string("memory not locked (mlockall: ") + std::strerror(errno) + ")";
  } else {
    r.policy = "SCHED_OTHER";
    r.note = std::string("SCHED_FIFO refused (") + std::strerror(rc) +
             "): the loop runs at normal priority, so other load on this machine shows up as jitter; "
             "grant CAP_SYS_NICE or an rtprio limit (ulimit -r) to the user to get real-time priority";
  }
  return r;
}

}  // namespace palpation::device
