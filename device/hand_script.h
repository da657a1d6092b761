// Where the operator's fingertips want to be over time: keyframe paths per device finger
// (device frame, linear in between, held outside). Built from a scenario's finger paths
// or from a recorded session (fingers.csv); drives the emulator and the scripted/replay
// devices. Built before a session starts; sample() never allocates.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "haptic_device.h"
#include "vec3.h"

namespace palpation::device {

struct PathKey {
  double t = 0;   // s
  Vec3 p;         // m
};

class HandScript {
 public:
  /// Keys must have increasing t (checked: throws std::invalid_argument).
  void set_path(int finger, std::vector<PathKey> keys);
  bool driven(int finger) const { return finger >= 0 && finger < kMaxFingers && !paths_[finger].empty(); }
  int driven_count() const;
  /// Position and velocity at time t. False (outputs untouched) for an undriven finger.
  bool sample(double t, int finger, Vec3& position, Vec3& velocity) const;
  /// Time of the last key over all fingers, s.
  double duration() const;

 private:
  std::array<std::vector<PathKey>, kMaxFingers> paths_{};
};

/// A recorded session's fingers.csv (header t,finger,x,y,z,fx,fy,fz): per recorded finger
/// index, its positions as keys (the file's frame, usually the simulation's world frame).
/// Throws std::runtime_error("FILE: line N: reason") on a malformed file.
std::vector<std::vector<PathKey>> load_fingers_csv(const std::string& path);

}  // namespace palpation::device
