// The PC side of the HandHIRO link (docs/handhiro-protocol.md): a HapticDevice that talks
// UDP to the robot's real-time controller (or to handhiro-emulator). read() drains the
// socket and keeps the newest valid state (late, duplicate and corrupt packets dropped
// and counted); write() sends one command packet. The link is "connected" while a valid
// state arrived within `timeout`; the haptic loop's safety filter ramps forces to zero
// when it is not. Never blocks, never allocates after open().
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "haptic_device.h"
#include "handhiro_protocol.h"
#include "loop_stats.h"
#include "udp_socket.h"

namespace palpation::device {

struct LinkConfig {
  std::string robot_address = "127.0.0.1";
  std::uint16_t robot_port = 47001;
  std::string bind_address = "127.0.0.1";   // the PC's own address (0.0.0.0: any)
  std::uint16_t bind_port = 0;              // 0: any free port
  double timeout = 0.05;                    // s without a valid state: disconnected
  std::uint32_t session = 0;                // 0: derived from the clock at open()
};

class HandHiroLink : public HapticDevice {
 public:
  HandHiroLink(const DeviceCapabilities& caps, const LinkConfig& config);
  bool open(std::string* error = nullptr);
  std::uint16_t local_port() const { return socket_.local_port(); }
  /// Blocks up to timeout_ms until a datagram is waiting (tests, idle waits; never in a tick).
  bool wait_readable(int timeout_ms) { return socket_.wait_readable(timeout_ms); }

  DeviceCapabilities capabilities() const override { return caps_; }
  std::string name() const override { return "handhiro"; }
  bool read(std::int64_t now_ns, DeviceState& state) override;
  void write(std::int64_t now_ns, const ForceCommand& command) override;
  LinkCounters counters() const override { return c_; }

  const protocol::StatePacket& last_state() const { return latest_; }
  std::uint64_t peer_restarts() const { return tracker_.restarts; }
  /// Round trips measured from the echoed time stamps (read it when the loop stopped).
  const MicrosecondHistogram& rtt_us() const { return rtt_; }

 private:
  DeviceCapabilities caps_;
  LinkConfig cfg_;
  Endpoint robot_;
  UdpSocket socket_;
  protocol::SequenceTracker tracker_;
  protocol::StatePacket latest_;
  std::array<std::uint8_t, 2048> buf_{};
  LinkCounters c_;
  MicrosecondHistogram rtt_;
  bool have_state_ = false, connected_ = false;
  std::int64_t last_rx_ns_ = 0;
  std::uint32_t session_ = 0, seq_ = 0;
};

}  // namespace palpation::device
