// The HandHIRO model (device/handhiro_model.h, handhiro_robot.h) and its configuration
// file (resources/handhiro.json via app/live/device_config.h). Checks invariants: Jacobian =
// d(tip)/dq by finite differences, virtual work (tau . dq = f . dx), IK/FK consistency,
// torque limits that keep the force's direction, magnet release and re-attachment.
#include <QtTest>

#include <cmath>
#include <random>

#include "live/device_config.h"
#include "handhiro_model.h"
#include "handhiro_robot.h"
#include "scenario.h"

using namespace palpation::device;

namespace {

JointVector jitter(const HandHiroKinematics& k, std::mt19937& rng, double amp) {
  std::uniform_real_distribution<double> u(-amp, amp);
  JointVector q = k.neutral();
  for (double& v : q) v += u(rng);
  return q;
}

HandScript still_script(const HandHiroKinematics& k, int finger, Vec3* where = nullptr) {
  const Vec3 p = k.fingertip(k.neutral(), finger);
  if (where) *where = p;
  HandScript s;
  s.set_path(finger, {{0.0, p}, {100.0, p}});
  return s;
}

}  // namespace

class TestHandHiroModel : public QObject {
  Q_OBJECT
 private slots:
  // Jacobian columns against central finite differences of the FK (1e-6 rad steps; the
  // truncation error is ~1e-12 m, so 1e-8 relative to the column is a tight bound).
  void jacobianMatchesFiniteDifferences() {
    HandHiroKinematics k(default_handhiro_params());
    std::mt19937 rng(7);
    for (int trial = 0; trial < 5; ++trial) {
      const JointVector q = jitter(k, rng, 0.3);
      for (int f = 0; f < kMaxFingers; ++f) {
        std::array<Vec3, kJoints> cols;
        k.fingertip_jacobian(q, f, cols);
        for (int j = 0; j < kJoints; ++j) {
          JointVector qp = q, qm = q;
          qp[j] += 1e-6;
          qm[j] -= 1e-6;
          const Vec3 fd = (k.fingertip(qp, f) - k.fingertip(qm, f)) * (1.0 / 2e-6);
          QVERIFY2(norm(fd - cols[j]) < 1e-7, qPrintable(QString("finger %1 joint %2").arg(f).arg(j)));
        }
      }
    }
  }

  // tau = J^T f is the torque that balances f: tau . dq == f . d(tip) for any small dq.
  void torquesAreVirtualWork() {
    HandHiroKinematics k(default_handhiro_params());
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    const JointVector q = jitter(k, rng, 0.2);
    std::array<Vec3, kMaxFingers> F;
    for (auto& f : F) f = {u(rng), u(rng), 3 * u(rng)};
    JointVector tau;
    k.joint_torques(q, F, tau);
    for (int trial = 0; trial < 10; ++trial) {
      JointVector dq{}, q2 = q;
      for (int j = 0; j < kJoints; ++j) {
        dq[j] = 1e-7 * u(rng);
        q2[j] += dq[j];
      }
      double lhs = 0, rhs = 0;
      for (int j = 0; j < kJoints; ++j) lhs += tau[j] * dq[j];
      for (int f = 0; f < kMaxFingers; ++f) rhs += dot(F[f], k.fingertip(q2, f) - k.fingertip(q, f));
      QVERIFY(std::fabs(lhs - rhs) < 1e-9 * (std::fabs(lhs) + 1e-9) + 1e-13);
    }
  }

  // The emulator's IK: the palm reaches a reachable pose, each finger a reachable point.
  void inverseKinematicsReachesTargets() {
    HandHiroKinematics k(default_handhiro_params());
    std::mt19937 rng(3);
    for (int trial = 0; trial < 20; ++trial) {
      const JointVector truth = jitter(k, rng, 0.25);
      // Clamp the truth to the limits so that it is reachable.
      JointVector t = truth;
      for (int j = 0; j < kArmJoints; ++j) t[j] = std::clamp(t[j], k.params().arm[j].lower, k.params().arm[j].upper);
      for (int f = 0; f < kMaxFingers; ++f)
        for (int j = 0; j < kFingerJoints; ++j) {
          const auto& s = k.params().fingers[f].joints[j];
          t[kArmJoints + 3 * f + j] = std::clamp(t[kArmJoints + 3 * f + j], s.lower + 0.01, s.upper - 0.01);
        }
      JointVector q = k.neutral();
      QVERIFY(k.solve_palm(k.palm(t), q, 200));
      const Pose pa = k.palm(q), pb = k.palm(t);
      QVERIFY(norm(pa.position - pb.position) < 1e-6);
      for (int f = 0; f < kMaxFingers; ++f) {
        const Vec3 goal = pb.position + pb.rotation * (k.palm(t).rotation.transposed() * (k.fingertip(t, f) - pb.position));
        k.solve_finger(f, goal, q, 100, 1e-9);
        QVERIFY2(norm(k.fingertip(q, f) - goal) < 1e-6, qPrintable(QString("trial %1 finger %2").arg(trial).arg(f)));
      }
    }
  }

