// The robot side of HandHIRO, emulated: the operator's hand (a scripted path, each
// fingertip a mass on a spring-damper to it unless `rigid_hand`), the robot following
// it (arm IK to the palm, finger IK to the fingertips, FK back to the reported
// positions), the controller's rendering of fingertip forces through J^T f with joint
// torque limits, and the magnet joints that come off above the release force.
//
// Magnet joint: the joint carries the rendered force and accelerates the robot's distal
// mass with the finger, so its load is |F_applied - tip_mass * a_finger|. Above
// release_force it opens: that finger gets no force and the robot fingertip holds where
// it was. After reattach_delay the robot moves its fingertip to the operator's finger
// (reattach_speed) and the joint closes within reattach_distance (the user reconnects).
#pragma once

#include <array>
#include <cstdint>

#include "hand_script.h"
#include "handhiro_model.h"
#include "handhiro_protocol.h"

namespace palpation::device {

struct RobotCounters {
  std::uint64_t steps = 0;
  std::uint64_t releases = 0;
  std::uint64_t reattaches = 0;
  std::uint64_t torque_limited = 0;   // finger-steps scaled by the joint torque limits
  std::uint64_t ik_misses = 0;        // finger-steps the robot could not follow (reach/limits)
  double max_applied = 0;             // N, largest force rendered to a fingertip
};

class HandHiroRobot {
 public:
  HandHiroRobot(const HandHiroParams& params, HandScript script, bool rigid_hand);
  void reset();

  /// Advances to script time t by dt with the controller's force command (device frame,
  /// N, already clamped and gained by the controller).
  void step(double t, double dt, const std::array<Vec3, kMaxFingers>& command);
  /// Writes fingers, joints and flags into a state packet (header/status untouched).
  void fill(protocol::StatePacket& p) const;

  struct Finger {
    Vec3 user_x, user_v, user_a;   // operator's fingertip
    Vec3 tip, tip_v;               // robot fingertip (FK)
    Vec3 applied;                  // force rendered on the finger, N
    bool attached = true;
    bool torque_limited = false, joint_limit = false;
    double released_at = -1;
  };
  const Finger& finger(int f) const { return fingers_[f]; }
  const JointVector& joints() const { return q_; }
  const RobotCounters& counters() const { return c_; }
  const HandHiroKinematics& kinematics() const { return kin_; }
  const HandScript& script() const { return script_; }
  /// Opens a magnet joint now (tests: the operator pulls a finger off).
  void force_release(int f, double t);

 private:
  void targets(double t, std::array<Vec3, kMaxFingers>& p, std::array<Vec3, kMaxFingers>& v, Pose& palm) const;
  HandHiroKinematics kin_;
  HandScript script_;
  bool rigid_;
  JointVector q_{};
  std::array<Finger, kMaxFingers> fingers_{};
  std::array<Vec3, kMaxFingers> neutral_offset_{};  // fingertip from palm at the neutral pose, palm axes
  Pose neutral_palm_;
  RobotCounters c_;
  bool first_ = true;
};

}  // namespace palpation::device
