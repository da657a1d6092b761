#include "handhiro_robot.h"

#include <algorithm>
#include <cmath>

namespace palpation::device {

HandHiroRobot::HandHiroRobot(const HandHiroParams& params, HandScript script, bool rigid_hand)
    : kin_(params), script_(std::move(script)), rigid_(rigid_hand) {
  const JointVector q0 = kin_.neutral();
  neutral_palm_ = kin_.palm(q0);
  for (int f = 0; f < kMaxFingers; ++f)
    neutral_offset_[f] = neutral_palm_.rotation.transposed() * (kin_.fingertip(q0, f) - neutral_palm_.position);
  reset();
}

void HandHiroRobot::reset() {
  q_ = kin_.neutral();
  c_ = {};
  first_ = true;
  for (auto& f : fingers_) f = Finger{};
}

void HandHiroRobot::targets(double t, std::array<Vec3, kMaxFingers>& p, std::array<Vec3, kMaxFingers>& v, Pose& palm) const {
  // The palm follows the driven fingertips (fixed orientation: palm down, fingers +x).
  palm.rotation = Mat3::identity();
  Vec3 sum, vsum;
  int n = 0;
  for (int f = 0; f < kMaxFingers; ++f) {
    Vec3 pf, vf;
    if (script_.sample(t, f, pf, vf)) {
      p[f] = pf;
      v[f] = vf;
      sum += pf - palm.rotation * neutral_offset_[f];
      vsum += vf;
      ++n;
    }
  }
  palm.position = n > 0 ? sum * (1.0 / n) : neutral_palm_.position;
  const Vec3 palm_v = n > 0 ? vsum * (1.0 / n) : Vec3{};
  for (int f = 0; f < kMaxFingers; ++f)
    if (!script_.driven(f)) {
      p[f] = palm.position + palm.rotation * neutral_offset_[f];
      v[f] = palm_v;
    }
}

void HandHiroRobot::force_release(int f, double t) {
  if (!fingers_[f].attached) return;
  fingers_[f].attached = false;
  fingers_[f].released_at = t;
  ++c_.releases;
}

void HandHiroRobot::step(double t, double dt, const std::array<Vec3, kMaxFingers>& command) {
  const HandHiroParams& P = kin_.params();
  std::array<Vec3, kMaxFingers> target_p, target_v;
  Pose palm;
  targets(t, target_p, target_v, palm);
  if (first_) {
    for (int f = 0; f < kMaxFingers; ++f) {
      fingers_[f].user_x = target_p[f];
      fingers_[f].user_v = target_v[f];
    }
    kin_.solve_palm(palm, q_, 100);
  }

  // The controller renders the command through J^T f within the joint torque limits;
  // detached fingertips render nothing.
  std::array<Vec3, kMaxFingers> force{};
  for (int f = 0; f < kMaxFingers; ++f)
    if (fingers_[f].attached && finite(command[f])) force[f] = command[f];
  const auto scale = kin_.limit_forces(q_, force);

  for (int f = 0; f < kMaxFingers; ++f) {
    Finger& s = fingers_[f];
    s.applied = force[f];
    s.torque_limited = scale[f] < 1.0;
    if (s.torque_limited) ++c_.torque_limited;
    c_.max_applied = std::max(c_.max_applied, norm(force[f]));
    // The operator's fingertip.
    const Vec3 v_old = s.user_v;
    if (rigid_ || first_) {
      s.user_x = target_p[f];
      s.user_v = target_v[f];
    } else {
      const UserFingerSpec& u = P.user;
      const Vec3 a = ((target_p[f] - s.user_x) * u.stiffness + (target_v[f] - s.user_v) * u.damping + s.applied) *
                     (1.0 / u.mass);
      s.user_v += a * dt;           // semi-implicit Euler
      s.user_x += s.user_v * dt;
    }
    s.user_a = first_ ? Vec3{} : (s.user_v - v_old) * (1.0 / dt);
    // The magnet joint.
    if (s.attached) {
      const Vec3 load = s.applied - s.user_a * P.tip_mass;
      if (norm(load) > P.capabilities.release_force) force_release(f, t);
    }
  }

  // The robot follows the hand: arm to the palm, fingers to the fingertips.
  if (!kin_.solve_palm(palm, q_, 30)) ++c_.ik_misses;
  for (int f = 0; f < kMaxFingers; ++f) {
    Finger& s = fingers_[f];
    Vec3 goal = s.user_x;
    if (!s.attached) {
      goal = s.tip;  // hold
      if (s.released_at >= 0 && t - s.released_at >= P.reattach_delay) {
        const Vec3 d = s.user_x - s.tip;
        const double dn = norm(d), reach = P.reattach_speed * dt;
        goal = dn > reach ? s.tip + d * (reach / dn) : s.user_x;
        if (norm(s.user_x - goal) < P.reattach_distance) {
          s.attached = true;
          s.released_at = -1;
          ++c_.reattaches;
        }
      }
    }
    const bool ok = kin_.solve_finger(f, goal, q_, 30, 1e-7);
    const Vec3 tip = kin_.fingertip(q_, f);
    s.joint_limit = kin_.at_limit(q_, f) || kin_.at_limit(q_, -1);
    if (!ok && norm(tip - goal) > 1e-3) ++c_.ik_misses;
    s.tip_v = first_ ? target_v[f] : (tip - s.tip) * (1.0 / dt);
    s.tip = tip;
  }
  first_ = false;
  ++c_.steps;
}

void HandHiroRobot::fill(protocol::StatePacket& p) const {
  p.finger_count = kMaxFingers;
  for (int f = 0; f < kMaxFingers; ++f) {
    const Finger& s = fingers_[f];
    auto& o = p.fingers[f];
    o.position = s.tip;
    o.velocity = s.tip_v;
    o.applied_force = s.applied;
    o.flags = protocol::kFingerPresent;
    if (s.attached) o.flags |= protocol::kFingerAttached;
    if (s.torque_limited) o.flags |= protocol::kFingerTorqueLimited;
    if (s.joint_limit) o.flags |= protocol::kFingerJointLimit;
  }
  for (int j = 0; j < kJoints; ++j) p.joints[j] = float(q_[j]);
}

}  // namespace palpation::device