  // Torque limits scale a finger's force down along its own direction and leave no joint
  // above its limit.
  void torqueLimitsKeepDirection() {
    HandHiroParams p = default_handhiro_params();
    for (auto& fs : p.fingers)
      for (auto& j : fs.joints) j.max_torque = 0.05;  // weak fingers
    HandHiroKinematics k(p);
    const JointVector q = k.neutral();
    std::array<Vec3, kMaxFingers> F{};
    F[kIndex] = {0.5, 0.0, 4.0};
    F[kMiddle] = {0.0, 0.0, 0.1};  // small enough to pass
    const auto original = F;
    const auto scale = k.limit_forces(q, F);
    QVERIFY(scale[kIndex] < 1.0);
    QCOMPARE(scale[kMiddle], 1.0);
    QVERIFY(norm(F[kIndex] - original[kIndex] * scale[kIndex]) < 1e-12);
    QVERIFY(norm(F[kMiddle] - original[kMiddle]) < 1e-15);
    JointVector tau;
    k.joint_torques(q, F, tau);
    for (int f = 0; f < kMaxFingers; ++f)
      for (int j = 0; j < kFingerJoints; ++j)
        QVERIFY(std::fabs(tau[kArmJoints + 3 * f + j]) <= p.fingers[f].joints[j].max_torque * (1 + 1e-9));
    // The arm carries all fingers: one common factor.
    HandHiroParams pa = default_handhiro_params();
    pa.arm[1].max_torque = 0.1;
    HandHiroKinematics ka(pa);
    std::array<Vec3, kMaxFingers> G{};
    G[kIndex] = {0, 0, 3};
    G[kThumb] = {0, 0, 3};
    const auto s2 = ka.limit_forces(q, G);
    QVERIFY(s2[kIndex] < 1.0);
    QCOMPARE(s2[kIndex], s2[kThumb]);
    ka.joint_torques(q, G, tau);
    QVERIFY(std::fabs(tau[1]) <= 0.1 * (1 + 1e-9));
  }

  // A rigid hand: the robot reports the scripted fingertip positions (FK of its IK).
  void robotFollowsRigidHand() {
    HandHiroParams p = default_handhiro_params();
    HandHiroKinematics k(p);
    const Vec3 a = k.fingertip(k.neutral(), kIndex);
    HandScript s;
    s.set_path(kIndex, {{0.0, a}, {1.0, a + Vec3{0.03, 0.01, -0.02}}});
    HandHiroRobot robot(p, s, true);
    std::array<Vec3, kMaxFingers> zero{};
    for (int i = 0; i <= 1000; ++i) {
      const double t = i * 0.001;
      robot.step(t, 0.001, zero);
      Vec3 want, v;
      s.sample(t, kIndex, want, v);
      QVERIFY2(norm(robot.finger(kIndex).tip - want) < 1e-6, qPrintable(QString("t = %1").arg(t)));
    }
    QCOMPARE(robot.counters().ik_misses, std::uint64_t(0));
    protocol::StatePacket pkt;
    robot.fill(pkt);
    QVERIFY(pkt.fingers[kIndex].flags & protocol::kFingerAttached);
    QVERIFY(norm(pkt.fingers[kIndex].position - robot.finger(kIndex).tip) == 0);
  }

  // A compliant operator finger settles where its spring balances the rendered force.
  void compliantFingerBalancesForce() {
    HandHiroParams p = default_handhiro_params();
    HandHiroKinematics k(p);
    Vec3 at;
    HandHiroRobot robot(p, still_script(k, kIndex, &at), false);
    std::array<Vec3, kMaxFingers> F{};
    F[kIndex] = {0, 0, 2.0};
    for (int i = 0; i < 3000; ++i) robot.step(i * 0.001, 0.001, F);
    const double expect = 2.0 / p.user.stiffness;  // 2.5 mm up
    QVERIFY(std::fabs(robot.finger(kIndex).user_x.z - (at.z + expect)) < 1e-5);
    QVERIFY(norm(robot.finger(kIndex).tip - robot.finger(kIndex).user_x) < 1e-6);
  }

