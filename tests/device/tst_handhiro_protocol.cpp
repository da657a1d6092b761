// The HandHIRO UDP protocol (device/handhiro_protocol.h, docs/handhiro-protocol.md):
// encode/decode round trips, the CRC-32, rejection of every kind of damaged datagram,
// and the receiver's ordering rules (loss, reordering, duplicates, wrap-around, peer
// restart).
#include <QtTest>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "crc32.h"
#include "handhiro_protocol.h"

using namespace palpation::device;
using namespace palpation::device::protocol;

namespace {

StatePacket sample_state(std::uint32_t seq) {
  StatePacket p;
  p.header.session = 0xA5A5F00Du;
  p.header.sequence = seq;
  p.header.send_time_ns = 123456789012345LL + seq;
  p.header.echo_time_ns = -42;  // any 64-bit value survives
  p.header.echo_sequence = seq - 3;
  p.header.echo_hold_us = 250;
  p.status = kStatusWatchdog;
  p.finger_count = 5;
  for (int f = 0; f < kMaxFingers; ++f) {
    auto& w = p.fingers[f];
    w.position = {0.4 + 0.01 * f, -0.02 * f, 0.1 + 1e-9 * f};
    w.velocity = {1e-3 * f, -2e-3, 3.5e-2};
    w.flags = std::uint8_t(kFingerPresent | (f % 2 ? kFingerAttached : 0) | (f == 3 ? kFingerTorqueLimited : 0));
    w.applied_force = {0.5f * float(f), -0.25f, 1.0f};  // f32 on the wire: exact in binary
  }
  for (int j = 0; j < kJoints; ++j) p.joints[j] = 0.01f * float(j) - 0.1f;
  return p;
}

CommandPacket sample_command(std::uint32_t seq) {
  CommandPacket p;
  p.header.session = 77;
  p.header.sequence = seq;
  p.header.send_time_ns = 987654321;
  p.flags = kCommandEnable;
  for (int f = 0; f < kMaxFingers; ++f) {
    p.fingers[f].force = {0.1 * f, -0.3, 2.0 + 1e-12 * f};
    p.fingers[f].enabled = f != 2;
  }
  return p;
}

}  // namespace

class TestHandHiroProtocol : public QObject {
  Q_OBJECT
 private slots:
  void crcKnownValue() {
    const char* s = "123456789";
    QCOMPARE(crc32(reinterpret_cast<const std::uint8_t*>(s), 9), 0xCBF43926u);
    QCOMPARE(crc32(nullptr, 0), 0u);
  }

  void sizesAreFixed() {
    QCOMPARE(kStateSize, std::size_t(456));
    QCOMPARE(kCommandSize, std::size_t(212));
    std::uint8_t buf[kMaxPacketSize];
    QCOMPARE(encode(sample_state(1), buf, sizeof buf), kStateSize);
    QCOMPARE(encode(sample_command(1), buf, sizeof buf), kCommandSize);
    QCOMPARE(encode(sample_state(1), buf, kStateSize - 1), std::size_t(0));  // too small: nothing written
  }

  void stateRoundTrip() {
    const StatePacket in = sample_state(1001);
    std::uint8_t buf[kMaxPacketSize];
    const std::size_t n = encode(in, buf, sizeof buf);
    // Little-endian magic "HHRO" at the start, whatever the host.
    QCOMPARE(std::memcmp(buf, "HHRO", 4), 0);
    StatePacket out;
    QCOMPARE(decode(buf, n, out), DecodeStatus::Ok);
    QCOMPARE(out.header.session, in.header.session);
    QCOMPARE(out.header.sequence, in.header.sequence);
    QCOMPARE(out.header.send_time_ns, in.header.send_time_ns);
    QCOMPARE(out.header.echo_time_ns, in.header.echo_time_ns);
    QCOMPARE(out.header.echo_sequence, in.header.echo_sequence);
    QCOMPARE(out.header.echo_hold_us, in.header.echo_hold_us);
    QCOMPARE(out.status, in.status);
    QCOMPARE(int(out.finger_count), 5);
    for (int f = 0; f < kMaxFingers; ++f) {
      QVERIFY(out.fingers[f].position == in.fingers[f].position);  // f64: exact
      QVERIFY(out.fingers[f].velocity == in.fingers[f].velocity);
      QCOMPARE(out.fingers[f].flags, in.fingers[f].flags);
      QVERIFY(out.fingers[f].applied_force == in.fingers[f].applied_force);
    }
    for (int j = 0; j < kJoints; ++j) QCOMPARE(out.joints[j], in.joints[j]);
    PacketType t{};
    QCOMPARE(peek_type(buf, n, t), DecodeStatus::Ok);
    QVERIFY(t == PacketType::State);
  }

