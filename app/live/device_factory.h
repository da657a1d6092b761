// The one place a haptic device is made, for the command line (`palpation session`) and
// the workstation: the simulated hand, a scripted or replayed hand, the HandHIRO emulator
// (in this process on a thread of the caller's, or as a child process) reached over the
// real UDP protocol on loopback, or the HandHIRO itself.
#pragma once

#include <memory>
#include <string>
#include <sys/types.h>
#include <vector>

#include "live/device_config.h"
#include "hand_script.h"
#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "haptic_device.h"
#include "scripted_device.h"
#include "simulated_hand.h"

namespace palpation::app::live {

/// A child process (posix_spawn), ended with SIGTERM (SIGKILL after 3 s) when destroyed.
class ChildProcess {
 public:
  ChildProcess() = default;
  ChildProcess(ChildProcess&& o) noexcept : pid_(o.pid_) { o.pid_ = -1; }
  ChildProcess& operator=(ChildProcess&& o) noexcept;
  ~ChildProcess() { end(); }
  /// Throws std::runtime_error naming args[0] when it cannot start.
  void spawn(const std::vector<std::string>& args);
  bool alive();
  void end();

 private:
  pid_t pid_ = -1;
};

struct DeviceRequest {
  /// "simulated" (SimulatedHand, looped script or mouse), "scripted" (the script exactly),
  /// "replay" (a recorded fingers.csv), "emulator" (the HandHIRO emulator driven by the
  /// script, over UDP loopback), "handhiro" (the robot at the configuration's address).
  std::string kind = "simulated";
  DeviceConfig config = default_device_config();
  device::HandScript script;           // the operator's hand (device frame)
  std::string recording;               // replay: fingers.csv (world frame)
  bool rigid_hand = false;             // emulator: fingertips follow the script exactly
  bool looped = false;                 // emulator: the script starts over at its end
  std::string robot_address;           // handhiro: empty for the configuration's
  int robot_port = 0;                  // handhiro: 0 for the configuration's
  /// emulator: non-empty runs `emulator_command[0] --port P emulator_command[1..]` as a
  /// child process instead of an in-process emulator.
  std::vector<std::string> emulator_command;
};

/// What a request opened. `device` is what the haptic loop talks to; the others are views
/// of it (or of the robot side) for counters and tests, null where they do not apply.
struct DeviceWiring {
  std::unique_ptr<device::HapticDevice> device;
  std::unique_ptr<device::HandHiroEmulator> emulator;  // emulator in-process: tick it at 1 kHz
  ChildProcess child;                                  // emulator as a child process
  device::HandHiroLink* link = nullptr;
  device::ScriptedDevice* scripted = nullptr;          // simulated, scripted, replay
  device::SimulatedHand* hand = nullptr;               // simulated
  std::string description;                             // in words, for the user
};

/// Opens the device. Throws sim::ScenarioError for bad input (an unknown kind, an
/// unreadable recording) and std::runtime_error when it cannot be opened (address in use).
DeviceWiring open_device(DeviceRequest r);

}  // namespace palpation::app::live
