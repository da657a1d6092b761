#include "handhiro_model.h"

#include <algorithm>
#include <cmath>

namespace palpation::device {

namespace {

// Solves A x = b (n x n, row-major) by Gaussian elimination with partial pivoting, in
// place. Small fixed sizes only (3 and 6): no allocation.
template <int N>
bool solve_dense(std::array<double, N * N>& a, std::array<double, N>& b) {
  for (int c = 0; c < N; ++c) {
    int piv = c;
    for (int r = c + 1; r < N; ++r)
      if (std::fabs(a[r * N + c]) > std::fabs(a[piv * N + c])) piv = r;
    if (std::fabs(a[piv * N + c]) < 1e-300) return false;
    if (piv != c) {
      for (int k = 0; k < N; ++k) std::swap(a[c * N + k], a[piv * N + k]);
      std::swap(b[c], b[piv]);
    }
    for (int r = c + 1; r < N; ++r) {
      const double f = a[r * N + c] / a[c * N + c];
      for (int k = c; k < N; ++k) a[r * N + k] -= f * a[c * N + k];
      b[r] -= f * b[c];
    }
  }
  for (int r = N - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < N; ++k) s -= a[r * N + k] * b[k];
    b[r] = s / a[r * N + r];
  }
  return true;
}

struct Frame {
  Mat3 r = Mat3::identity();
  Vec3 p;
  // T * Trans(offset)
  void translate(const Vec3& offset) { p += r * offset; }
  void rotate(const Vec3& axis, double angle) { r = r * axis_angle(axis, angle); }
};

JointSpec joint(Vec3 offset, Vec3 axis, double lo, double hi, double torque) {
  JointSpec j;
  j.offset = offset;
  j.axis = axis;
  j.lower = lo;
  j.upper = hi;
  j.max_torque = torque;
  return j;
}

}  // namespace

HandHiroParams default_handhiro_params() {
  HandHiroParams p;
  const Vec3 X{1, 0, 0}, Y{0, 1, 0}, Z{0, 0, 1};
  // Arm: shoulder 0.30 m above the base, upper arm 0.30 m, forearm 0.28 m, wrist axes
  // intersecting; palm centre 0.04 m ahead of the wrist.
  p.arm = {joint({0, 0, 0}, Z, -2.6, 2.6, 40.0), joint({0, 0, 0.30}, Y, -1.8, 1.8, 40.0),
           joint({0.30, 0, 0}, Y, -2.6, 2.6, 25.0), joint({0.28, 0, 0}, X, -2.6, 2.6, 6.0),
           joint({0, 0, 0}, Y, -1.7, 1.7, 6.0), joint({0, 0, 0}, Z, -2.6, 2.6, 6.0)};
  p.arm_neutral = {0.0, -0.2, 1.0, 0.0, -0.8, 0.0};
  p.palm = {0.04, 0, 0};
  // Right hand, palm down: palm x toward the fingers, y toward the thumb, z up.
  struct F {
    Vec3 base;
    double yaw, l1, l2, abd;
  };
  const F f[kMaxFingers] = {{{0.000, 0.045, -0.010}, 0.9, 0.040, 0.035, 0.6},
                            {{0.035, 0.025, 0.0}, 0.05, 0.045, 0.040, 0.35},
                            {{0.040, 0.005, 0.0}, 0.0, 0.048, 0.042, 0.35},
                            {{0.035, -0.015, 0.0}, -0.05, 0.045, 0.040, 0.35},
                            {{0.030, -0.035, 0.0}, -0.10, 0.038, 0.034, 0.35}};
  for (int i = 0; i < kMaxFingers; ++i) {
    FingerSpec& s = p.fingers[i];
    s.base = f[i].base;
    s.base_yaw = f[i].yaw;
    s.joints = {joint({0, 0, 0}, Z, -f[i].abd, f[i].abd, 0.4), joint({0, 0, 0}, Y, -0.4, 1.6, 0.6),
                joint({f[i].l1, 0, 0}, Y, 0.0, 1.9, 0.35)};
    s.tip = {f[i].l2, 0, 0};
    s.neutral = {0.0, 0.5, 0.7};
  }
  p.registration.origin = {0.40, 0.0, 0.0};
  return p;
}

