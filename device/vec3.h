// Small fixed-size vector and matrix types for the device layer (standard library only:
// design.md section 2 keeps Eigen out of device/). Plain aggregates, no allocation.
#pragma once

#include <array>
#include <cmath>

namespace palpation::device {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3& operator+=(const Vec3& b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
  friend constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
  friend constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
  friend constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
  friend constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline bool finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

/// Row-major 3 x 3 matrix.
struct Mat3 {
  std::array<double, 9> m{0, 0, 0, 0, 0, 0, 0, 0, 0};

  static constexpr Mat3 identity() { return Mat3{{1, 0, 0, 0, 1, 0, 0, 0, 1}}; }
  constexpr double& operator()(int r, int c) { return m[3 * r + c]; }
  constexpr double operator()(int r, int c) const { return m[3 * r + c]; }
  friend constexpr Vec3 operator*(const Mat3& a, const Vec3& v) {
    return {a.m[0] * v.x + a.m[1] * v.y + a.m[2] * v.z, a.m[3] * v.x + a.m[4] * v.y + a.m[5] * v.z,
            a.m[6] * v.x + a.m[7] * v.y + a.m[8] * v.z};
  }
  friend constexpr Mat3 operator*(const Mat3& a, const Mat3& b) {
    Mat3 c;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int j = 0; j < 3; ++j) s += a(r, j) * b(j, k);
        c(r, k) = s;
      }
    return c;
  }
  friend constexpr Mat3 operator*(Mat3 a, double s) {
    for (double& v : a.m) v *= s;
    return a;
  }
  friend constexpr Mat3 operator+(Mat3 a, const Mat3& b) {
    for (int i = 0; i < 9; ++i) a.m[i] += b.m[i];
    return a;
  }
  constexpr Mat3 transposed() const {
    return Mat3{{m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]}};
  }
  friend constexpr bool operator==(const Mat3&, const Mat3&) = default;
};

inline double frobenius(const Mat3& a) {
  double s = 0;
  for (double v : a.m) s += v * v;
  return std::sqrt(s);
}
inline bool finite(const Mat3& a) {
  for (double v : a.m)
    if (!std::isfinite(v)) return false;
  return true;
}

/// Rotation by `angle` (rad) about the unit `axis` (Rodrigues).
inline Mat3 axis_angle(const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  return Mat3{{t * x * x + c, t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
               t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c}};
}

/// Rotation vector (axis * angle) of a rotation matrix: the log map, for orientation errors.
inline Vec3 rotation_vector(const Mat3& r) {
  const double tr = r.m[0] + r.m[4] + r.m[8];
  const double c = std::fmax(-1.0, std::fmin(1.0, 0.5 * (tr - 1)));
  const double angle = std::acos(c);
  const Vec3 w{r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1)};
  if (angle < 1e-9) return w * 0.5;
  const double s = std::sin(angle);
  if (s > 1e-6) return w * (angle / (2 * s));
  // Near pi: axis from the symmetric part.
  Vec3 axis{std::sqrt(std::fmax(0.0, 0.5 * (r(0, 0) + 1))), std::sqrt(std::fmax(0.0, 0.5 * (r(1, 1) + 1))),
            std::sqrt(std::fmax(0.0, 0.5 * (r(2, 2) + 1)))};
  if (r(0, 1) < 0) axis.y = -axis.y;
  if (r(0, 2) < 0) axis.z = -axis.z;
  return axis * angle;
}

/// A rigid frame: maps coordinates between two frames, p_out = rotation * (p_in - origin).
/// Used for the registration between the device frame and the simulation's world frame.
struct RigidFrame {
  Mat3 rotation = Mat3::identity();  // device -> world axes
  Vec3 origin;                       // world origin, in device coordinates, m
  Vec3 to_world(const Vec3& device_point) const { return rotation * (device_point - origin); }
  Vec3 to_device(const Vec3& world_point) const { return rotation.transposed() * world_point + origin; }
  Vec3 vector_to_world(const Vec3& v) const { return rotation * v; }
  Vec3 vector_to_device(const Vec3& v) const { return rotation.transposed() * v; }
  /// A stiffness (or any rank-2 tensor) from world to device axes: R^T K R.
  Mat3 tensor_to_device(const Mat3& k) const { return rotation.transposed() * k * rotation; }
};

}  // namespace palpation::device
