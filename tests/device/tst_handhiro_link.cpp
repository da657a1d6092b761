// The HandHIRO link over loopback UDP (127.0.0.1 only): the PC side (HandHiroLink under
// the haptic loop) against the robot side (HandHiroEmulator), stepped in lockstep with a
// fake clock; a third socket injects lost, reordered, duplicated, damaged and garbage
// datagrams. Real sockets, no timing assertions: each side waits (generously) for the
// other's datagram before its next tick.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>

#include "handhiro_emulator.h"
#include "handhiro_link.h"
#include "haptic_loop.h"

using namespace palpation::device;
namespace pr = palpation::device::protocol;

namespace {

constexpr std::int64_t kTick = 1000000;
constexpr int kWaitMs = 2000;  // generous: a loaded CI machine may be slow to deliver

HandScript still(const HandHiroKinematics& k, int finger, Vec3* at = nullptr) {
  const Vec3 p = k.fingertip(k.neutral(), finger);
  if (at) *at = p;
  HandScript s;
  s.set_path(finger, {{0.0, p}, {1000.0, p}});
  return s;
}

FingerContactModel push(const Vec3& f, const Vec3& x0) {
  FingerContactModel m;
  m.valid = true;
  m.contacts = 4;
  m.force = f;
  m.position = x0;
  m.normal = f * (1.0 / norm(f));
  return m;
}

// PC (link + loop) and robot (emulator) in lockstep.
struct Chain {
  HandHiroParams params;
  Vec3 tip;
  std::unique_ptr<HandHiroEmulator> emu;
  std::unique_ptr<HandHiroLink> link;
  TripleBuffer<PoseFrame> poses;
  TripleBuffer<ContactFrame> contacts;
  std::unique_ptr<HapticLoop> loop;
  std::int64_t t = 1000 * kTick;
  std::uint64_t seq = 0;

  explicit Chain(HandHiroParams p = default_handhiro_params(), HapticLoopParams lp = {}) : params(p) {
    HandHiroKinematics k(params);
    emu = std::make_unique<HandHiroEmulator>(params, still(k, kIndex, &tip), EmulatorOptions{"127.0.0.1", 0, true, 11});
    std::string err;
    if (!emu->open(&err)) qFatal("emulator: %s", err.c_str());
    LinkConfig lc;
    lc.robot_port = emu->port();
    lc.session = 22;
    link = std::make_unique<HandHiroLink>(params.capabilities, lc);
    if (!link->open(&err)) qFatal("link: %s", err.c_str());
    lp.safety.stale_after = 1e6;  // the contact model is set by hand here
    loop = std::make_unique<HapticLoop>(*link, poses, contacts, nullptr, lp);
  }
  void publish(const FingerContactModel& m) {
    ContactFrame& f = contacts.write_slot();
    f.fingers = {};
    f.fingers[kIndex] = m;
    f.sequence = ++seq;
    f.published_ns = t;
    contacts.publish();
  }
  // One tick of both sides; either may be switched off (a disconnected peer).
  void tick(bool pc = true, bool robot = true) {
    t += kTick;
    if (pc) {
      loop->tick(t, t);
      if (robot) emu->wait_readable(kWaitMs);
    }
    if (robot) {
      emu->tick(t);
      if (pc) link->wait_readable(kWaitMs);
    }
  }
  void ticks(int n, bool pc = true, bool robot = true) {
    for (int i = 0; i < n; ++i) tick(pc, robot);
  }
  double robot_force() const { return norm(emu->robot().finger(kIndex).applied); }
  double pc_force() const { return norm(loop->command().force[kIndex]); }
};

// A raw socket that plays one side of the protocol by hand.
struct Injector {
  UdpSocket sock;
  Injector() {
    std::string err;
    if (!sock.open("127.0.0.1", 0, &err)) qFatal("injector: %s", err.c_str());
  }
  void send(std::uint16_t port, const std::uint8_t* d, std::size_t n) {
    QVERIFY(sock.send_to({0x7F000001u, port}, d, n));
  }
  void send_state(std::uint16_t port, std::uint32_t session, std::uint32_t seq, double marker, bool corrupt = false) {
    pr::StatePacket p;
    p.header.session = session;
    p.header.sequence = seq;
    p.header.send_time_ns = seq;
    for (auto& f : p.fingers) {
      f.position = {marker, 0, 0};
      f.flags = pr::kFingerPresent | pr::kFingerAttached;
    }
    std::uint8_t buf[pr::kMaxPacketSize];
    const std::size_t n = pr::encode(p, buf, sizeof buf);
    if (corrupt) buf[100] ^= 0x10;
    send(port, buf, n);
  }
  void send_command(std::uint16_t port, std::uint32_t seq, const Vec3& f, bool nan = false) {
    pr::CommandPacket p;
    p.header.session = 5;
    p.header.sequence = seq;
    p.flags = pr::kCommandEnable;
    p.fingers[kIndex].force = f;
    p.fingers[kIndex].enabled = true;
    if (nan) p.fingers[kIndex].force.x = std::numeric_limits<double>::quiet_NaN();
    std::uint8_t buf[pr::kMaxPacketSize];
    const std::size_t n = pr::encode(p, buf, sizeof buf);
    send(port, buf, n);
  }
};

}  // namespace

