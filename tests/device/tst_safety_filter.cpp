// The safety filter (device/safety_filter.h): clamps, rate limit, NaN/Inf guard, the
// stale-simulation and link watchdogs, ramp-in, released fingers, and the passivity
// controller. Tick-driven with a fake clock: no timing assertions.
#include <QtTest>

#include <cmath>
#include <deque>
#include <limits>
#include <random>

#include "safety_filter.h"

using namespace palpation::device;

namespace {

constexpr std::int64_t kTick = 1000000;  // 1 ms in ns
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

DeviceState attached_state() {
  DeviceState s;
  s.connected = true;
  for (auto& f : s.fingers) {
    f.present = true;
    f.attached = true;
  }
  return s;
}

std::array<Vec3, kMaxFingers> all(const Vec3& v) {
  std::array<Vec3, kMaxFingers> a;
  a.fill(v);
  return a;
}

// Runs n ticks from `t` with a fresh simulation; returns the last command.
ForceCommand run(SafetyFilter& sf, std::int64_t& t, int n, const DeviceState& st, const std::array<Vec3, kMaxFingers>& des,
                 double sim_age = 0.0) {
  ForceCommand out;
  for (int i = 0; i < n; ++i) {
    t += kTick;
    sf.apply(t, st, sim_age, des, out);
  }
  return out;
}

bool safe(const ForceCommand& c, double limit) {
  for (const auto& f : c.force)
    if (!finite(f) || norm(f) > limit) return false;
  return true;
}

}  // namespace

class TestSafetyFilter : public QObject {
  Q_OBJECT
 private slots:
  void rampsInAtStart() {
    SafetyParams p;
    p.ramp_in = 0.1;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    const auto des = all({0, 0, 2.0});
    ForceCommand c = run(sf, t, 1, attached_state(), des);
    QVERIFY(norm(c.force[0]) < 0.05);  // starts near zero
    double prev = norm(c.force[0]);
    for (int i = 0; i < 99; ++i) {  // monotone ramp, no jump
      c = run(sf, t, 1, attached_state(), des);
      QVERIFY(norm(c.force[0]) >= prev - 1e-12);
      QVERIFY(norm(c.force[0]) - prev <= 2.0 * 0.001 / 0.1 + 1e-9);
      prev = norm(c.force[0]);
    }
    c = run(sf, t, 5, attached_state(), des);
    QVERIFY(std::fabs(c.force[0].z - 2.0) < 1e-9);
  }

  void clampsToTheLimit() {
    SafetyParams p;
    p.max_force = 3.0;
    p.ramp_in = 0;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    ForceCommand c = run(sf, t, 50, attached_state(), all({30, 40, 0}));  // 50 N asked
    for (const auto& f : c.force) {
      QVERIFY(norm(f) <= 3.0);
      QVERIFY(norm(f) > 3.0 - 1e-9);
      QVERIFY(std::fabs(f.x / f.y - 0.75) < 1e-9);  // direction kept
    }
    QVERIFY(sf.counters().clamped > 0);
  }

  void rateLimitsSteps() {
    SafetyParams p;
    p.max_rate = 500;  // N/s -> 0.5 N per tick
    p.ramp_in = 0;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    ForceCommand c = run(sf, t, 1, attached_state(), all({0, 0, 0}));
    c = run(sf, t, 1, attached_state(), all({0, 0, 3.0}));
    QVERIFY(std::fabs(c.force[0].z - 0.5) < 1e-9);
    c = run(sf, t, 1, attached_state(), all({0, 0, 3.0}));
    QVERIFY(std::fabs(c.force[0].z - 1.0) < 1e-9);
    c = run(sf, t, 10, attached_state(), all({0, 0, 3.0}));
    QVERIFY(std::fabs(c.force[0].z - 3.0) < 1e-9);
    c = run(sf, t, 1, attached_state(), all({0, 0, -3.0}));  // reversal: also limited
    QVERIFY(std::fabs(c.force[0].z - 2.5) < 1e-9);
    QVERIFY(sf.counters().rate_limited > 0);
  }

