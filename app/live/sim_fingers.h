// The simulation thread's side of the device hand-off, shared by the headless session
// (session.cpp) and the workstation (workstation.cpp): the simulated fingertips from the
// haptic loop's newest poses, and the contact models published back.
#pragma once

#include <array>

#include <Eigen/Core>

#include "contact_model.h"
#include "live/device_bridge.h"
#include "haptic_loop.h"
#include "params.h"

namespace palpation::app::live {

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

/// Release/onset spike guard for the force sent to the haptic loop (docs/stability.md,
/// "Force spikes at real-time dt"). At the workstation's real-time dt (up to 10 ms) the
/// simulated contact force chatters with a period of two steps while a fingertip is lifted
/// (surface nodes recoiling into the fingertip within a step, outside that step's contact
/// set, are pushed out in the next) and overshoots on the first step of a contact: single
/// steps 3-5x too high (coarse breast, dt 10 ms: up to 27 N against 6 N at dt 1 ms). The
/// guard sends the smaller of this step's and the previous step's force (a two-step
/// minimum, erosion) with this step's stiffness, position and normal: one-step spikes
/// vanish, falling forces pass at once, rising ones a step late (the local stiffness still
/// renders the motion in between). `prev`: the previous step's simulated force of this
/// finger (zero when it had no contact). Returns the output to build the contact model of.
inline sim::FingerOutput guard_force_spike(const sim::FingerOutput& now, const Eigen::Vector3d& prev) {
  sim::FingerOutput o = now;
  if (prev.squaredNorm() < now.force.squaredNorm()) o.force = prev;
  return o;
}

}  // namespace palpation::app::live
