#include "handhiro_emulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace palpation::device {

HandHiroEmulator::HandHiroEmulator(const HandHiroParams& params, HandScript script, const EmulatorOptions& options)
    : p_(params),
      o_(options),
      robot_(params, std::move(script), options.rigid_hand),
      period_(options.looped ? robot_.script().duration() : 0.0) {}

bool HandHiroEmulator::open(std::string* error) {
  session_ = o_.session;
  if (session_ == 0)
    session_ = std::uint32_t(std::chrono::steady_clock::now().time_since_epoch().count() * 2654435761u) | 1u;
  return socket_.open(o_.bind_address, o_.port, error);
}

void HandHiroEmulator::tick(std::int64_t now_ns) {
  ++c_.ticks;
  const double dt = c_.ticks == 1 ? 0.001 : std::clamp(double(now_ns - last_tick_ns_) * 1e-9, 1e-5, 0.02);
  last_tick_ns_ = now_ns;

  // 1. Commands: keep the newest valid one.
  for (;;) {
    Endpoint from;
    bool truncated = false;
    const long n = socket_.receive(buf_.data(), buf_.size(), &from, &truncated);
    if (n < 0) break;
    protocol::CommandPacket pkt;
    const auto st = truncated ? protocol::DecodeStatus::BadSize : protocol::decode(buf_.data(), std::size_t(n), pkt);
    if (st == protocol::DecodeStatus::BadValue) {
      ++c_.refused_nonfinite;
      continue;
    }
    if (st != protocol::DecodeStatus::Ok) {
      ++c_.corrupt;
      continue;
    }
    const auto verdict = tracker_.check(pkt.header.session, pkt.header.sequence);
    if (verdict != protocol::SequenceTracker::Verdict::Accept) continue;
    cmd_ = pkt;
    peer_ = from;
    have_cmd_ = true;
    last_cmd_ns_ = now_ns;
    for (const auto& f : pkt.fingers) {
      if (!f.enabled) continue;
      const double m = norm(f.force);
      c_.max_force_received = std::max(c_.max_force_received, m);
      if (m > p_.capabilities.max_force * (1 + 1e-9)) ++c_.over_limit;
    }
  }
  c_.commands = tracker_.accepted;
  c_.lost = tracker_.lost;
  c_.duplicates = tracker_.duplicates;
  c_.late = tracker_.late;

  // 2. Watchdog: forces ramp to zero without fresh commands.
  const bool fresh = have_cmd_ && double(now_ns - last_cmd_ns_) * 1e-9 <= p_.robot_watchdog;
  if (!fresh && !watchdog_) ++c_.watchdog_events;
  watchdog_ = !fresh;
  const bool live = fresh && (cmd_.flags & protocol::kCommandEnable);
  const double ramp = p_.robot_ramp > 0 ? dt / p_.robot_ramp : 1.0;
  gain_ = live ? std::min(1.0, gain_ + ramp) : std::max(0.0, gain_ - ramp);

  // 3. The operator's script starts with the first command.
  if (!started_ && have_cmd_) {
    started_ = true;
    t0_ns_ = now_ns;
  }
  t_ = started_ ? double(now_ns - t0_ns_) * 1e-9 : 0.0;
  if (period_ > 0) t_ = std::fmod(t_, period_);

  // 4. The controller's own force limit, then the robot.
  std::array<Vec3, kMaxFingers> force{};
  for (int f = 0; f < kMaxFingers && f < cmd_.finger_count; ++f) {
    if (!cmd_.fingers[f].enabled) continue;
    Vec3 F = cmd_.fingers[f].force;
    const double m = norm(F);
    if (!(m <= p_.capabilities.max_force)) F = finite(F) ? F * (p_.capabilities.max_force / m) : Vec3{};
    force[f] = F * gain_;
  }
  robot_.step(t_, dt, force);

  // 5. State to the PC.
  if (!peer_.valid()) return;
  state_.header.session = session_;
  state_.header.sequence = ++seq_;
  state_.header.send_time_ns = now_ns;
  state_.header.echo_sequence = cmd_.header.sequence;
  state_.header.echo_time_ns = have_cmd_ ? cmd_.header.send_time_ns : 0;
  state_.header.echo_hold_us = have_cmd_ ? std::uint32_t(std::clamp<std::int64_t>((now_ns - last_cmd_ns_) / 1000, 0, 0xFFFFFFFFll)) : 0;
  state_.status = watchdog_ ? protocol::kStatusWatchdog : 0u;
  robot_.fill(state_);
  const std::size_t n = protocol::encode(state_, buf_.data(), buf_.size());
  if (socket_.send_to(peer_, buf_.data(), n)) ++c_.states_sent;
  else ++c_.send_errors;
}

}  // namespace palpation::device