JointVector HandHiroKinematics::neutral() const {
  JointVector q{};
  for (int j = 0; j < kArmJoints; ++j) q[j] = p_.arm_neutral[j];
  for (int f = 0; f < kMaxFingers; ++f)
    for (int j = 0; j < kFingerJoints; ++j) q[kArmJoints + 3 * f + j] = p_.fingers[f].neutral[j];
  return q;
}

void HandHiroKinematics::arm_chain(const JointVector& q, std::array<ChainPoint, kArmJoints>& joints, Pose& palm) const {
  Frame t;
  for (int j = 0; j < kArmJoints; ++j) {
    t.translate(p_.arm[j].offset);
    joints[j] = {t.p, t.r * p_.arm[j].axis};
    t.rotate(p_.arm[j].axis, q[j]);
  }
  t.translate(p_.palm);
  palm.rotation = t.r;
  palm.position = t.p;
}

void HandHiroKinematics::finger_chain(const Pose& palm, const JointVector& q, int finger,
                                      std::array<ChainPoint, kFingerJoints>& joints, Vec3& tip) const {
  const FingerSpec& s = p_.fingers[finger];
  Frame t{palm.rotation, palm.position};
  t.translate(s.base);
  t.rotate({0, 0, 1}, s.base_yaw);
  for (int j = 0; j < kFingerJoints; ++j) {
    t.translate(s.joints[j].offset);
    joints[j] = {t.p, t.r * s.joints[j].axis};
    t.rotate(s.joints[j].axis, q[kArmJoints + 3 * finger + j]);
  }
  t.translate(s.tip);
  tip = t.p;
}

Pose HandHiroKinematics::palm(const JointVector& q) const {
  std::array<ChainPoint, kArmJoints> a;
  Pose palm;
  arm_chain(q, a, palm);
  return palm;
}

Vec3 HandHiroKinematics::fingertip(const JointVector& q, int finger) const {
  std::array<ChainPoint, kArmJoints> a;
  std::array<ChainPoint, kFingerJoints> fj;
  Pose palm;
  Vec3 tip;
  arm_chain(q, a, palm);
  finger_chain(palm, q, finger, fj, tip);
  return tip;
}

void HandHiroKinematics::fingertip_jacobian(const JointVector& q, int finger, std::array<Vec3, kJoints>& columns) const {
  std::array<ChainPoint, kArmJoints> a;
  std::array<ChainPoint, kFingerJoints> fj;
  Pose palm;
  Vec3 tip;
  arm_chain(q, a, palm);
  finger_chain(palm, q, finger, fj, tip);
  columns.fill(Vec3{});
  for (int j = 0; j < kArmJoints; ++j) columns[j] = cross(a[j].axis, tip - a[j].origin);
  for (int j = 0; j < kFingerJoints; ++j) columns[kArmJoints + 3 * finger + j] = cross(fj[j].axis, tip - fj[j].origin);
}

void HandHiroKinematics::joint_torques(const JointVector& q, const std::array<Vec3, kMaxFingers>& force, JointVector& tau) const {
  tau.fill(0.0);
  std::array<Vec3, kJoints> cols;
  for (int f = 0; f < kMaxFingers; ++f) {
    if (dot(force[f], force[f]) == 0) continue;
    fingertip_jacobian(q, f, cols);
    for (int j = 0; j < kJoints; ++j) tau[j] += dot(cols[j], force[f]);
  }
}

std::array<double, kMaxFingers> HandHiroKinematics::limit_forces(const JointVector& q, std::array<Vec3, kMaxFingers>& force) const {
  std::array<double, kMaxFingers> scale;
  scale.fill(1.0);
  JointVector tau;
  joint_torques(q, force, tau);
  for (int f = 0; f < kMaxFingers; ++f) {
    for (int j = 0; j < kFingerJoints; ++j) {
      const double t = std::fabs(tau[kArmJoints + 3 * f + j]);
      const double lim = p_.fingers[f].joints[j].max_torque;
      if (t > lim) scale[f] = std::min(scale[f], lim / t);
    }
    force[f] *= scale[f];
  }
  joint_torques(q, force, tau);
  double arm_scale = 1.0;
  for (int j = 0; j < kArmJoints; ++j) {
    const double t = std::fabs(tau[j]);
    if (t > p_.arm[j].max_torque) arm_scale = std::min(arm_scale, p_.arm[j].max_torque / t);
  }
  if (arm_scale < 1.0)
    for (int f = 0; f < kMaxFingers; ++f) {
      force[f] *= arm_scale;
      scale[f] *= arm_scale;
    }
  return scale;
}

