// The 1 kHz haptic loop's logic (device/haptic_loop.h) driven tick by tick with a fake
// clock and a scripted device, the lock-free hand-offs it relies on, and the replay
// device. No timing assertions: everything here is deterministic.
#include <QtTest>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <thread>

#include "haptic_loop.h"
#include "scripted_device.h"
#include "spsc_ring.h"
#include "triple_buffer.h"

using namespace palpation::device;

namespace {

constexpr std::int64_t kTick = 1000000;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

HandScript line_script(const Vec3& a, const Vec3& b, double T) {
  HandScript s;
  s.set_path(kIndex, {{0.0, a}, {T, b}});
  return s;
}

struct Rig {
  ScriptedDevice device;
  TripleBuffer<PoseFrame> poses;
  TripleBuffer<ContactFrame> contacts;
  SpscRing<TickRecord> ring{4096};
  HapticLoop loop;
  std::int64_t t = 0;
  std::uint64_t seq = 0;
  Rig(HandScript script, const HapticLoopParams& p, DeviceCapabilities caps = {})
      : device(std::move(script), caps), loop(device, poses, contacts, &ring, p) {}
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      t += kTick;
      loop.tick(t, t);
      TickRecord r;
      while (ring.pop(r)) {
      }
    }
  }
  void publish(const FingerContactModel& m, int finger = kIndex) {
    ContactFrame& f = contacts.write_slot();
    f.fingers = {};
    f.fingers[finger] = m;
    f.sequence = ++seq;
    f.published_ns = t;
    contacts.publish();
  }
};

HapticLoopParams plain_params() {
  HapticLoopParams p;
  p.safety.ramp_in = 0;
  p.safety.passivity = false;
  p.safety.max_rate = 1e9;
  p.safety.max_force = 100;
  p.safety.stale_after = 1e6;  // models never go stale unless a test says so
  p.max_stiffness = 1e9;
  p.virtual_coupling = false;  // F0 + K (x - x0) at the device position; coupling tested apart
  return p;
}

DeviceCapabilities big_caps() {
  DeviceCapabilities c;
  c.max_force = 100;
  c.max_stiffness = 1e9;
  return c;
}

FingerContactModel contact(const Vec3& f0, double k, const Vec3& x0) {
  FingerContactModel m;
  m.valid = true;
  m.contacts = 5;
  m.force = f0;
  m.stiffness = Mat3{{0, 0, 0, 0, 0, 0, 0, 0, -k}};  // along z only
  m.position = x0;
  m.normal = {0, 0, 1};
  return m;
}

}  // namespace

class TestHapticLoop : public QObject {
  Q_OBJECT
 private slots:
  // F(x) = F0 + K (x - x0) at the current position, every tick, between updates.
  void evaluatesModelAtCurrentPosition() {
    const Vec3 a{0.5, 0, 0.05}, b{0.5, 0, 0.04};
    Rig r(line_script(a, b, 1.0), plain_params(), big_caps());
    r.tick();
    r.publish(contact({0, 0, 1.0}, 1000, a));
    r.tick(2);  // the model arrives and its (one-tick) fade ends
    for (int i = 0; i < 100; ++i) {
      r.tick();
      const double z = r.loop.state().fingers[kIndex].position.z;
      QVERIFY(std::fabs(r.loop.desired()[kIndex].z - (1.0 + 1000 * (a.z - z))) < 1e-9);
      QVERIFY(std::fabs(r.device.received().last.force[kIndex].z - r.loop.desired()[kIndex].z) < 1e-9);
    }
    // Other fingers get nothing.
    QCOMPARE(norm(r.device.received().last.force[kMiddle]), 0.0);
  }

  // Moving off the surface beyond the model's reach gives zero, never a pull.
  void neverAdhesive() {
    const Vec3 a{0.5, 0, 0.05}, b{0.5, 0, 0.06};
    Rig r(line_script(a, b, 0.1), plain_params(), big_caps());
    r.tick();
    r.publish(contact({0, 0, 1.0}, 1000, a));
    for (int i = 0; i < 150; ++i) {
      r.tick();
      QVERIFY(r.loop.desired()[kIndex].z >= 0.0);
    }
    QCOMPARE(r.loop.desired()[kIndex].z, 0.0);  // 10 mm away: 1 - 10 N -> 0
  }

