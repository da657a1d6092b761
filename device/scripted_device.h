// In-process devices for tests and hardware-free sessions (iMSTK's dummy clients):
//   ScriptedDevice: fingertips follow a HandScript exactly (a rigid, perfect device);
//   ReplayDevice:   a ScriptedDevice playing a recorded session (fingers.csv).
// Both record what they were sent, so tests can check that a device never received a
// NaN, an Inf or a force above its limit.
#pragma once

#include <cstdint>
#include <string>

#include "hand_script.h"
#include "haptic_device.h"

namespace palpation::device {

struct ReceivedForces {
  std::uint64_t writes = 0;
  std::uint64_t nonfinite = 0;      // commands holding NaN/Inf (must stay 0)
  std::uint64_t over_limit = 0;     // finger forces above max_force (must stay 0)
  double max_force = 0;             // N, largest finite force received
  ForceCommand last;
};

class ScriptedDevice : public HapticDevice {
 public:
  ScriptedDevice(HandScript script, DeviceCapabilities caps = {});
  DeviceCapabilities capabilities() const override { return caps_; }
  std::string name() const override { return "scripted"; }
  /// The script's clock starts at the first read().
  bool read(std::int64_t now_ns, DeviceState& state) override;
  void write(std::int64_t now_ns, const ForceCommand& command) override;

  // Test hooks (call from the same thread as the loop, or before it starts).
  void set_attached(int finger, bool attached) { detached_[finger] = !attached; }
  void set_connected(bool c) { connected_ = c; }
  /// Overrides a finger's position (NaN injection tests); cleared by passing finite=false.
  void override_position(int finger, const Vec3& p, bool on) {
    override_[finger] = on;
    override_pos_[finger] = p;
  }
  /// Looped: the script starts over at its end (a hand palpating on its own).
  void set_looped(bool on) { looped_ = on; }
  const ReceivedForces& received() const { return rx_; }
  const HandScript& script() const { return script_; }
  double script_time(std::int64_t now_ns) const { return started_ ? double(now_ns - t0_) * 1e-9 : 0.0; }

 protected:
  /// Fills the state's clock, sequence and link fields of a read at now_ns; returns
  /// whether the device is connected.
  bool stamp(std::int64_t now_ns, DeviceState& state);
  /// The script's clock starts again at the next read() (from the reading thread).
  void restart_clock() { started_ = false; }

 private:
  HandScript script_;
  DeviceCapabilities caps_;
  ReceivedForces rx_;
  bool started_ = false, connected_ = true, looped_ = false;
  std::int64_t t0_ = 0;
  std::uint32_t seq_ = 0;
  std::array<bool, kMaxFingers> detached_{}, override_{};
  std::array<Vec3, kMaxFingers> override_pos_{};
};

class ReplayDevice : public ScriptedDevice {
 public:
  /// Plays `fingers_csv` (world frame); recorded finger k drives device finger map[k];
  /// positions go through registration.to_device. Throws std::runtime_error.
  ReplayDevice(const std::string& fingers_csv, const RigidFrame& registration, const std::array<int, kMaxFingers>& map,
               DeviceCapabilities caps = {});
  std::string name() const override { return "replay"; }
};

}  // namespace palpation::device
