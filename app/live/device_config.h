// The device configuration file (resources/handhiro.json): the HandHIRO model, its
// limits, the registration to the simulation's world frame, the UDP link and the haptic
// loop's safety settings. Every key is optional (the built-in defaults are the file's
// values); unknown keys are an error; keys starting with "_" are comments.
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "haptic_loop.h"
#include "live/force_mapping.h"
#include "handhiro_link.h"
#include "handhiro_model.h"

namespace palpation::app::live {

struct DeviceConfig {
  device::HandHiroParams hand = device::default_handhiro_params();
  device::LinkConfig link;
  device::HapticLoopParams loop;
  /// The force scale between simulation and device (live/force_mapping.h): per patient
  /// by default, or fixed.
  ForceMappingConfig force_mapping;
  /// Scenario finger k drives device finger finger_map[k] (default: index, middle, ring,
  /// little, thumb: the paper palpates with the index finger).
  std::array<int, device::kMaxFingers> finger_map{device::kIndex, device::kMiddle, device::kRing, device::kLittle,
                                                  device::kThumb};
  std::string source = "built-in defaults";
};

/// The defaults, with the loop's limits tied to the device capabilities.
DeviceConfig default_device_config();
/// Reads and validates a file. Throws sim::ScenarioError("FILE: FIELD: reason").
DeviceConfig load_device_config(const std::string& path);
DeviceConfig parse_device_config(const std::string& json_text, const std::string& source);
/// The whole configuration as JSON (round-trips through parse_device_config).
nlohmann::json device_config_to_json(const DeviceConfig& c);

}  // namespace palpation::app::live