  void nonFiniteInputsRenderNothing() {
    SafetyParams p;
    p.ramp_in = 0;
    p.max_rate = 1e9;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    run(sf, t, 5, attached_state(), all({0, 0, 1.0}));
    for (const Vec3 bad : {Vec3{kNaN, 0, 0}, Vec3{0, kInf, 0}, Vec3{0, 0, -kInf}}) {
      const ForceCommand c = run(sf, t, 1, attached_state(), all(bad));
      QVERIFY(safe(c, p.max_force));
      QCOMPARE(c.force[0].z, 0.0);
    }
    DeviceState st = attached_state();
    st.fingers[2].position = {kNaN, 0, 0};
    const ForceCommand c = run(sf, t, 1, st, all({0, 0, 1.0}));
    QVERIFY(safe(c, p.max_force));
    QCOMPARE(norm(c.force[2]), 0.0);
    QVERIFY(sf.counters().nonfinite >= 3 * 5 + 1);
    QCOMPARE(sf.counters().final_guard, std::uint64_t(0));
  }

  // The stale-simulation watchdog: forces reach zero within stale_after + ramp_out after
  // the last update, and come back (ramped in) when updates resume.
  void staleSimulationRampsToZero() {
    SafetyParams p;
    p.ramp_in = 0.05;
    p.ramp_out = 0.05;
    p.stale_after = 0.1;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    const auto des = all({0, 0, 2.0});
    run(sf, t, 100, attached_state(), des, 0.0);
    // The simulation stops: its age grows with each tick.
    ForceCommand c;
    double age = 0;
    int zero_at = -1;
    for (int i = 0; i < 300; ++i) {
      age += 0.001;
      c = run(sf, t, 1, attached_state(), des, age);
      if (i < 99) QVERIFY(std::fabs(c.force[0].z - 2.0) < 1e-9);  // still fresh
      if (zero_at < 0 && norm(c.force[0]) == 0) zero_at = i;
    }
    QVERIFY(zero_at >= 99);
    QVERIFY2(zero_at <= 100 + 50 + 1, qPrintable(QString::number(zero_at)));  // stale_after + ramp_out
    QCOMPARE(sf.counters().stale_events, std::uint64_t(1));
    c = run(sf, t, 1, attached_state(), des, 0.0);
    QVERIFY(norm(c.force[0]) > 0 && norm(c.force[0]) < 0.1);  // ramps in again
    c = run(sf, t, 60, attached_state(), des, 0.0);
    QVERIFY(std::fabs(c.force[0].z - 2.0) < 1e-9);
  }

  void lostLinkRampsToZero() {
    SafetyParams p;
    p.ramp_in = 0.0;
    p.ramp_out = 0.02;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    run(sf, t, 10, attached_state(), all({0, 0, 1.0}));
    DeviceState st = attached_state();
    st.connected = false;
    ForceCommand c = run(sf, t, 10, st, all({0, 0, 1.0}));
    QVERIFY(c.force[0].z > 0 && c.force[0].z < 1.0);
    c = run(sf, t, 11, st, all({0, 0, 1.0}));
    QCOMPARE(c.force[0].z, 0.0);
    QCOMPARE(sf.counters().link_events, std::uint64_t(1));
  }

  void releasedFingerGetsNothing() {
    SafetyParams p;
    p.ramp_in = 0.05;
    p.passivity = false;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    run(sf, t, 100, attached_state(), all({0, 0, 1.5}));
    DeviceState st = attached_state();
    st.fingers[kIndex].attached = false;
    ForceCommand c = run(sf, t, 1, st, all({0, 0, 1.5}));
    QCOMPARE(norm(c.force[kIndex]), 0.0);
    QVERIFY(!c.enabled[kIndex]);
    QVERIFY(c.enabled[kMiddle] && std::fabs(c.force[kMiddle].z - 1.5) < 1e-9);
    QCOMPARE(sf.counters().releases, std::uint64_t(1));
    // Re-attached: that finger ramps in from zero, no jump.
    c = run(sf, t, 1, attached_state(), all({0, 0, 1.5}));
    QVERIFY(c.force[kIndex].z < 0.1);
    QCOMPARE(sf.counters().reattaches, std::uint64_t(1));
  }