  // The local stiffness is clamped to what the device renders stably.
  void stiffnessClamped() {
    HapticLoopParams p = plain_params();
    p.max_stiffness = 2000;
    const Vec3 a{0.5, 0, 0.05};
    Rig r(line_script(a, a, 1.0), p, big_caps());
    FingerContactModel m = contact({0, 0, 1.0}, 50000, a + Vec3{0, 0, 0.001});  // 1 mm above: +50 N unclamped
    r.tick();
    r.publish(m);
    r.tick(3);
    QVERIFY(std::fabs(r.loop.desired()[kIndex].z - (1.0 + 2000 * 0.001)) < 1e-9);
  }

  // The virtual coupling: the user feels the series combination of the coupling spring and
  // the contact, never stiffer than k_c; the proxy balances coupling and tissue; the loop
  // publishes the proxy for the simulation.
  void virtualCoupling() {
    HapticLoopParams p = plain_params();
    p.virtual_coupling = true;
    p.max_stiffness = 2000;
    const double kc = 2000, S = 50000;
    const Vec3 a{0.5, 0, 0.05};
    const Vec3 x0 = a + Vec3{0, 0, 0.001};  // the simulation's proxy, 1 mm above the device
    Rig r(line_script(a, a - Vec3{0, 0, 0.002}, 1.0), p, big_caps());
    r.tick();
    r.publish(contact({0, 0, 2.0}, S, x0));
    r.tick(2);
    double prev_f = 0, prev_z = 0;
    for (int i = 0; i < 200; ++i) {
      r.tick();
      const Vec3 xd = r.loop.state().fingers[kIndex].position;
      const Vec3 f = r.loop.desired()[kIndex];
      const Vec3 xp = r.loop.proxy()[kIndex];
      // Balance: k_c (x_p - x_d) = F0 - S (x_p - x0) along z, and F = k_c (x_p - x_d).
      QVERIFY(std::fabs(kc * (xp.z - xd.z) - (2.0 - S * (xp.z - x0.z))) < 1e-9);
      QVERIFY(std::fabs(f.z - kc * (xp.z - xd.z)) < 1e-9);
      // Series stiffness k_c S / (k_c + S) as the device goes down.
      if (i > 0) QVERIFY(std::fabs((f.z - prev_f) / (xd.z - prev_z) + kc * S / (kc + S)) < 1e-3);
      prev_f = f.z;
      prev_z = xd.z;
    }
    QVERIFY(r.poses.update());
    QVERIFY(norm(r.poses.read().proxy[kIndex] - r.loop.proxy()[kIndex]) == 0);
    // Direct rendering of the same model would hand the device the full 50 kN/m.
    QVERIFY(std::fabs(norm(couple(contact({0, 0, 2.0}, S, x0), a, kc).force) - 2.0 / (1 + S / kc) - kc * S / (kc + S) * 0.001) < 1e-9);
    // Unilateral: a device far above the surface feels nothing, the proxy follows it.
    const Coupled free = couple(contact({0, 0, 2.0}, S, x0), x0 + Vec3{0, 0, 0.01}, kc);
    QCOMPARE(norm(free.force), 0.0);
    QVERIFY(norm(free.proxy - (x0 + Vec3{0, 0, 0.01})) == 0);
    // No contact: no force, proxy = device.
    FingerContactModel none;
    QVERIFY(norm(couple(none, a, kc).force) == 0 && norm(couple(none, a, kc).proxy - a) == 0);
  }

