#include "simulated_hand.h"

namespace palpation::device {

SimulatedHand::SimulatedHand(HandScript script, DeviceCapabilities caps) : ScriptedDevice(std::move(script), caps) {
  set_looped(true);
}

bool SimulatedHand::read(std::int64_t now_ns, DeviceState& state) {
  const double dt = prev_ns_ > 0 ? double(now_ns - prev_ns_) * 1e-9 : 0.0;
  prev_ns_ = now_ns;
  if (mode() == Mode::Script) {
    if (restart_.exchange(false, std::memory_order_acq_rel)) restart_clock();
    const bool ok = ScriptedDevice::read(now_ns, state);
    for (int f = 0; f < kMaxFingers; ++f)
      if (state.fingers[f].present) last_pos_[f] = state.fingers[f].position;
    return ok;
  }
  targets_.update();
  const Targets& tg = targets_.read();
  for (int f = 0; f < kMaxFingers; ++f) {
    FingerState& fs = state.fingers[f];
    fs.present = tg.present[f];
    if (fs.present) {
      const Vec3 p = tg.position[f];
      fs.position = p;
      fs.velocity = dt > 0 ? (p - last_pos_[f]) * (1.0 / dt) : Vec3{};
      last_pos_[f] = p;
    }
    fs.attached = fs.present;
    fs.torque_limited = false;
  }
  return stamp(now_ns, state);
}

}  // namespace palpation::device
