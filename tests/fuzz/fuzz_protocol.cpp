// libFuzzer target: the HandHIRO packet decoder (device/handhiro_protocol.cpp), the one
// parser that reads bytes from the network. Any datagram decodes to Ok (then every
// number is finite, finger_count <= 5, and encode -> decode gives the same bytes) or to
// an error status; it never crashes or reads out of bounds.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include <vector>

#include "crc32.h"
#include "handhiro_protocol.h"

namespace pr = palpation::device::protocol;

namespace {
bool all_finite(const palpation::device::Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* in, std::size_t size) {
  // Datagrams end in a CRC-32 of everything before it: put the right one there (a peer
  // can send any bytes with a valid CRC), so the fuzzer explores the field checks behind
  // it. Inputs whose first byte is 0x5A keep theirs (the CRC test itself).
  std::vector<std::uint8_t> bytes(in, in + size);
  if (size >= 8 && in[0] != 0x5A) {
    const std::uint32_t c = palpation::device::crc32(bytes.data(), size - 4);
    for (int k = 0; k < 4; ++k) bytes[size - 4 + k] = std::uint8_t(c >> (8 * k));
  }
  const std::uint8_t* data = bytes.data();
  pr::PacketType type{};
  (void)pr::peek_type(data, size, type);
  std::uint8_t buf[pr::kMaxPacketSize];
  pr::StatePacket s;
  if (pr::decode(data, size, s) == pr::DecodeStatus::Ok) {
    if (s.finger_count > palpation::device::kMaxFingers) std::abort();
    for (const auto& f : s.fingers)
      if (!all_finite(f.position) || !all_finite(f.velocity) || !all_finite(f.applied_force)) std::abort();
    const std::size_t n = pr::encode(s, buf, sizeof buf);
    pr::StatePacket again;
    if (n != pr::kStateSize || pr::decode(buf, n, again) != pr::DecodeStatus::Ok) std::abort();
  }
  pr::CommandPacket c;
  if (pr::decode(data, size, c) == pr::DecodeStatus::Ok) {
    if (c.finger_count > palpation::device::kMaxFingers) std::abort();
    for (const auto& f : c.fingers)
      if (!all_finite(f.force)) std::abort();
    const std::size_t n = pr::encode(c, buf, sizeof buf);
    pr::CommandPacket again;
    if (n != pr::kCommandSize || pr::decode(buf, n, again) != pr::DecodeStatus::Ok) std::abort();
  }
  // The sequence tracker sees whatever the header says.
  if (size >= 16) {
    static pr::SequenceTracker tr;
    std::uint32_t a, b;
    std::memcpy(&a, data + 8, 4);
    std::memcpy(&b, data + 12, 4);
    (void)tr.check(a, b);
  }
  return 0;
}
