// sim <-> device: the two libraries never include each other (design.md section 2); this
// is where their types meet. The device works in its own frame, the simulation in the
// world frame; the registration (resources/handhiro.json) maps between them.
#pragma once

#include <array>
#include <stdexcept>

#include <Eigen/Core>

#include "contact_model.h"
#include "hand_script.h"
#include "haptic_loop.h"
#include "params.h"
#include "scenario.h"
#include "vec3.h"

namespace palpation::app::live {

inline device::Vec3 to_dev(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d to_eigen(const device::Vec3& v) { return {v.x, v.y, v.z}; }
inline device::Mat3 to_dev(const Eigen::Matrix3d& m) {
  device::Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r(i, k) = m(i, k);
  return r;
}

/// The local contact model of one finger, from a simulation step (world frame, simulated
/// force) to the device (device frame, device force). `x0_world` is the finger position
/// the step used; `force_scale` the device force per simulated force
/// (app/live/force_mapping.h): force and stiffness both scale, so the model renders
/// s * F_sim at every position.
inline device::FingerContactModel contact_model(const sim::FingerOutput& o, const Eigen::Vector3d& x0_world,
                                                const device::RigidFrame& reg, double force_scale = 1.0) {
  device::FingerContactModel m;
  m.valid = true;
  m.contacts = o.contacts;
  m.force = reg.vector_to_device(to_dev(o.force)) * force_scale;
  m.stiffness = reg.tensor_to_device(to_dev(o.stiffness)) * force_scale;
  m.position = reg.to_device(to_dev(x0_world));
  m.contact_point = reg.to_device(to_dev(o.contact_point));
  m.normal = reg.vector_to_device(to_dev(o.normal));
  return m;
}

/// The spacing of the keys a scripted hand gets from a path that is not linear: the haptic
/// tick, so the device's linear follower samples the path itself at every tick.
inline const double kScriptKeyStep = device::HapticLoopParams{}.period;

/// A finger path as the device's keys (device frame, through the registration):
/// device::HandScript follows keys linearly, and device/ does not include sim/, so a
/// curved path arrives sampled (sim::FingerPath::linear_keys).
inline std::vector<device::PathKey> device_keys(const sim::FingerPath& path, const device::RigidFrame& reg) {
  std::vector<device::PathKey> keys;
  const auto world = path.linear_keys(kScriptKeyStep);
  keys.reserve(world.size());
  for (const auto& key : world) keys.push_back({key[0], reg.to_device({key[1], key[2], key[3]})});
  return keys;
}

/// The operator's hand from the scenario's finger paths: finger k drives device finger
/// map[k], positions through the registration.
inline device::HandScript script_from_scenario(const sim::Scenario& s, const device::RigidFrame& reg,
                                               const std::array<int, device::kMaxFingers>& map) {
  if (s.fingers.size() > std::size_t(device::kMaxFingers))
    throw sim::ScenarioError(s.source + ": fingers: at most 5 (the device has five), got " + std::to_string(s.fingers.size()));
  device::HandScript script;
  for (std::size_t k = 0; k < s.fingers.size(); ++k) {
    std::vector<device::PathKey> keys = device_keys(s.fingers[k], reg);
    if (keys.empty()) throw sim::ScenarioError(s.source + ": fingers[" + std::to_string(k) + "].path: no keys");
    script.set_path(map[k], std::move(keys));
  }
  return script;
}

}  // namespace palpation::app::live