class TestHandHiroLink : public QObject {
  Q_OBJECT
 private slots:
  // The whole chain on loopback: the PC reads the robot's fingertips, renders a contact
  // force, the robot applies it; the books balance.
  void endToEndOnLoopback() {
    Chain c;
    c.ticks(5);
    c.publish(push({0, 0, 1.5}, c.tip));
    c.ticks(800);  // ramp-in 0.5 s
    QVERIFY(c.loop->state().connected);
    QVERIFY(norm(c.loop->state().fingers[kIndex].position - c.tip) < 1e-6);
    QVERIFY(c.loop->state().fingers[kIndex].attached);
    QVERIFY(std::fabs(c.robot_force() - 1.5) < 1e-6);
    QVERIFY(std::fabs(c.emu->robot().finger(kIndex).applied.z - 1.5) < 1e-6);
    const LinkCounters lc = c.link->counters();
    QVERIFY(lc.received >= 790);
    QCOMPARE(lc.corrupt, std::uint64_t(0));
    QCOMPARE(lc.link_losses, std::uint64_t(0));
    QCOMPARE(c.emu->counters().corrupt, std::uint64_t(0));
    QCOMPARE(c.emu->counters().watchdog_events, std::uint64_t(0));
    QVERIFY(lc.last_rtt_ns >= 0);
    QVERIFY(c.link->rtt_us().count() > 700);
  }