  void commandRoundTrip() {
    const CommandPacket in = sample_command(0xFFFFFFFFu);
    std::uint8_t buf[kMaxPacketSize];
    const std::size_t n = encode(in, buf, sizeof buf);
    CommandPacket out;
    QCOMPARE(decode(buf, n, out), DecodeStatus::Ok);
    QCOMPARE(out.header.sequence, 0xFFFFFFFFu);
    QCOMPARE(out.flags, kCommandEnable);
    for (int f = 0; f < kMaxFingers; ++f) {
      QVERIFY(out.fingers[f].force == in.fingers[f].force);
      QCOMPARE(out.fingers[f].enabled, in.fingers[f].enabled);
    }
    // A command is not a state and vice versa.
    StatePacket st;
    QCOMPARE(decode(buf, n, st), DecodeStatus::BadType);
  }

  // Every single-bit error anywhere in a datagram is caught (CRC-32 detects all of them).
  void everyBitFlipIsRejected() {
    std::uint8_t buf[kMaxPacketSize];
    const std::size_t n = encode(sample_state(5), buf, sizeof buf);
    int accepted = 0;
    for (std::size_t byte = 0; byte < n; ++byte)
      for (int bit = 0; bit < 8; ++bit) {
        buf[byte] ^= std::uint8_t(1u << bit);
        StatePacket out;
        if (decode(buf, n, out) == DecodeStatus::Ok) ++accepted;
        buf[byte] ^= std::uint8_t(1u << bit);
      }
    QCOMPARE(accepted, 0);
  }

  void damagedDatagramsAreRejected() {
    std::uint8_t buf[kMaxPacketSize + 16];
    const std::size_t n = encode(sample_command(9), buf, sizeof buf);
    CommandPacket out;
    QCOMPARE(decode(buf, 0, out), DecodeStatus::TooShort);
    QCOMPARE(decode(buf, 20, out), DecodeStatus::TooShort);
    QCOMPARE(decode(buf, n - 1, out), DecodeStatus::BadSize);  // truncated
    QCOMPARE(decode(buf, n + 4, out), DecodeStatus::BadSize);  // trailing bytes
    std::uint8_t copy[kMaxPacketSize];
    std::memcpy(copy, buf, n);
    copy[0] = 'X';
    QCOMPARE(decode(copy, n, out), DecodeStatus::BadMagic);
    std::memcpy(copy, buf, n);
    copy[4] = 2;  // version 2
    QCOMPARE(decode(copy, n, out), DecodeStatus::BadVersion);
    std::memcpy(copy, buf, n);
    copy[6] = 9;  // unknown type
    QCOMPARE(decode(copy, n, out), DecodeStatus::BadType);
  }

