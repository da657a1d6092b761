// The simulation thread's side of the device hand-off, shared by the headless session
// (session.cpp) and the workstation (workstation.cpp): the simulated fingertips from the
// haptic loop's newest poses, and the contact models published back.
#pragma once

#include <array>

#include <Eigen/Core>

#include "contact_model.h"
#include "device_bridge.h"
#include "haptic_loop.h"
#include "params.h"

namespace palpation::app {

/// One simulated fingertip from device finger `d` of a pose frame. With the virtual
/// coupling (kc > 0) the proxy balanced against `last` (the newest contact model this
/// thread published, device frame) at the newest device position; with direct coupling
/// the device's fingertip. Its velocity: the proxy's since the previous step (`since` s).
/// A detached fingertip or a lost link touches nothing.
inline void finger_from_pose(const device::PoseFrame& pf, int d, const device::FingerContactModel& last, double kc,
                             const device::RigidFrame& reg, double since, sim::FingerInput& in) {
  const device::FingerState& fs = pf.fingers[d];
  const device::Vec3 xd = kc > 0 ? device::couple(last, fs.position, kc).proxy : fs.position;
  const bool ok = device::finite(xd) && device::finite(fs.velocity);
  const Eigen::Vector3d x = to_eigen(reg.to_world(ok ? xd : device::Vec3{}));
  in.velocity = (since > 0 && in.active && ok) ? Eigen::Vector3d((x - in.position) / since)
                                               : to_eigen(reg.vector_to_world(ok ? fs.velocity : device::Vec3{}));
  in.position = x;
  in.active = ok && fs.present && fs.attached && pf.connected;
}

}  // namespace palpation::app