  // States arriving lost, late, twice, damaged or as garbage: the PC keeps the newest
  // valid one and counts the rest.
  void pcSurvivesLossReorderDuplicatesGarbage() {
    LinkConfig lc;
    Injector robot;
    lc.robot_port = robot.sock.local_port();
    HandHiroLink link(DeviceCapabilities{}, lc);
    QVERIFY(link.open());
    DeviceState st;
    std::int64_t t = 0;
    auto deliver = [&]() {
      link.wait_readable(kWaitMs);
      t += kTick;
      link.read(t, st);
    };
    robot.send_state(link.local_port(), 9, 1, 1.0);
    deliver();
    QVERIFY(st.connected);
    QCOMPARE(st.fingers[0].position.x, 1.0);
    robot.send_state(link.local_port(), 9, 2, 2.0);
    robot.send_state(link.local_port(), 9, 2, 2.0);  // duplicate
    robot.send_state(link.local_port(), 9, 5, 5.0);  // 3, 4 not yet
    robot.send_state(link.local_port(), 9, 4, 4.0);  // late: must not win over 5
    robot.send_state(link.local_port(), 9, 6, 6.0, true);  // damaged
    const std::uint8_t garbage[] = {'H', 'H', 'R', 'O', 1, 0, 1, 0, 9, 9, 9};
    robot.send(link.local_port(), garbage, sizeof garbage);
    robot.send_state(link.local_port(), 9, 7, 7.0);
    // All of those are queued; one read drains them (poll until the last has arrived).
    for (int i = 0; i < 100 && st.fingers[0].position.x != 7.0; ++i) deliver();
    QCOMPARE(st.fingers[0].position.x, 7.0);
    const LinkCounters c = link.counters();
    QCOMPARE(c.received, std::uint64_t(4));   // 1, 2, 5, 7
    QCOMPARE(c.duplicates, std::uint64_t(1));
    QCOMPARE(c.reordered, std::uint64_t(1));  // 4
    QCOMPARE(c.lost, std::uint64_t(2));       // 3 and 6 (the damaged one never counted as received)
    QCOMPARE(c.corrupt, std::uint64_t(2));
    // A late packet alone never moves the state back.
    robot.send_state(link.local_port(), 9, 3, 3.0);
    deliver();
    QCOMPARE(st.fingers[0].position.x, 7.0);
    // The robot restarts (new session): its first packet is accepted.
    robot.send_state(link.local_port(), 10, 1, 8.0);
    for (int i = 0; i < 100 && st.fingers[0].position.x != 8.0; ++i) deliver();
    QCOMPARE(st.fingers[0].position.x, 8.0);
    QCOMPARE(link.peer_restarts(), std::uint64_t(1));
    // The PC's own commands are well-formed and finite.
    ForceCommand cmd;
    cmd.force[kIndex] = {0, 0, 1};
    cmd.enabled[kIndex] = true;
    link.write(t, cmd);
    QVERIFY(robot.sock.wait_readable(kWaitMs));
    std::uint8_t buf[1024];
    const long n = robot.sock.receive(buf, sizeof buf);
    pr::CommandPacket p;
    QCOMPARE(pr::decode(buf, std::size_t(n), p), pr::DecodeStatus::Ok);
    QCOMPARE(p.fingers[kIndex].force.z, 1.0);
    QCOMPARE(p.header.echo_sequence, 1u);  // echoes the newest state it accepted
  }

  // The operator's script from the first command: it rests at its last point, or with
  // `looped` starts over (the workstation's operator palpates until stopped). Rigid hand:
  // the robot's fingertip is where the script is, 10 mm down over 100 ms.
  void scriptRestsOrLoops() {
    HandHiroParams params = default_handhiro_params();
    HandHiroKinematics k(params);
    const Vec3 top = k.fingertip(k.neutral(), kIndex), down = top + Vec3{0, 0, -0.01};
    for (const bool looped : {false, true}) {
      HandScript script;
      script.set_path(kIndex, {{0.0, top}, {0.1, down}});
      EmulatorOptions o{"127.0.0.1", 0, true, 3};
      o.looped = looped;
      HandHiroEmulator emu(params, std::move(script), o);
      QVERIFY(emu.open());
      Injector pc;
      std::int64_t t = 0;
      for (std::uint32_t s = 1; s <= 150; ++s) {  // 150 ms of commands (no force)
        pc.send_command(emu.port(), s, {0, 0, 0});
        emu.wait_readable(kWaitMs);
        t += kTick;
        emu.tick(t);
      }
      QVERIFY(emu.started());
      // The script began at the first command's tick: 149 ms of it have run.
      const double want_t = looped ? 0.049 : 0.149;
      QVERIFY2(std::fabs(emu.script_time() - want_t) < 1e-9, qPrintable(QString::number(emu.script_time())));
      const Vec3 want_tip = looped ? top + (down - top) * (0.049 / 0.1) : down;
      QVERIFY2(norm(emu.robot().finger(kIndex).tip - want_tip) < 1e-4,  // IK tolerance: 0.1 mm
               qPrintable(QString("looped %1: tip %2 mm from the script").arg(looped).arg(norm(emu.robot().finger(kIndex).tip - want_tip) * 1e3)));
    }
  }

