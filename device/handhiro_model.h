// The HandHIRO model (HIRO III: Endo et al.; seed paper section 2.1): a 6-DOF interface
// arm carrying a 15-DOF hand (3 joints per finger), a passive spherical permanent-magnet
// joint at each of the five fingertips.
//
//   arm:    base -> 6 revolute joints (yaw, shoulder pitch, elbow pitch, wrist roll,
//           wrist pitch, wrist yaw) -> palm frame
//   finger: palm -> base point, fixed yaw -> abduction (palm z) -> MCP flexion -> PIP
//           flexion -> fingertip (magnet joint centre)
//
// Each joint frame is T_j = T_{j-1} * Trans(offset_j) * Rot(axis_j, q_j). The fingertip
// Jacobian column of joint j is a_j x (p_tip - p_j) (a_j its world axis, p_j its origin);
// torques for fingertip forces are tau = sum_f J_f^T F_f.
//
// The published figures (link lengths, torque limits, force range, release force) were
// not available: every number here is an approximate, conservative default (?) kept in
// resources/handhiro.json; see docs/handhiro-protocol.md.
#pragma once

#include <array>

#include "haptic_device.h"
#include "handhiro_protocol.h"
#include "vec3.h"

namespace palpation::device {

inline constexpr int kArmJoints = protocol::kArmJoints;        // 6
inline constexpr int kFingerJoints = protocol::kFingerJoints;  // 3
inline constexpr int kJoints = protocol::kJoints;              // 21

struct JointSpec {
  Vec3 offset;                 // from the previous joint frame, m (previous frame's axes)
  Vec3 axis{0, 0, 1};          // unit, in the joint's own frame
  double lower = -3.14159, upper = 3.14159;  // rad
  double max_torque = 1.0;     // N m, the controller's limit
};

struct FingerSpec {
  Vec3 base;                   // in the palm frame, m
  double base_yaw = 0;         // fixed rotation about palm z before the joints, rad
  std::array<JointSpec, kFingerJoints> joints{};
  Vec3 tip;                    // fingertip from the last joint frame, m
  std::array<double, kFingerJoints> neutral{};  // relaxed pose, rad
};

/// The operator's finger as the emulator models it: a mass on a spring-damper to where
/// the hand wants it (the scripted path). Human fingertip impedance, approximate (?).
struct UserFingerSpec {
  double mass = 0.03;          // kg, fingertip + robot distal link
  double stiffness = 800.0;    // N/m
  double damping = 4.0;        // N s/m
};

struct HandHiroParams {
  std::array<JointSpec, kArmJoints> arm{};
  std::array<double, kArmJoints> arm_neutral{};
  Vec3 palm;                   // palm frame origin from the last arm joint frame, m
  std::array<FingerSpec, kMaxFingers> fingers{};
  DeviceCapabilities capabilities;  // force/stiffness limits, release force, workspace
  double tip_mass = 0.02;      // kg, robot distal mass behind each magnet joint
  double reattach_delay = 0.5; // s after a release before the user reconnects
  double reattach_speed = 0.2; // m/s the robot fingertip moves to meet the finger
  double reattach_distance = 0.002;  // m
  double robot_watchdog = 0.05;      // s without commands before the robot ramps forces off
  double robot_ramp = 0.02;          // s, its ramp
  UserFingerSpec user;
  RigidFrame registration;     // device frame <-> simulation world frame
};

/// The built-in defaults (identical to resources/handhiro.json).
HandHiroParams default_handhiro_params();

/// Joint angles: arm 0..5, then finger f at 6 + 3f .. 8 + 3f (the wire order).
using JointVector = std::array<double, kJoints>;

struct Pose {
  Mat3 rotation = Mat3::identity();
  Vec3 position;
};

class HandHiroKinematics {
 public:
  explicit HandHiroKinematics(const HandHiroParams& p) : p_(p) {}
  const HandHiroParams& params() const { return p_; }

  JointVector neutral() const;
  Pose palm(const JointVector& q) const;
  Vec3 fingertip(const JointVector& q, int finger) const;
  /// Columns d(tip)/d(q_j), j = 0..20 (zero for other fingers' joints).
  void fingertip_jacobian(const JointVector& q, int finger, std::array<Vec3, kJoints>& columns) const;
  /// tau = sum_f J_f^T F_f (F_f: force the fingertip applies to the user, device frame).
  void joint_torques(const JointVector& q, const std::array<Vec3, kMaxFingers>& force, JointVector& tau) const;
  /// Scales the forces so that no joint torque exceeds its limit (per finger for the hand
  /// joints, then one common factor for the arm, which carries them all). Direction is
  /// kept. Returns the scale applied to each finger (1 = unlimited).
  std::array<double, kMaxFingers> limit_forces(const JointVector& q, std::array<Vec3, kMaxFingers>& force) const;

  /// Damped-least-squares inverse kinematics from the current `q` (warm start), joint
  /// limits enforced. True when the residual is below `tolerance` (m; rad for the palm
  /// orientation).
  bool solve_palm(const Pose& target, JointVector& q, int iterations = 30, double tolerance = 1e-7) const;
  bool solve_finger(int finger, const Vec3& target, JointVector& q, int iterations = 30, double tolerance = 1e-7) const;
  /// True when any joint of the arm (finger < 0) or of the finger sits at a limit.
  bool at_limit(const JointVector& q, int finger) const;

 private:
  struct ChainPoint {
    Vec3 origin, axis;
  };
  // Arm frames: the six joint origins/axes and the palm pose.
  void arm_chain(const JointVector& q, std::array<ChainPoint, kArmJoints>& joints, Pose& palm) const;
  void finger_chain(const Pose& palm, const JointVector& q, int finger, std::array<ChainPoint, kFingerJoints>& joints,
                    Vec3& tip) const;
  HandHiroParams p_;
};

}  // namespace palpation::device
