// The workstation's device when no robot is attached: a simulated HandHIRO whose
// fingertips either follow a HandScript in a loop (the hand palpating on its own) or
// targets set by the GUI thread (mouse palpation). Non-blocking and lock-free: the
// targets arrive through a triple buffer, the mode through an atomic.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "scripted_device.h"
#include "triple_buffer.h"

namespace palpation::device {

class SimulatedHand : public ScriptedDevice {
 public:
  enum class Mode { Script, Mouse };
  SimulatedHand(HandScript script, DeviceCapabilities caps);
  std::string name() const override { return "simulated HandHIRO"; }
  bool read(std::int64_t now_ns, DeviceState& state) override;

  void set_mode(Mode m) { mode_.store(int(m), std::memory_order_release); }
  Mode mode() const { return Mode(mode_.load(std::memory_order_acquire)); }
  /// One thread (the GUI) sets where the mouse-driven fingertips should be (device frame).
  struct Targets {
    std::array<Vec3, kMaxFingers> position{};
    std::array<bool, kMaxFingers> present{};
  };
  void set_targets(const Targets& t) { targets_.publish(t); }
  /// Any thread: the script starts over at the next read (the hand begins its palpation
  /// when the simulation is ready, not while a patient loads: a fingertip that is already
  /// deep below the skin at the body's first step is pulled in).
  void restart_script() { restart_.store(true, std::memory_order_release); }

 private:
  std::atomic<int> mode_{0};
  std::atomic<bool> restart_{false};
  TripleBuffer<Targets> targets_;
  std::array<Vec3, kMaxFingers> last_pos_{};
  std::int64_t prev_ns_ = 0;
};

}  // namespace palpation::device
