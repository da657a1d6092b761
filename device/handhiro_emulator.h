// handhiro-emulator's core: the robot's real-time controller side of the UDP protocol
// (docs/handhiro-protocol.md) around an emulated robot (handhiro_robot.h). Call tick()
// at 1 kHz: it drains the commands, runs the controller's watchdog (no valid command for
// robot_watchdog seconds -> forces ramp to zero over robot_ramp and the state says so),
// clamps forces to the robot's own limit, steps the robot and sends the state to the PC
// (the sender of the newest valid command). The operator's script starts at the first
// valid command and, with `looped`, starts over at its end (an operator who palpates
// until stopped). No allocation after open().
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "handhiro_protocol.h"
#include "handhiro_robot.h"
#include "udp_socket.h"

namespace palpation::device {

struct EmulatorOptions {
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 0;      // 0: any free port (see port())
  bool rigid_hand = false;
  std::uint32_t session = 0;   // 0: derived from the clock at open()
  bool looped = false;         // the script starts over at its end
};

struct EmulatorCounters {
  std::uint64_t ticks = 0;
  std::uint64_t commands = 0;        // accepted
  std::uint64_t lost = 0, duplicates = 0, late = 0, corrupt = 0;
  std::uint64_t refused_nonfinite = 0;  // command packets with NaN/Inf (refused whole)
  std::uint64_t over_limit = 0;      // accepted finger forces above max_force (clamped)
  double max_force_received = 0;     // N
  std::uint64_t watchdog_events = 0; // commands fresh -> stale transitions
  std::uint64_t states_sent = 0, send_errors = 0;
};

class HandHiroEmulator {
 public:
  HandHiroEmulator(const HandHiroParams& params, HandScript script, const EmulatorOptions& options);
  bool open(std::string* error = nullptr);
  std::uint16_t port() const { return socket_.local_port(); }
  /// Blocks up to timeout_ms until a datagram is waiting (tests, idle waits; never in a tick).
  bool wait_readable(int timeout_ms) { return socket_.wait_readable(timeout_ms); }
  void tick(std::int64_t now_ns);

  const EmulatorCounters& counters() const { return c_; }
  const HandHiroRobot& robot() const { return robot_; }
  HandHiroRobot& robot() { return robot_; }
  bool watchdog() const { return watchdog_; }
  double gain() const { return gain_; }
  bool started() const { return started_; }
  double script_time() const { return t_; }
  const protocol::CommandPacket& last_command() const { return cmd_; }

 private:
  HandHiroParams p_;
  EmulatorOptions o_;
  HandHiroRobot robot_;
  UdpSocket socket_;
  protocol::SequenceTracker tracker_;
  protocol::CommandPacket cmd_;
  protocol::StatePacket state_;
  std::array<std::uint8_t, 2048> buf_{};
  Endpoint peer_;
  EmulatorCounters c_;
  bool have_cmd_ = false, watchdog_ = true, started_ = false;
  std::int64_t last_cmd_ns_ = 0, last_tick_ns_ = 0, t0_ns_ = 0;
  double gain_ = 0, t_ = 0;
  double period_ = 0;  // the script's duration where it loops (EmulatorOptions::looped), else 0
  std::uint32_t session_ = 0, seq_ = 0;
};

}  // namespace palpation::device