  // Force continuity: a new simulation result is faded in over the update interval, so
  // the per-tick change caused by an update is at most |dF| / L (L = ticks between
  // updates, here 8). Without the fade (blend_max_ticks = 1) the step is the whole jump.
  void continuityWhenModelUpdates() {
    for (int blend : {20, 1}) {
      HapticLoopParams p = plain_params();
      p.blend_max_ticks = blend;
      const Vec3 a{0.5, 0, 0.05};
      Rig r(line_script(a, a, 10.0), p, big_caps());
      r.tick();
      double level = 1.0;
      double max_step = 0;
      Vec3 prev;
      for (int u = 0; u < 60; ++u) {
        level = (u % 2 == 0) ? 1.0 : 2.0;  // 1 N jumps every update
        r.publish(contact({0, 0, level}, 0, a));
        for (int i = 0; i < 8; ++i) {
          r.tick();
          const Vec3 f = r.loop.desired()[kIndex];
          if (u >= 30) max_step = std::max(max_step, norm(f - prev));  // after the interval estimate settled
          prev = f;
        }
      }
      qInfo("blend_max_ticks %d: largest per-tick step %.4f N for 1 N jumps every 8 ticks", blend, max_step);
      if (blend > 1) QVERIFY(max_step <= 1.0 / 7.0 + 1e-9);  // bound |dF| / L with L >= 7
      else QVERIFY(max_step > 0.99);
    }
  }

  // A stale simulation: forces ramp to zero within stale_after + ramp_out.
  void staleSimulationRampsOut() {
    HapticLoopParams p = plain_params();
    p.safety.stale_after = 0.05;
    p.safety.ramp_out = 0.02;
    const Vec3 a{0.5, 0, 0.05};
    Rig r(line_script(a, a, 10.0), p, big_caps());
    r.tick();
    r.publish(contact({0, 0, 2.0}, 0, a));
    r.tick(10);
    QVERIFY(std::fabs(r.device.received().last.force[kIndex].z - 2.0) < 1e-9);
    int ticks_to_zero = 0;
    while (r.device.received().last.force[kIndex].z > 0 && ticks_to_zero < 1000) {
      r.tick();
      ++ticks_to_zero;
    }
    QVERIFY2(ticks_to_zero <= 50 + 20 + 2 - 10, qPrintable(QString::number(ticks_to_zero)));
    QCOMPARE(r.loop.safety().counters().stale_events, std::uint64_t(1));
    // Updates resume: forces come back.
    for (int i = 0; i < 20; ++i) {
      r.publish(contact({0, 0, 2.0}, 0, a));
      r.tick(10);
    }
    QVERIFY(r.device.received().last.force[kIndex].z > 1.9);
  }

  // The device never receives NaN, Inf or a force above its limit, whatever the
  // simulation publishes and whatever the device reports.
  void deviceNeverReceivesBadForces() {
    DeviceCapabilities caps;  // 4 N
    HapticLoopParams p;       // the real defaults: passivity on, ramps, rate limit
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    HandScript s;
    for (int f = 0; f < kMaxFingers; ++f)
      s.set_path(f, {{0.0, {0.5 + 0.01 * f, 0, 0.05}}, {5.0, {0.5 + 0.01 * f, 0.01, 0.04}}});
    Rig r(std::move(s), p, caps);
    for (int i = 0; i < 5000; ++i) {
      if (i % 7 == 0) {
        ContactFrame& cf = r.contacts.write_slot();
        for (auto& m : cf.fingers) {
          const double scale = std::pow(10.0, 6 * u(rng));
          m.valid = rng() % 10 != 0;
          m.contacts = int(rng() % 30);
          m.force = {scale * u(rng), scale * u(rng), scale * u(rng)};
          for (double& k : m.stiffness.m) k = scale * 1000 * u(rng);
          m.position = {0.5 + 0.01 * u(rng), 0.01 * u(rng), 0.05 + 0.01 * u(rng)};
          m.normal = {u(rng), u(rng), u(rng)};
          switch (rng() % 40) {
            case 0: m.force.x = kNaN; break;
            case 1: m.force.z = kInf; break;
            case 2: m.stiffness.m[4] = kNaN; break;
            case 3: m.position.y = -kInf; break;
            case 4: m.normal = {kNaN, 0, 0}; break;
            default: break;
          }
        }
        cf.sequence = ++r.seq;
        cf.published_ns = r.t;
        r.contacts.publish();
      }
      const int f = int(rng() % kMaxFingers);
      r.device.override_position(f, {kNaN, 0, 0}, rng() % 200 == 0);
      if (rng() % 300 == 0) r.device.set_attached(int(rng() % kMaxFingers), rng() % 2 == 0);
      r.tick();
    }
    const ReceivedForces& rx = r.device.received();
    QCOMPARE(rx.writes, std::uint64_t(5000));
    QCOMPARE(rx.nonfinite, std::uint64_t(0));
    QCOMPARE(rx.over_limit, std::uint64_t(0));
    QVERIFY(rx.max_force <= caps.max_force);
    QVERIFY(rx.max_force > 0.5 * caps.max_force);  // it did render forces, clamped
    QVERIFY(r.loop.safety().counters().nonfinite > 0);
    QCOMPARE(r.loop.safety().counters().final_guard, std::uint64_t(0));
  }