  // Property: whatever comes in (huge, tiny, NaN, Inf, random link/attach flips), what
  // goes out is finite, within the limit, and never jumps by more than the rate limit.
  void randomInputsAlwaysSafe() {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 20; ++trial) {
      SafetyParams p;
      p.max_force = 0.5 + 5 * std::fabs(u(rng));
      p.max_rate = 100 + 2000 * std::fabs(u(rng));
      p.passivity = trial % 2 == 0;
      SafetyFilter sf(p);
      std::int64_t t = 0;
      DeviceState st = attached_state();
      ForceCommand prev;
      for (int i = 0; i < 3000; ++i) {
        std::array<Vec3, kMaxFingers> des;
        for (auto& d : des) {
          const double scale = std::pow(10.0, 4 * u(rng));
          d = {scale * u(rng), scale * u(rng), scale * u(rng)};
          const int r = int(rng() % 50);
          if (r == 0) d.x = kNaN;
          if (r == 1) d.z = kInf;
        }
        for (auto& f : st.fingers) {
          f.position = f.position + Vec3{1e-4 * u(rng), 1e-4 * u(rng), 1e-4 * u(rng)};
          if (rng() % 500 == 0) f.attached = !f.attached;
        }
        if (rng() % 700 == 0) st.connected = !st.connected;
        // Irregular ticks (a loaded machine), occasionally a long stall.
        t += kTick / 2 + std::int64_t(rng() % kTick) + (rng() % 1000 == 0 ? 30 * kTick : 0);
        ForceCommand out;
        sf.apply(t, st, (rng() % 100 == 0) ? kInf : 0.01, des, out);
        QVERIFY(safe(out, p.max_force));
        for (int f = 0; f < kMaxFingers; ++f)
          if (out.enabled[f] && prev.enabled[f])  // released fingers drop to zero at once
            QVERIFY(norm(out.force[f] - prev.force[f]) <= p.max_rate * 0.02 + 1e-9);
        prev = out;
      }
      QCOMPARE(sf.counters().final_guard, std::uint64_t(0));
    }
  }

  // The passivity controller: a fingertip mass on the operator's spring touches a stiff
  // surface whose force arrives with a delay (the simulation's latency). The delayed
  // stiffness pumps energy in: without the controller the contact chatters and grows; with
  // it the oscillation is damped out.
  void passivityDampsDelayedStiffContact() {
    auto simulate = [](bool passivity, double& late_amplitude, double& dissipated) {
      SafetyParams p;
      p.passivity = passivity;
      p.ramp_in = 0;
      p.max_force = 20;
      p.max_rate = 1e5;
      SafetyFilter sf(p);
      const double m = 0.03, k_user = 800, b_user = 2, k_env = 3000, dt = 0.001;
      const int delay = 8;  // ticks of latency on the environment force
      double x = 0.0005, v = 0;  // m above the surface at 0; target below it
      const double target = -0.002;
      std::deque<double> pipe(delay, 0.0);
      std::int64_t t = 0;
      double amp = 0;
      DeviceState st = attached_state();
      ForceCommand out;
      double applied = 0;
      for (int i = 0; i < 4000; ++i) {
        // Environment force (up, +z) from the delayed position.
        pipe.push_back(x < 0 ? -k_env * x : 0.0);
        const double fenv = pipe.front();
        pipe.pop_front();
        st.fingers[0].position = {0, 0, x};
        st.fingers[0].velocity = {0, 0, v};
        t += kTick;
        sf.apply(t, st, 0.0, all({0, 0, fenv}), out);
        applied = out.force[0].z;
        const double a = (k_user * (target - x) - b_user * v + applied) / m;
        v += a * dt;
        x += v * dt;
        if (i >= 3000) amp = std::max(amp, std::fabs(applied - k_user * (0 - target)));
      }
      late_amplitude = amp;
      dissipated = sf.counters().dissipated;
    };
    double amp_off = 0, amp_on = 0, d_off = 0, d_on = 0;
    simulate(false, amp_off, d_off);
    simulate(true, amp_on, d_on);
    qInfo("force oscillation in the last second: %.4f N without, %.4f N with the passivity controller", amp_off, amp_on);
    QVERIFY(amp_off > 0.5);          // the delayed contact is unstable on its own
    QVERIFY(amp_on < 0.2 * amp_off); // the controller removes most of it
    QVERIFY(d_on > 0 && d_off == 0);
  }

  // Slow pressing and releasing (below the observer's band) is left alone.
  void passivityLeavesSlowPalpationAlone() {
    SafetyParams p;
    p.ramp_in = 0;
    SafetyFilter sf(p);
    std::int64_t t = 0;
    DeviceState st = attached_state();
    ForceCommand out;
    for (int i = 0; i < 4000; ++i) {
      const double z = -0.005 * 0.5 * (1 - std::cos(2 * M_PI * i / 1000.0));  // 1 Hz push, 5 mm
      st.fingers[0].position = {0, 0, z};
      t += kTick;
      sf.apply(t, st, 0.0, all({0, 0, -500 * z}), out);  // a passive spring
      QVERIFY(std::fabs(out.force[0].z - (-500 * z)) < 1e-3);
    }
    QCOMPARE(sf.counters().passivity_active, std::uint64_t(0));
  }
};

QTEST_APPLESS_MAIN(TestSafetyFilter)
#include "tst_safety_filter.moc"
