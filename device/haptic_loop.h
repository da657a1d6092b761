// The 1 kHz haptic loop's logic (design.md section 3): one tick is
//   read the fingertips -> take the newest contact model -> evaluate it at the current
//   positions through the virtual coupling (contact_model.h: couple()) -> blend a new
//   model in -> publish the fingertips and proxies (for the simulation) -> safety filter
//   -> send -> record.
// It never waits for the simulation, never allocates, locks, logs or touches Qt. The
// thread that calls tick() at 1 kHz lives in app/ (app/live/haptic_thread.h); tests call it
// directly with a fake clock.
//
// Force continuity: when a new contact model arrives, the difference between the force
// being rendered and the new model's force at the same position is faded out linearly
// over L ticks, L = the recent update interval in ticks (1..blend_max_ticks). So the
// per-tick change of the force caused by a model update is at most |dF| / L, and the
// rendered force is the piecewise-linear interpolation of successive simulation results
// (one update of latency) plus the local stiffness term for motion in between.
#pragma once

#include <array>
#include <cstdint>

#include "contact_model.h"
#include "haptic_device.h"
#include "loop_stats.h"
#include "safety_filter.h"
#include "spsc_ring.h"
#include "triple_buffer.h"

namespace palpation::device {

/// Fingertip poses as the haptic loop publishes them for the simulation thread.
struct PoseFrame {
  std::array<FingerState, kMaxFingers> fingers{};
  std::array<Vec3, kMaxFingers> proxy{};  // where the simulated fingertips go (= position when direct)
  std::int64_t time_ns = 0;     // host monotonic clock of the tick
  std::uint64_t tick = 0;
  bool connected = false;
};

/// One tick as recorded (telemetry ring -> recorder / fingers.csv). Device frame.
struct TickRecord {
  std::int64_t time_ns = 0;
  std::array<Vec3, kMaxFingers> position{};
  std::array<Vec3, kMaxFingers> force{};     // sent to the device
  std::uint8_t attached = 0;                 // bit f
  float gain = 0;                            // global safety gain
};

struct HapticLoopParams {
  double period = 0.001;        // s, nominal tick period
  int blend_max_ticks = 20;     // longest fade of a model update
  double max_stiffness = 3000;  // N/m clamp of the local model (device capability)
  bool virtual_coupling = true; // false: render F0 + K (x - x0) at the device position ("direct")
  double coupling_stiffness = 0;  // N/m, k_c of the virtual coupling; 0: max_stiffness
  SafetyParams safety;
};

class HapticLoop {
 public:
  /// `telemetry` may be null. The device's capabilities cap max_force / max_stiffness /
  /// max_damping.
  HapticLoop(HapticDevice& device, TripleBuffer<PoseFrame>& poses, TripleBuffer<ContactFrame>& contacts,
             SpscRing<TickRecord>* telemetry, const HapticLoopParams& params);

  /// One servo cycle at host time now_ns; deadline_ns is when it was due (statistics).
  void tick(std::int64_t now_ns, std::int64_t deadline_ns);
  /// Reported by the runner after a tick: its duration and whether it overran.
  void note_compute(double us) { stats_.compute_us.add(us); }
  void note_overrun(std::uint64_t missed_deadlines) {
    ++stats_.overruns;
    stats_.missed += missed_deadlines;
  }
  /// Sends zero forces (all fingers disabled): call once after the last tick.
  void stop(std::int64_t now_ns);

  const LoopStats& stats() const { return stats_; }
  const SafetyFilter& safety() const { return safety_; }
  const HapticLoopParams& params() const { return p_; }
  const DeviceState& state() const { return state_; }
  /// Pre-safety force of the last tick (for tests).
  const std::array<Vec3, kMaxFingers>& desired() const { return desired_; }
  const ForceCommand& command() const { return command_; }
  /// Proxy (simulated fingertip) positions of the last tick.
  const std::array<Vec3, kMaxFingers>& proxy() const { return proxy_; }

 private:
  HapticDevice& device_;
  TripleBuffer<PoseFrame>& poses_;
  TripleBuffer<ContactFrame>& contacts_;
  SpscRing<TickRecord>* telemetry_;
  Coupled render(const FingerContactModel& m, const Vec3& x) const;
  HapticLoopParams p_;
  SafetyFilter safety_;
  LoopStats stats_;
  DeviceState state_;
  ForceCommand command_;
  std::array<Vec3, kMaxFingers> desired_{}, offset_{}, proxy_{};
  int blend_left_ = 0, blend_len_ = 1;
  double update_interval_ticks_ = 1.0;
  std::uint64_t last_update_tick_ = 0;
  std::int64_t prev_ns_ = 0;
};

}  // namespace palpation::device