  // A sender that puts NaN/Inf on the wire (with a valid checksum) is refused whole: the
  // robot never sees a non-finite force.
  void nonFiniteValuesAreRefused() {
    std::uint8_t buf[kMaxPacketSize];
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()}) {
      CommandPacket c = sample_command(3);
      c.fingers[4].force.y = bad;
      const std::size_t n = encode(c, buf, sizeof buf);
      CommandPacket out;
      out.flags = 12345;
      QCOMPARE(decode(buf, n, out), DecodeStatus::BadValue);
      QCOMPARE(out.flags, 12345u);  // untouched
      StatePacket s = sample_state(3);
      s.fingers[0].position.z = bad;
      const std::size_t m = encode(s, buf, sizeof buf);
      StatePacket so;
      QCOMPARE(decode(buf, m, so), DecodeStatus::BadValue);
    }
    CommandPacket c = sample_command(3);
    c.finger_count = 6;
    const std::size_t n = encode(c, buf, sizeof buf);
    CommandPacket out;
    QCOMPARE(decode(buf, n, out), DecodeStatus::BadValue);
  }

  // Random garbage of every length never decodes and never crashes.
  void garbageNeverDecodes() {
    std::mt19937 rng(1234);
    std::vector<std::uint8_t> buf(600);
    int accepted = 0;
    for (int i = 0; i < 20000; ++i) {
      const std::size_t n = rng() % buf.size();
      for (std::size_t k = 0; k < n; ++k) buf[k] = std::uint8_t(rng());
      if (i % 3 == 0 && n >= 8) std::memcpy(buf.data(), "HHRO\x01\x00\x01\x00", 8);  // plausible header
      StatePacket s;
      CommandPacket c;
      if (decode(buf.data(), n, s) == DecodeStatus::Ok) ++accepted;
      if (decode(buf.data(), n, c) == DecodeStatus::Ok) ++accepted;
    }
    QCOMPARE(accepted, 0);
  }

  void trackerInOrderAndLoss() {
    SequenceTracker t;
    using V = SequenceTracker::Verdict;
    QVERIFY(t.check(1, 10) == V::Accept);
    QVERIFY(t.check(1, 11) == V::Accept);
    QVERIFY(t.check(1, 14) == V::Accept);  // 12, 13 lost
    QCOMPARE(t.lost, std::uint64_t(2));
    QCOMPARE(t.accepted, std::uint64_t(3));
    QCOMPARE(t.last_sequence(), 14u);
  }

  void trackerReorderAndDuplicates() {
    SequenceTracker t;
    using V = SequenceTracker::Verdict;
    QVERIFY(t.check(1, 100) == V::Accept);
    QVERIFY(t.check(1, 103) == V::Accept);  // 101, 102 missing so far
    QCOMPARE(t.lost, std::uint64_t(2));
    QVERIFY(t.check(1, 101) == V::Late);    // arrives late: dropped, no longer lost
    QCOMPARE(t.lost, std::uint64_t(1));
    QVERIFY(t.check(1, 101) == V::Duplicate);
    QVERIFY(t.check(1, 103) == V::Duplicate);
    QVERIFY(t.check(1, 100) == V::Duplicate);
    QVERIFY(t.check(1, 104) == V::Accept);
    QCOMPARE(t.duplicates, std::uint64_t(3));
    QCOMPARE(t.late, std::uint64_t(1));
    QCOMPARE(t.accepted, std::uint64_t(3));
    // Very old packets (beyond the window) are late, never accepted.
    QVERIFY(t.check(1, 5) == V::Late);
  }

  void trackerWrapsAround() {
    SequenceTracker t;
    using V = SequenceTracker::Verdict;
    QVERIFY(t.check(4, 0xFFFFFFFEu) == V::Accept);
    QVERIFY(t.check(4, 0xFFFFFFFFu) == V::Accept);
    QVERIFY(t.check(4, 0u) == V::Accept);
    QVERIFY(t.check(4, 2u) == V::Accept);
    QCOMPARE(t.lost, std::uint64_t(1));
    QVERIFY(t.check(4, 0xFFFFFFFFu) == V::Duplicate);
  }

  void trackerPeerRestart() {
    SequenceTracker t;
    using V = SequenceTracker::Verdict;
    QVERIFY(t.check(1, 5000) == V::Accept);
    QVERIFY(t.check(2, 1) == V::Accept);  // new session id: the peer restarted
    QCOMPARE(t.restarts, std::uint64_t(1));
    QVERIFY(t.check(2, 2) == V::Accept);
    QVERIFY(t.check(1, 5001) == V::Accept);  // (an old session again counts as another restart)
    QCOMPARE(t.restarts, std::uint64_t(2));
  }

  // Shuffled, duplicated, partly lost stream: the receiver accepts a strictly increasing
  // subsequence that ends with the newest packet, and its books balance.
  void trackerRandomisedStream() {
    std::mt19937 rng(99);
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<std::uint32_t> sent;
      for (std::uint32_t s = 1; s <= 400; ++s) {
        if (rng() % 10 == 0) continue;       // lost
        sent.push_back(s);
        if (rng() % 15 == 0) sent.push_back(s);  // duplicated
      }
      for (std::size_t i = 1; i < sent.size(); ++i)  // local reordering
        if (rng() % 5 == 0) std::swap(sent[i], sent[i - 1]);
      SequenceTracker t;
      std::uint32_t last = 0;
      std::uint32_t newest = 0;
      for (std::uint32_t s : sent) {
        newest = std::max(newest, s);
        if (t.check(1, s) == SequenceTracker::Verdict::Accept) {
          QVERIFY(s > last);
          last = s;
        }
      }
      QCOMPARE(last, newest);
      QCOMPARE(t.accepted + t.duplicates + t.late, std::uint64_t(sent.size()));
    }
  }
};

QTEST_APPLESS_MAIN(TestHandHiroProtocol)
#include "tst_handhiro_protocol.moc"