  // Commands arriving lost, late, twice, damaged, non-finite or above the limit: the
  // robot applies only the newest valid one, never a NaN, never more than its limit.
  void robotSurvivesBadCommands() {
    HandHiroParams params = default_handhiro_params();
    HandHiroKinematics k(params);
    HandHiroEmulator emu(params, still(k, kIndex), EmulatorOptions{"127.0.0.1", 0, true, 3});
    QVERIFY(emu.open());
    Injector pc;
    std::int64_t t = 0;
    auto deliver = [&]() {
      emu.wait_readable(kWaitMs);
      t += kTick;
      emu.tick(t);
    };
    for (std::uint32_t s = 1; s <= 50; ++s) {  // 50 ms of 1 N: the robot ramps in
      pc.send_command(emu.port(), s, {0, 0, 1.0});
      deliver();
    }
    QVERIFY(std::fabs(emu.robot().finger(kIndex).applied.z - 1.0) < 1e-9);
    pc.send_command(emu.port(), 52, {0, 0, 2.0});
    pc.send_command(emu.port(), 51, {0, 0, 0.5});                 // late
    pc.send_command(emu.port(), 52, {0, 0, 2.0});                 // duplicate
    pc.send_command(emu.port(), 53, {0, 0, 1.0}, true);           // NaN: refused whole
    const std::uint8_t junk[] = {1, 2, 3};
    pc.send(emu.port(), junk, sizeof junk);
    for (int i = 0; i < 100 && emu.counters().corrupt == 0; ++i) deliver();
    QVERIFY(std::fabs(emu.robot().finger(kIndex).applied.z - 2.0) < 1e-9);
    QCOMPARE(emu.counters().refused_nonfinite, std::uint64_t(1));
    QCOMPARE(emu.counters().duplicates, std::uint64_t(1));
    QCOMPARE(emu.counters().late, std::uint64_t(1));
    QCOMPARE(emu.counters().corrupt, std::uint64_t(1));
    QVERIFY(finite(emu.robot().finger(kIndex).applied));
    // Above the limit: the robot clamps to its own limit.
    pc.send_command(emu.port(), 60, {0, 0, 50.0});
    deliver();
    t += kTick;
    emu.tick(t);
    QVERIFY(norm(emu.robot().finger(kIndex).applied) <= params.capabilities.max_force * (1 + 1e-12));
    QCOMPARE(emu.counters().over_limit, std::uint64_t(1));
  }

  // The robot stops answering: the PC's link watchdog trips and its forces ramp to zero;
  // when the robot answers again the forces come back (ramped in).
  void disconnectedEmulatorRampsToZeroAndReconnects() {
    HapticLoopParams lp;
    lp.safety.ramp_in = 0.1;
    lp.safety.ramp_out = 0.05;
    Chain c(default_handhiro_params(), lp);
    c.publish(push({0, 0, 2.0}, c.tip));
    c.ticks(300);
    QVERIFY(std::fabs(c.pc_force() - 2.0) < 1e-9);
    // Emulator gone (stops ticking): nothing arrives at the PC.
    int zero_at = -1;
    for (int i = 0; i < 300; ++i) {
      c.tick(true, false);
      if (zero_at < 0 && c.pc_force() == 0.0) zero_at = i;
    }
    QVERIFY(!c.loop->state().connected);
    QVERIFY(zero_at >= 0);
    QVERIFY2(zero_at <= 50 + 50 + 2, qPrintable(QString::number(zero_at)));  // link timeout + ramp_out
    QCOMPARE(c.link->counters().link_losses, std::uint64_t(1));
    QCOMPARE(c.loop->safety().counters().link_events, std::uint64_t(1));
    // It comes back: the forces ramp in again, no jump.
    double prev = 0, max_step = 0;
    for (int i = 0; i < 300; ++i) {
      c.tick();
      max_step = std::max(max_step, std::fabs(c.pc_force() - prev));
      prev = c.pc_force();
    }
    QVERIFY(c.loop->state().connected);
    QVERIFY(std::fabs(c.pc_force() - 2.0) < 1e-9);
    QVERIFY(max_step <= 2.0 * 0.001 / 0.1 * 1.5 + 1e-9);
    QVERIFY(std::fabs(c.robot_force() - 2.0) < 1e-6);
  }

