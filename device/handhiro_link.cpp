#include "handhiro_link.h"

#include <algorithm>
#include <chrono>

namespace palpation::device {

HandHiroLink::HandHiroLink(const DeviceCapabilities& caps, const LinkConfig& config) : caps_(caps), cfg_(config) {}

bool HandHiroLink::open(std::string* error) {
  std::uint32_t addr = 0;
  if (!parse_ipv4(cfg_.robot_address, addr)) {
    if (error) *error = "robot address \"" + cfg_.robot_address + "\" is not an IPv4 address";
    return false;
  }
  robot_ = {addr, cfg_.robot_port};
  session_ = cfg_.session;
  if (session_ == 0)
    session_ = std::uint32_t(std::chrono::steady_clock::now().time_since_epoch().count() * 2246822519u) | 1u;
  return socket_.open(cfg_.bind_address, cfg_.bind_port, error);
}

bool HandHiroLink::read(std::int64_t now_ns, DeviceState& state) {
  bool fresh = false;
  for (;;) {
    Endpoint from;
    bool truncated = false;
    const long n = socket_.receive(buf_.data(), buf_.size(), &from, &truncated);
    if (n < 0) break;
    protocol::StatePacket pkt;
    const auto st = truncated ? protocol::DecodeStatus::BadSize : protocol::decode(buf_.data(), std::size_t(n), pkt);
    if (st != protocol::DecodeStatus::Ok) {
      ++c_.corrupt;
      continue;
    }
    if (tracker_.check(pkt.header.session, pkt.header.sequence) != protocol::SequenceTracker::Verdict::Accept) continue;
    latest_ = pkt;
    have_state_ = true;
    fresh = true;
    last_rx_ns_ = now_ns;
    if (pkt.header.echo_time_ns != 0 && pkt.header.echo_sequence != 0) {
      // RTT = now - our send time of the echoed command - the robot's holding time.
      c_.last_rtt_ns = now_ns - pkt.header.echo_time_ns - std::int64_t(pkt.header.echo_hold_us) * 1000;
      rtt_.add(double(c_.last_rtt_ns) * 1e-3);
    }
  }
  c_.received = tracker_.accepted;
  c_.lost = tracker_.lost;
  c_.duplicates = tracker_.duplicates;
  c_.reordered = tracker_.late;

  const bool connected = have_state_ && double(now_ns - last_rx_ns_) * 1e-9 <= cfg_.timeout;
  if (connected_ && !connected) ++c_.link_losses;
  connected_ = connected;
  state.connected = connected;
  if (fresh) {
    state.device_time_ns = latest_.header.send_time_ns;
    state.received_ns = last_rx_ns_;
    state.sequence = latest_.header.sequence;
    state.device_watchdog = (latest_.status & protocol::kStatusWatchdog) != 0;
    for (int f = 0; f < kMaxFingers; ++f) {
      const auto& w = latest_.fingers[f];
      FingerState& fs = state.fingers[f];
      fs.present = f < latest_.finger_count && (w.flags & protocol::kFingerPresent);
      fs.attached = fs.present && (w.flags & protocol::kFingerAttached);
      fs.torque_limited = (w.flags & protocol::kFingerTorqueLimited) != 0;
      fs.position = w.position;
      fs.velocity = w.velocity;
    }
  }
  return fresh;
}

void HandHiroLink::write(std::int64_t now_ns, const ForceCommand& command) {
  protocol::CommandPacket p;
  p.header.session = session_;
  p.header.sequence = ++seq_;
  if (seq_ == 0) p.header.sequence = seq_ = 1;  // 0 means "none" in echoes
  p.header.send_time_ns = now_ns;
  if (have_state_) {
    p.header.echo_sequence = latest_.header.sequence;
    p.header.echo_time_ns = latest_.header.send_time_ns;
    p.header.echo_hold_us = std::uint32_t(std::clamp<std::int64_t>((now_ns - last_rx_ns_) / 1000, 0, 0xFFFFFFFFll));
  }
  p.flags = protocol::kCommandEnable;
  p.finger_count = std::uint8_t(std::min(caps_.finger_count, kMaxFingers));
  for (int f = 0; f < kMaxFingers; ++f) {
    // The filter upstream guarantees finite forces; this is the last line: never put a
    // non-finite number on the wire.
    const bool ok = finite(command.force[f]);
    p.fingers[f].force = ok ? command.force[f] : Vec3{};
    p.fingers[f].enabled = command.enabled[f] && ok;
  }
  const std::size_t n = protocol::encode(p, buf_.data(), buf_.size());
  if (socket_.send_to(robot_, buf_.data(), n)) ++c_.sent;
  else ++c_.send_errors;
}

}  // namespace palpation::device
