#include "scripted_device.h"

#include <cmath>
#include <stdexcept>

namespace palpation::device {

ScriptedDevice::ScriptedDevice(HandScript script, DeviceCapabilities caps) : script_(std::move(script)), caps_(caps) {}

bool ScriptedDevice::read(std::int64_t now_ns, DeviceState& state) {
  if (!started_) {
    started_ = true;
    t0_ = now_ns;
  }
  double t = double(now_ns - t0_) * 1e-9;
  if (looped_ && script_.duration() > 0) t = std::fmod(t, script_.duration());
  for (int f = 0; f < kMaxFingers; ++f) {
    FingerState& fs = state.fingers[f];
    Vec3 p, v;
    fs.present = script_.sample(t, f, p, v);
    if (fs.present) {
      fs.position = override_[f] ? override_pos_[f] : p;
      fs.velocity = v;
    }
    fs.attached = fs.present && !detached_[f];
    fs.torque_limited = false;
  }
  return stamp(now_ns, state);
}

bool ScriptedDevice::stamp(std::int64_t now_ns, DeviceState& state) {
  state.device_time_ns = now_ns;
  state.received_ns = now_ns;
  state.sequence = ++seq_;
  state.connected = connected_;
  state.device_watchdog = false;
  return connected_;
}

void ScriptedDevice::write(std::int64_t, const ForceCommand& command) {
  ++rx_.writes;
  bool bad = false;
  for (int f = 0; f < kMaxFingers; ++f) {
    const Vec3& F = command.force[f];
    if (!finite(F)) {
      bad = true;
      continue;
    }
    const double n = norm(F);
    rx_.max_force = std::max(rx_.max_force, n);
    if (n > caps_.max_force) ++rx_.over_limit;
  }
  if (bad) ++rx_.nonfinite;
  rx_.last = command;
}

namespace {
HandScript replay_script(const std::string& csv, const RigidFrame& reg, const std::array<int, kMaxFingers>& map) {
  auto rec = load_fingers_csv(csv);
  HandScript s;
  for (std::size_t k = 0; k < rec.size() && k < std::size_t(kMaxFingers); ++k) {
    if (rec[k].empty()) continue;
    const int f = map[k];
    if (f < 0 || f >= kMaxFingers) throw std::runtime_error(csv + ": recorded finger " + std::to_string(k) + " has no device finger");
    for (auto& key : rec[k]) key.p = reg.to_device(key.p);
    s.set_path(f, std::move(rec[k]));
  }
  return s;
}
}  // namespace

ReplayDevice::ReplayDevice(const std::string& fingers_csv, const RigidFrame& registration,
                           const std::array<int, kMaxFingers>& map, DeviceCapabilities caps)
    : ScriptedDevice(replay_script(fingers_csv, registration, map), caps) {}

}  // namespace palpation::device
