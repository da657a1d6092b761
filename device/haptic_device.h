// The haptic device interface (iMSTK's idea: a device is a mailbox). The haptic thread
// reads the newest fingertip state and writes the newest forces; neither call blocks,
// allocates or locks, so an implementation may be a UDP link, a script or a recording.
//
// Frames and units: the device frame (see resources/handhiro.json, "registration"),
// metres, seconds, newtons. Forces are the force exerted ON the user's fingertip.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "vec3.h"

namespace palpation::device {

inline constexpr int kMaxFingers = 5;  // HandHIRO: thumb, index, middle, ring, little

/// Device finger numbering (HandHIRO order).
enum FingerId : int { kThumb = 0, kIndex = 1, kMiddle = 2, kRing = 3, kLittle = 4 };

/// What a device can do. The safety filter clamps to these.
struct DeviceCapabilities {
  int finger_count = kMaxFingers;
  double max_force = 4.0;        // N per fingertip, continuous (?) see handhiro.json
  double max_stiffness = 3000;   // N/m renderable at 1 kHz without instability (?)
  double max_damping = 10.0;     // N s/m the passivity controller may add (?)
  double release_force = 6.0;    // N, magnet-joint pull-off (?)
  Vec3 workspace_min{0.20, -0.30, -0.10};  // fingertip workspace box, device frame, m
  Vec3 workspace_max{0.80, 0.30, 0.50};
  double rate_hz = 1000;         // nominal state/command rate
};

/// One fingertip as the device reports it.
struct FingerState {
  Vec3 position;                 // fingertip (magnet joint centre), device frame, m
  Vec3 velocity;                 // m/s
  bool attached = false;         // magnet joint closed: the user's finger is on it
  bool present = false;          // the device has this finger and reports it
  bool torque_limited = false;   // the controller scaled the last force (J^T f limits)
};

/// The newest state of the whole device.
struct DeviceState {
  std::array<FingerState, kMaxFingers> fingers{};
  std::int64_t device_time_ns = 0;    // the device's own clock when it sampled this state
  std::int64_t received_ns = 0;       // host monotonic clock when it arrived
  std::uint32_t sequence = 0;         // device's packet/sample counter
  bool connected = false;             // a state arrived within the link timeout
  bool device_watchdog = false;       // the device reports it stopped hearing commands
};

/// Forces to render, one per finger (device frame, N, on the fingertip).
struct ForceCommand {
  std::array<Vec3, kMaxFingers> force{};
  std::array<bool, kMaxFingers> enabled{};  // false: the finger renders nothing
};

/// Link health, for statistics (zero for in-process devices).
struct LinkCounters {
  std::uint64_t received = 0;      // valid packets accepted
  std::uint64_t sent = 0;
  std::uint64_t lost = 0;          // gaps in the sequence
  std::uint64_t duplicates = 0;
  std::uint64_t reordered = 0;     // arrived after a newer one: dropped
  std::uint64_t corrupt = 0;       // bad CRC, size, magic, version or type
  std::uint64_t send_errors = 0;
  std::uint64_t link_losses = 0;   // connected -> disconnected transitions
  std::int64_t last_rtt_ns = 0;    // round trip from the echoed time stamps
};

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  virtual DeviceCapabilities capabilities() const = 0;
  virtual std::string name() const = 0;
  /// Non-blocking. Updates `state` to the newest sample (now_ns: host monotonic clock).
  /// Returns true when a new sample arrived since the previous call.
  virtual bool read(std::int64_t now_ns, DeviceState& state) = 0;
  /// Non-blocking. Sends the forces. Callers pass only filtered forces (safety_filter.h).
  virtual void write(std::int64_t now_ns, const ForceCommand& command) = 0;
  virtual LinkCounters counters() const { return {}; }
};

}  // namespace palpation::device