  // Statistics from a fake clock: periods, jitter, overruns.
  void statisticsFromFakeClock() {
    const Vec3 a{0.5, 0, 0.05};
    Rig r(line_script(a, a, 1.0), plain_params(), big_caps());
    std::int64_t t = 0;
    // Periods of 1000.2 us, every 10th 1100.3 us (values off the 1 us bin edges, so that
    // rounding in the arithmetic cannot move a sample to the neighbouring bin).
    for (int i = 0; i < 1000; ++i) {
      const std::int64_t period = (i % 10 == 0) ? 1100300 : 1000200;
      t += period;
      r.loop.tick(t, t - (period - 1000000));
    }
    r.loop.note_overrun(2);
    const LoopStats& st = r.loop.stats();
    QCOMPARE(st.ticks, std::uint64_t(1000));
    QVERIFY(std::fabs(st.period_us.percentile(50) - 1000.5) < 1e-9);   // bin centre
    QVERIFY(std::fabs(st.jitter_us.percentile(50) - 0.5) < 1e-9);
    QVERIFY(std::fabs(st.jitter_us.percentile(99) - 100.3) < 1e-6);    // bin centre capped at the maximum
    QVERIFY(std::fabs(st.jitter_us.max() - 100.3) < 1e-6);
    QVERIFY(std::fabs(st.latency_us.max() - 100.3) < 1e-6);
    QCOMPARE(st.overruns, std::uint64_t(1));
    QCOMPARE(st.missed, std::uint64_t(2));
    QVERIFY(std::fabs(st.rate_hz() - 1e9 / ((double(t) - 1100300.0) / 999.0)) < 1e-6);
  }

  // The loop publishes the fingertips for the simulation every tick.
  void publishesPoses() {
    const Vec3 a{0.5, 0, 0.05}, b{0.6, 0, 0.05};
    Rig r(line_script(a, b, 0.1), plain_params(), big_caps());
    r.tick(50);
    QVERIFY(r.poses.update());
    const PoseFrame& pf = r.poses.read();
    QCOMPARE(pf.tick, std::uint64_t(50));
    QVERIFY(pf.connected);
    QVERIFY(pf.fingers[kIndex].attached);
    QVERIFY(std::fabs(pf.fingers[kIndex].position.x - (0.5 + 0.1 * 49.0 / 100.0)) < 1e-12);
    QVERIFY(!r.poses.update());  // nothing newer
  }

