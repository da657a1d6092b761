// The HandHIRO UDP protocol, version 1 (docs/handhiro-protocol.md is the contract).
//
// Two datagram types, both fixed size, little-endian, CRC-32 trailer:
//   state   (robot -> PC, 1 kHz): fingertip positions/velocities, attach status, joint
//           angles, the force the controller applied;
//   command (PC -> robot, 1 kHz): fingertip forces.
// Every packet carries the sender's session id (new per start), a sequence number, the
// sender's monotonic send time, and an echo of the newest packet it accepted from the
// peer (sequence, send time, and how long it held it) so either side measures the round
// trip. Receivers keep only the newest packet: late ones are dropped, duplicates ignored,
// gaps counted (SequenceTracker).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "haptic_device.h"

namespace palpation::device::protocol {

inline constexpr std::uint32_t kMagic = 0x4F524848u;  // bytes "HHRO"
inline constexpr std::uint16_t kVersion = 1;
inline constexpr int kArmJoints = 6;
inline constexpr int kFingerJoints = 3;
inline constexpr int kJoints = kArmJoints + kMaxFingers * kFingerJoints;  // 21

enum class PacketType : std::uint8_t { State = 1, Command = 2 };

inline constexpr std::size_t kHeaderSize = 40;
inline constexpr std::size_t kStateFingerSize = 64;
inline constexpr std::size_t kStateSize = kHeaderSize + 8 + kMaxFingers * kStateFingerSize + kJoints * 4 + 4;  // 456
inline constexpr std::size_t kCommandFingerSize = 32;
inline constexpr std::size_t kCommandSize = kHeaderSize + 8 + kMaxFingers * kCommandFingerSize + 4;        // 212
inline constexpr std::size_t kMaxPacketSize = kStateSize;

struct Header {
  PacketType type = PacketType::State;
  std::uint32_t session = 0;         // sender's id, new at every start
  std::uint32_t sequence = 0;        // +1 per packet sent in a session (wraps)
  std::int64_t send_time_ns = 0;     // sender's monotonic clock
  std::int64_t echo_time_ns = 0;     // send_time_ns of the newest packet accepted from the peer
  std::uint32_t echo_sequence = 0;   // its sequence (0 with echo_time_ns 0: none yet)
  std::uint32_t echo_hold_us = 0;    // time between accepting it and sending this one, us
};

// State status bits.
inline constexpr std::uint32_t kStatusWatchdog = 1u << 0;   // robot hears no commands: forces off
inline constexpr std::uint32_t kStatusEstop = 1u << 1;      // emergency stop pressed
// Per-finger flag bits (state).
inline constexpr std::uint8_t kFingerAttached = 1u << 0;
inline constexpr std::uint8_t kFingerPresent = 1u << 1;
inline constexpr std::uint8_t kFingerTorqueLimited = 1u << 2;
inline constexpr std::uint8_t kFingerJointLimit = 1u << 3;
// Command flag bits.
inline constexpr std::uint32_t kCommandEnable = 1u << 0;   // forces are live (else all zero)

struct StateFinger {
  Vec3 position;          // m, device frame (f64 on the wire)
  Vec3 velocity;          // m/s (f64)
  std::uint8_t flags = 0; // kFinger*
  Vec3 applied_force;     // N, what the controller rendered after its limits (f32)
};

struct StatePacket {
  Header header;
  std::uint32_t status = 0;                 // kStatus*
  std::uint8_t finger_count = kMaxFingers;
  std::array<StateFinger, kMaxFingers> fingers{};
  std::array<float, kJoints> joints{};      // rad: arm 0..5, then finger f joints 6+3f..8+3f
};

struct CommandFinger {
  Vec3 force;             // N, device frame, on the fingertip (f64)
  bool enabled = false;
};

struct CommandPacket {
  Header header;
  std::uint32_t flags = 0;                  // kCommand*
  std::uint8_t finger_count = kMaxFingers;
  std::array<CommandFinger, kMaxFingers> fingers{};
};

enum class DecodeStatus { Ok, TooShort, BadMagic, BadVersion, BadType, BadSize, BadChecksum, BadValue };
const char* to_string(DecodeStatus s);

/// Writes the packet into `out` (kStateSize / kCommandSize bytes). Returns bytes written
/// (0 when `capacity` is too small).
std::size_t encode(const StatePacket& p, std::uint8_t* out, std::size_t capacity);
std::size_t encode(const CommandPacket& p, std::uint8_t* out, std::size_t capacity);

/// The type of a datagram that passed magic, version, size and checksum checks.
DecodeStatus peek_type(const std::uint8_t* data, std::size_t size, PacketType& type);
/// Full decode with validation (magic, version, type, exact size, CRC, finite numbers,
/// finger_count <= 5). `out` is untouched unless Ok.
DecodeStatus decode(const std::uint8_t* data, std::size_t size, StatePacket& out);
DecodeStatus decode(const std::uint8_t* data, std::size_t size, CommandPacket& out);

/// Receiver-side ordering: accepts only packets newer than the newest accepted one of the
/// same sender session (serial-number arithmetic, so the 32-bit counter may wrap). A new
/// session id restarts the tracking (the peer restarted).
class SequenceTracker {
 public:
  enum class Verdict { Accept, Duplicate, Late };
  Verdict check(std::uint32_t session, std::uint32_t sequence);

  std::uint64_t accepted = 0;
  std::uint64_t lost = 0;        // sequence gaps (corrected when a late packet shows up)
  std::uint64_t duplicates = 0;
  std::uint64_t late = 0;        // reordered: older than the newest accepted
  std::uint64_t restarts = 0;    // session changes after the first
  bool has_peer() const { return started_; }
  std::uint32_t last_sequence() const { return last_; }

 private:
  bool started_ = false;
  std::uint32_t session_ = 0, last_ = 0;
  std::uint64_t window_ = 0;     // bit i: sequence last_ - i was received
};

}  // namespace palpation::device::protocol