  // The magnet joint opens above the release force, the finger gets no force while it is
  // off, and it closes again when the operator reconnects.
  void magnetReleaseAndReattach() {
    HandHiroParams p = default_handhiro_params();
    p.capabilities.release_force = 1.0;
    p.reattach_delay = 0.2;
    HandHiroKinematics k(p);
    HandHiroRobot robot(p, still_script(k, kIndex), false);
    std::array<Vec3, kMaxFingers> F{};
    F[kIndex] = {0, 0, 0.5};
    for (int i = 0; i < 100; ++i) robot.step(i * 0.001, 0.001, F);
    QVERIFY(robot.finger(kIndex).attached);
    F[kIndex] = {0, 0, 1.5};  // above the release force
    int i = 100;
    for (; i < 200 && robot.finger(kIndex).attached; ++i) robot.step(i * 0.001, 0.001, F);
    QVERIFY(!robot.finger(kIndex).attached);
    QCOMPARE(robot.counters().releases, std::uint64_t(1));
    const int released_at = i;
    // While released: no force on the finger, reported as detached.
    for (; i < released_at + 100; ++i) {
      robot.step(i * 0.001, 0.001, F);
      QVERIFY(norm(robot.finger(kIndex).applied) == 0);
    }
    protocol::StatePacket pkt;
    robot.fill(pkt);
    QVERIFY(!(pkt.fingers[kIndex].flags & protocol::kFingerAttached));
    QVERIFY(pkt.fingers[kIndex].flags & protocol::kFingerPresent);
    // The PC stops commanding the finger; the operator reconnects after the delay.
    F[kIndex] = {};
    for (; i < released_at + 2000 && !robot.finger(kIndex).attached; ++i) robot.step(i * 0.001, 0.001, F);
    QVERIFY(robot.finger(kIndex).attached);
    QCOMPARE(robot.counters().reattaches, std::uint64_t(1));
    QVERIFY(i - released_at >= 200);  // not before the delay
    // Other fingers were never affected.
    QVERIFY(robot.finger(kMiddle).attached);
  }

  void configFileMatchesDefaults() {
    using namespace palpation::app::live;
    const std::string path = std::string(PALPATION_SOURCE_DIR) + "/resources/handhiro.json";
    const DeviceConfig file = load_device_config(path);
    const DeviceConfig def = default_device_config();
    QCOMPARE(QString::fromStdString(device_config_to_json(file).dump()), QString::fromStdString(device_config_to_json(def).dump()));
    // Round trip of a modified configuration.
    DeviceConfig c = def;
    c.hand.capabilities.max_force = 2.5;
    c.loop.safety.passivity = false;
    c.finger_map = {0, 1, 2, 3, 4};
    const DeviceConfig back = parse_device_config(device_config_to_json(c).dump(), "x.json");
    QCOMPARE(back.hand.capabilities.max_force, 2.5);
    QCOMPARE(back.loop.safety.max_force, 2.5);  // the loop's limit follows the device
    QCOMPARE(back.loop.safety.passivity, false);
    QCOMPARE(back.finger_map[0], 0);
  }

  void configErrorsNameFileAndField() {
    using namespace palpation::app::live;
    auto expect = [](const std::string& text, const std::string& needle) {
      try {
        parse_device_config(text, "dev.json");
        QFAIL(qPrintable(QString::fromStdString("accepted: " + text)));
      } catch (const palpation::sim::ScenarioError& e) {
        const std::string m = e.what();
        QVERIFY2(m.rfind("dev.json: ", 0) == 0 && m.find(needle) != std::string::npos, e.what());
        QVERIFY(m.find('\n') == std::string::npos);
      }
    };
    expect("{", "(syntax): malformed JSON");
    expect(R"({"capabilities": {"max_forse": 3}})", "capabilities.max_forse: unknown key");
    expect(R"({"capabilities": {"max_force": -1}})", "capabilities.max_force: must be > 0");
    expect(R"({"capabilities": {"max_force": 10}})", "capabilities.release_force");
    expect(R"({"link": {"robot_address": "robot.local"}})", "link.robot_address");
    expect(R"({"link": {"robot_port": 70000}})", "link.robot_port");
    expect(R"({"finger_map": [1, 1, 2, 3, 4]})", "finger_map");
    expect(R"({"registration": {"rotation": [[1,0,0],[0,1,0],[0,0,-1]]}})", "registration.rotation");
    expect(R"({"arm": {"joints": [{}, {}, {}]}})", "arm.joints");
    expect(R"({"fingers": [{}, {}, {}, {}, {"joints": [{}, {}, {"limits": [1, 0]}]}]})", "fingers[4].joints[2].limits");
    // Comments are allowed.
    parse_device_config(R"({"_note": "hello", "capabilities": {"_why": "test"}})", "dev.json");
  }
};

QTEST_APPLESS_MAIN(TestHandHiroModel)
#include "tst_handhiro_model.moc"
