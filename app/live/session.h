// A real-time session (design.md section 3), headless: the device (the HandHIRO link to
// the emulator over loopback UDP, or a scripted device), the 1 kHz haptic thread, the
// simulation thread, and a recorder draining the haptic thread's telemetry. Runs for the
// scenario's duration in wall-clock time.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "live/device_config.h"
#include "live/headless_run.h"
#include "scenario.h"

namespace palpation::app::live {

struct SessionOptions {
  std::string device = "emulator";   // "emulator" (UDP to handhiro-emulator) | "scripted" | "replay"
  DeviceConfig config = default_device_config();
  double duration = 0;               // s; <= 0: the scenario's
  int priority = 80;                 // SCHED_FIFO priority of the haptic thread (0: normal)
  bool rigid_hand = false;           // emulator: fingertips follow the path exactly
  std::string recording;             // emulator/replay: drive the hand by this fingers.csv
  std::string emulator_exe;          // non-empty: run handhiro-emulator as a child process
  std::string scenario_arg;          // what the child gets as its scenario (file or built-in name)
  std::string device_config_path;    // what the child gets as --config (may be empty)
  bool sim_realtime = true;          // simulation dt follows the wall clock (else the scenario's dt)
  double sim_max_dt = 0.01;          // s, cap of the real-time dt
  double vibration_from = -1, vibration_to = -1;  // s; window of the vibration figures (default: 2nd half)
  bool progress = false;
  sim::LogFn log;
  /// Called once the simulation is built, before anything starts (fault injection in
  /// tests: replace the backend by a failing one).
  std::function<void(sim::Simulation&)> prepare_simulation;
  std::string record_path;           // non-empty: record the session there (app/store/recording.h)
  nlohmann::json record_settings;    // extra settings for the recording's header (command line, ...)
};

struct SessionResult {
  std::vector<FingerSample> samples;   // what the device received, per tick and scenario finger (world frame)
  nlohmann::json loop;                 // loop.json
  bool ok = true;                      // finite, never above the limit
  nlohmann::json recording;            // path, bytes, ticks, error (when recording)
};

/// Runs a session. Throws sim::ScenarioError (bad input) or std::runtime_error.
SessionResult run_session(const sim::Scenario& s, const SessionOptions& opt);

/// Force oscillation of one finger's fz over [from, to]: fz minus its 31-sample centred
/// moving average (a high-pass with its -3 dB point near 24 Hz at 1 kHz), RMS and
/// peak-to-peak.
struct Vibration {
  double rms = 0, peak_to_peak = 0;
  int samples = 0;
};
Vibration force_vibration(const std::vector<FingerSample>& samples, int finger, double from, double to);

}  // namespace palpation::app::live