bool HandHiroKinematics::solve_palm(const Pose& target, JointVector& q, int iterations, double tolerance) const {
  constexpr double lambda2 = 1e-4;  // damping (m^2): robust near singularities
  for (int it = 0; it < iterations; ++it) {
    std::array<ChainPoint, kArmJoints> a;
    Pose palm;
    arm_chain(q, a, palm);
    const Vec3 ep = target.position - palm.position;
    const Vec3 eo = rotation_vector(target.rotation * palm.rotation.transposed());
    const std::array<double, 6> e{ep.x, ep.y, ep.z, eo.x, eo.y, eo.z};
    double en = 0;
    for (double v : e) en = std::max(en, std::fabs(v));
    if (en < tolerance) return true;
    // J (6 x 6): rows position (a x (p - o)), orientation (a).
    std::array<std::array<double, 6>, 6> jac{};
    for (int j = 0; j < kArmJoints; ++j) {
      const Vec3 lin = cross(a[j].axis, palm.position - a[j].origin);
      for (int k = 0; k < 3; ++k) {
        jac[k][j] = lin[k];
        jac[3 + k][j] = a[j].axis[k];
      }
    }
    std::array<double, 36> m{};
    std::array<double, 6> y = e;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        double s = 0;
        for (int j = 0; j < 6; ++j) s += jac[r][j] * jac[c][j];
        m[r * 6 + c] = s + (r == c ? lambda2 : 0.0);
      }
    if (!solve_dense<6>(m, y)) return false;
    for (int j = 0; j < kArmJoints; ++j) {
      double d = 0;
      for (int r = 0; r < 6; ++r) d += jac[r][j] * y[r];
      d = std::clamp(d, -0.5, 0.5);  // trust region, rad per iteration
      q[j] = std::clamp(q[j] + d, p_.arm[j].lower, p_.arm[j].upper);
    }
  }
  const Pose palm = this->palm(q);
  return norm(target.position - palm.position) < tolerance * 10 &&
         norm(rotation_vector(target.rotation * palm.rotation.transposed())) < tolerance * 10;
}

bool HandHiroKinematics::solve_finger(int finger, const Vec3& target, JointVector& q, int iterations, double tolerance) const {
  constexpr double lambda2 = 1e-6;
  std::array<ChainPoint, kArmJoints> a;
  Pose palm;
  arm_chain(q, a, palm);
  for (int it = 0; it <= iterations; ++it) {
    std::array<ChainPoint, kFingerJoints> fj;
    Vec3 tip;
    finger_chain(palm, q, finger, fj, tip);
    const Vec3 e = target - tip;
    if (norm(e) < tolerance) return true;
    if (it == iterations) break;
    std::array<Vec3, kFingerJoints> col;
    for (int j = 0; j < kFingerJoints; ++j) col[j] = cross(fj[j].axis, tip - fj[j].origin);
    std::array<double, 9> m{};
    std::array<double, 3> y{e.x, e.y, e.z};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int j = 0; j < 3; ++j) s += col[j][r] * col[j][c];
        m[r * 3 + c] = s + (r == c ? lambda2 : 0.0);
      }
    if (!solve_dense<3>(m, y)) return false;
    for (int j = 0; j < kFingerJoints; ++j) {
      const double d = std::clamp(col[j].x * y[0] + col[j].y * y[1] + col[j].z * y[2], -0.5, 0.5);
      const JointSpec& s = p_.fingers[finger].joints[j];
      double& qj = q[kArmJoints + 3 * finger + j];
      qj = std::clamp(qj + d, s.lower, s.upper);
    }
  }
  return false;
}

bool HandHiroKinematics::at_limit(const JointVector& q, int finger) const {
  constexpr double eps = 1e-9;
  if (finger < 0) {
    for (int j = 0; j < kArmJoints; ++j)
      if (q[j] <= p_.arm[j].lower + eps || q[j] >= p_.arm[j].upper - eps) return true;
    return false;
  }
  for (int j = 0; j < kFingerJoints; ++j) {
    const JointSpec& s = p_.fingers[finger].joints[j];
    const double v = q[kArmJoints + 3 * finger + j];
    if (v <= s.lower + eps || v >= s.upper - eps) return true;
  }
  return false;
}

}  // namespace palpation::device