  // The triple buffer under real concurrency: the consumer only ever sees whole frames,
  // in order.
  void tripleBufferIsConsistentUnderConcurrency() {
    struct Frame {
      std::uint64_t n = 0;
      std::array<std::uint64_t, 64> copy{};
    };
    TripleBuffer<Frame> tb;
    std::atomic<bool> done{false};
    const std::uint64_t N = 200000;
    std::thread producer([&] {
      for (std::uint64_t i = 1; i <= N; ++i) {
        Frame& f = tb.write_slot();
        f.n = i;
        f.copy.fill(i);
        tb.publish();
      }
      done.store(true);
    });
    std::uint64_t last = 0, torn = 0, backwards = 0, reads = 0;
    while (true) {
      const bool finished = done.load();
      if (tb.update()) {
        const Frame& f = tb.read();
        ++reads;
        for (auto c : f.copy)
          if (c != f.n) ++torn;
        if (f.n < last) ++backwards;
        last = f.n;
      }
      if (finished && !tb.update()) break;
    }
    producer.join();
    if (tb.update()) last = tb.read().n;
    QCOMPARE(torn, std::uint64_t(0));
    QCOMPARE(backwards, std::uint64_t(0));
    QCOMPARE(last, N);  // the newest always arrives
    QVERIFY(reads > 0);
  }

  void spscRingDeliversInOrder() {
    SpscRing<std::uint64_t> ring(128);
    const std::uint64_t N = 300000;
    std::thread producer([&] {
      for (std::uint64_t i = 1; i <= N; ++i)
        while (!ring.push(i)) std::this_thread::yield();
    });
    std::uint64_t expect = 1, v = 0;
    while (expect <= N) {
      if (ring.pop(v)) {
        QCOMPARE(v, expect);
        ++expect;
      } else {
        std::this_thread::yield();
      }
    }
    producer.join();
    QVERIFY(!ring.pop(v));
    // Full ring: push fails and counts.
    SpscRing<int> small(2);
    QVERIFY(small.push(1));
    QVERIFY(small.push(2));
    QVERIFY(!small.push(3));
    QCOMPARE(small.dropped(), std::uint64_t(1));
  }

  // The replay device plays a recorded fingers.csv through the registration and map.
  void replayDevicePlaysRecording() {
    const QString path = QDir::temp().filePath(QString("tst_haptic_loop_%1.csv").arg(QCoreApplication::applicationPid()));
    {
      std::FILE* f = std::fopen(path.toLocal8Bit().constData(), "w");
      QVERIFY(f);
      std::fputs("t,finger,x,y,z,fx,fy,fz\n", f);
      for (int k = 1; k <= 100; ++k) std::fprintf(f, "%.3f,0,%.6f,0,0.05,0,0,0.5\n", k * 0.001, 0.1 + 0.001 * k);
      std::fclose(f);
    }
    RigidFrame reg;
    reg.origin = {0.4, 0, 0};
    std::array<int, kMaxFingers> map{kIndex, kMiddle, kRing, kLittle, kThumb};
    ReplayDevice dev(path.toStdString(), reg, map);
    DeviceState st;
    dev.read(0, st);  // t = 0: first key held
    QVERIFY(st.fingers[kIndex].present && st.fingers[kIndex].attached);
    QVERIFY(!st.fingers[kThumb].present);
    QVERIFY(std::fabs(st.fingers[kIndex].position.x - 0.501) < 1e-12);
    dev.read(50 * kTick - kTick, st);  // t = 0.049 s -> sample k = 49
    QVERIFY(std::fabs(st.fingers[kIndex].position.x - (0.4 + 0.1 + 0.049)) < 1e-9);
    QVERIFY(std::fabs(st.fingers[kIndex].velocity.x - 1.0) < 1e-6);  // 1 mm per ms
    std::remove(path.toLocal8Bit().constData());
    // A malformed recording names the file and the line.
    {
      std::FILE* f = std::fopen(path.toLocal8Bit().constData(), "w");
      std::fputs("t,finger,x,y,z,fx,fy,fz\n0.001,0,1,2,3,0,0,0\n0.002,9,1,2,3,0,0,0\n", f);
      std::fclose(f);
    }
    try {
      ReplayDevice bad(path.toStdString(), reg, map);
      QFAIL("accepted a bad recording");
    } catch (const std::runtime_error& e) {
      QVERIFY2(std::string(e.what()).find("line 3") != std::string::npos, e.what());
    }
    std::remove(path.toLocal8Bit().constData());
  }
};

QTEST_APPLESS_MAIN(TestHapticLoop)
#include "tst_haptic_loop.moc"