  // The PC stops sending: the robot's own watchdog ramps its forces off and says so in
  // its state; commands again -> forces again.
  void robotWatchdog() {
    Chain c;
    c.publish(push({0, 0, 1.0}, c.tip));
    c.ticks(700);
    QVERIFY(std::fabs(c.robot_force() - 1.0) < 1e-6);
    for (int i = 0; i < 200; ++i) c.tick(false, true);
    QCOMPARE(c.robot_force(), 0.0);
    QVERIFY(c.emu->watchdog());
    QCOMPARE(c.emu->counters().watchdog_events, std::uint64_t(1));
    QVERIFY(!c.loop->state().device_watchdog);  // the PC has not heard of it yet
    // The PC's next tick reads the robot's states sent meanwhile (with the flag) before the
    // robot has its command: the PC sees the robot's watchdog.
    QVERIFY(c.link->wait_readable(kWaitMs));
    c.tick(true, false);
    QVERIFY(c.loop->state().device_watchdog);
    c.ticks(100);
    QVERIFY(!c.emu->watchdog());
    QVERIFY(!c.loop->state().device_watchdog);  // and that it cleared
    QVERIFY(std::fabs(c.robot_force() - 1.0) < 1e-6);
  }

  // A magnet joint opens at the robot: the PC sees the finger detached and stops
  // rendering to it; the operator reconnects and forces resume.
  void releaseReportedAndRecovered() {
    HandHiroParams p = default_handhiro_params();
    p.capabilities.release_force = 1.5;
    p.reattach_delay = 0.1;
    HapticLoopParams lp;
    lp.safety.ramp_in = 0.05;
    Chain c(p, lp);
    c.publish(push({0, 0, 1.0}, c.tip));
    c.ticks(200);
    QVERIFY(c.loop->state().fingers[kIndex].attached);
    c.publish(push({0, 0, 3.0}, c.tip));  // above the release force
    int released_at = -1;
    for (int i = 0; i < 300 && released_at < 0; ++i) {
      c.tick();
      if (!c.loop->state().fingers[kIndex].attached) released_at = i;
    }
    QVERIFY(released_at >= 0);
    QCOMPARE(c.emu->robot().counters().releases, std::uint64_t(1));
    c.tick();
    QCOMPARE(c.pc_force(), 0.0);
    QVERIFY(!c.loop->command().enabled[kIndex]);
    QCOMPARE(c.loop->safety().counters().releases, std::uint64_t(1));
    c.publish(push({0, 0, 1.0}, c.tip));  // the trainee presses gently again
    c.ticks(400);
    QVERIFY(c.loop->state().fingers[kIndex].attached);
    QCOMPARE(c.loop->safety().counters().reattaches, std::uint64_t(1));
    QVERIFY(std::fabs(c.pc_force() - 1.0) < 1e-9);
  }

  // Whatever the simulation publishes, nothing non-finite or above the limit reaches the
  // robot over the wire.
  void robotNeverReceivesBadForces() {
    Chain c;
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 1500; ++i) {
      if (i % 5 == 0) {
        FingerContactModel m = push({u(rng), u(rng), 1 + std::fabs(u(rng))}, c.tip);
        const double scale = std::pow(10.0, 5 * u(rng));
        m.force = m.force * scale;
        for (double& k : m.stiffness.m) k = 1e4 * scale * u(rng);
        if (rng() % 10 == 0) m.force.y = std::numeric_limits<double>::quiet_NaN();
        if (rng() % 10 == 0) m.stiffness.m[0] = std::numeric_limits<double>::infinity();
        c.publish(m);
      }
      c.tick();
    }
    const EmulatorCounters& e = c.emu->counters();
    QCOMPARE(e.refused_nonfinite, std::uint64_t(0));
    QCOMPARE(e.over_limit, std::uint64_t(0));
    QVERIFY(e.max_force_received <= c.params.capabilities.max_force);
    QVERIFY(e.max_force_received > 0.5 * c.params.capabilities.max_force);
    QVERIFY(e.commands >= 1400);
  }
};

QTEST_APPLESS_MAIN(TestHandHiroLink)
#include "tst_handhiro_link.moc"
