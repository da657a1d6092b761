#include "handhiro_protocol.h"

#include <bit>
#include <cmath>
#include <cstring>

#include "crc32.h"

namespace palpation::device::protocol {

namespace {

// Little-endian writer/reader over a fixed buffer (explicit bytes: portable to the
// robot's controller whatever its endianness).
struct Writer {
  std::uint8_t* p;
  void u8(std::uint8_t v) { *p++ = v; }
  void u16(std::uint16_t v) { for (int i = 0; i < 2; ++i) *p++ = std::uint8_t(v >> (8 * i)); }
  void u32(std::uint32_t v) { for (int i = 0; i < 4; ++i) *p++ = std::uint8_t(v >> (8 * i)); }
  void u64(std::uint64_t v) { for (int i = 0; i < 8; ++i) *p++ = std::uint8_t(v >> (8 * i)); }
  void i64(std::int64_t v) { u64(std::uint64_t(v)); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void vec64(const Vec3& v) { f64(v.x); f64(v.y); f64(v.z); }
  void vec32(const Vec3& v) { f32(float(v.x)); f32(float(v.y)); f32(float(v.z)); }
  void zeros(int n) { for (int i = 0; i < n; ++i) *p++ = 0; }
};

struct Reader {
  const std::uint8_t* p;
  std::uint8_t u8() { return *p++; }
  std::uint16_t u16() { std::uint16_t v = 0; for (int i = 0; i < 2; ++i) v |= std::uint16_t(std::uint16_t(*p++) << (8 * i)); return v; }
  std::uint32_t u32() { std::uint32_t v = 0; for (int i = 0; i < 4; ++i) v |= std::uint32_t(*p++) << (8 * i); return v; }
  std::uint64_t u64() { std::uint64_t v = 0; for (int i = 0; i < 8; ++i) v |= std::uint64_t(*p++) << (8 * i); return v; }
  std::int64_t i64() { return std::int64_t(u64()); }
  float f32() { return std::bit_cast<float>(u32()); }
  double f64() { return std::bit_cast<double>(u64()); }
  Vec3 vec64() { Vec3 v; v.x = f64(); v.y = f64(); v.z = f64(); return v; }
  Vec3 vec32() { Vec3 v; v.x = f32(); v.y = f32(); v.z = f32(); return v; }
  void skip(int n) { p += n; }
};

void write_header(Writer& w, const Header& h, PacketType type) {
  w.u32(kMagic);
  w.u16(kVersion);
  w.u8(std::uint8_t(type));
  w.u8(0);
  w.u32(h.session);
  w.u32(h.sequence);
  w.i64(h.send_time_ns);
  w.i64(h.echo_time_ns);
  w.u32(h.echo_sequence);
  w.u32(h.echo_hold_us);
}

Header read_header(Reader& r) {
  Header h;
  r.skip(6);  // magic, version (checked by validate)
  h.type = PacketType(r.u8());
  r.skip(1);
  h.session = r.u32();
  h.sequence = r.u32();
  h.send_time_ns = r.i64();
  h.echo_time_ns = r.i64();
  h.echo_sequence = r.u32();
  h.echo_hold_us = r.u32();
  return h;
}

void seal(std::uint8_t* begin, std::size_t size) {
  Writer w{begin + size - 4};
  w.u32(crc32(begin, size - 4));
}

DecodeStatus validate(const std::uint8_t* data, std::size_t size, PacketType& type) {
  if (size < kHeaderSize + 4) return DecodeStatus::TooShort;
  Reader r{data};
  if (r.u32() != kMagic) return DecodeStatus::BadMagic;
  if (r.u16() != kVersion) return DecodeStatus::BadVersion;
  const std::uint8_t t = r.u8();
  std::size_t expect = 0;
  if (t == std::uint8_t(PacketType::State)) expect = kStateSize;
  else if (t == std::uint8_t(PacketType::Command)) expect = kCommandSize;
  else return DecodeStatus::BadType;
  if (size != expect) return DecodeStatus::BadSize;
  Reader c{data + size - 4};
  if (c.u32() != crc32(data, size - 4)) return DecodeStatus::BadChecksum;
  type = PacketType(t);
  return DecodeStatus::Ok;
}

}  // namespace

const char* to_string(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::Ok: return "ok";
    case DecodeStatus::TooShort: return "too short";
    case DecodeStatus::BadMagic: return "bad magic";
    case DecodeStatus::BadVersion: return "unsupported version";
    case DecodeStatus::BadType: return "unknown type";
    case DecodeStatus::BadSize: return "wrong size for its type";
    case DecodeStatus::BadChecksum: return "checksum mismatch";
    case DecodeStatus::BadValue: return "non-finite or out-of-range value";
  }
  return "?";
}

std::size_t encode(const StatePacket& p, std::uint8_t* out, std::size_t capacity) {
  if (capacity < kStateSize) return 0;
  Writer w{out};
  write_header(w, p.header, PacketType::State);
  w.u32(p.status);
  w.u8(p.finger_count);
  w.zeros(3);
  for (const auto& f : p.fingers) {
    w.vec64(f.position);
    w.vec64(f.velocity);
    w.u8(f.flags);
    w.zeros(3);
    w.vec32(f.applied_force);
  }
  for (float q : p.joints) w.f32(q);
  seal(out, kStateSize);
  return kStateSize;
}

std::size_t encode(const CommandPacket& p, std::uint8_t* out, std::size_t capacity) {
  if (capacity < kCommandSize) return 0;
  Writer w{out};
  write_header(w, p.header, PacketType::Command);
  w.u32(p.flags);
  w.u8(p.finger_count);
  w.zeros(3);
  for (const auto& f : p.fingers) {
    w.vec64(f.force);
    w.u8(f.enabled ? 1 : 0);
    w.zeros(7);
  }
  seal(out, kCommandSize);
  return kCommandSize;
}

DecodeStatus peek_type(const std::uint8_t* data, std::size_t size, PacketType& type) {
  return validate(data, size, type);
}

DecodeStatus decode(const std::uint8_t* data, std::size_t size, StatePacket& out) {
  PacketType type{};
  const DecodeStatus s = validate(data, size, type);
  if (s != DecodeStatus::Ok) return s;
  if (type != PacketType::State) return DecodeStatus::BadType;
  Reader r{data};
  StatePacket p;
  p.header = read_header(r);
  p.status = r.u32();
  p.finger_count = r.u8();
  r.skip(3);
  if (p.finger_count > kMaxFingers) return DecodeStatus::BadValue;
  for (auto& f : p.fingers) {
    f.position = r.vec64();
    f.velocity = r.vec64();
    f.flags = r.u8();
    r.skip(3);
    f.applied_force = r.vec32();
    if (!finite(f.position) || !finite(f.velocity) || !finite(f.applied_force)) return DecodeStatus::BadValue;
  }
  for (float& q : p.joints) {
    q = r.f32();
    if (!std::isfinite(q)) return DecodeStatus::BadValue;
  }
  out = p;
  return DecodeStatus::Ok;
}

DecodeStatus decode(const std::uint8_t* data, std::size_t size, CommandPacket& out) {
  PacketType type{};
  const DecodeStatus s = validate(data, size, type);
  if (s != DecodeStatus::Ok) return s;
  if (type != PacketType::Command) return DecodeStatus::BadType;
  Reader r{data};
  CommandPacket p;
  p.header = read_header(r);
  p.flags = r.u32();
  p.finger_count = r.u8();
  r.skip(3);
  if (p.finger_count > kMaxFingers) return DecodeStatus::BadValue;
  for (auto& f : p.fingers) {
    f.force = r.vec64();
    f.enabled = r.u8() != 0;
    r.skip(7);
    // A non-finite force is refused whole: the robot must never see one.
    if (!finite(f.force)) return DecodeStatus::BadValue;
  }
  out = p;
  return DecodeStatus::Ok;
}

SequenceTracker::Verdict SequenceTracker::check(std::uint32_t session, std::uint32_t sequence) {
  if (!started_ || session != session_) {
    if (started_) ++restarts;
    started_ = true;
    session_ = session;
    last_ = sequence;
    window_ = 1;
    ++accepted;
    return Verdict::Accept;
  }
  const auto delta = std::int32_t(sequence - last_);
  if (delta > 0) {
    lost += std::uint64_t(delta - 1);
    window_ = delta >= 64 ? 1 : (window_ << delta) | 1;
    last_ = sequence;
    ++accepted;
    return Verdict::Accept;
  }
  const auto back = std::uint32_t(-std::int64_t(delta));
  if (back < 64) {
    const std::uint64_t bit = std::uint64_t(1) << back;
    if (window_ & bit) {
      ++duplicates;
      return Verdict::Duplicate;
    }
    window_ |= bit;
    if (lost > 0) --lost;  // counted as lost when the gap appeared; it was only late
  }
  ++late;
  return Verdict::Late;
}

}  // namespace palpation::device::protocol
