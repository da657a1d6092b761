// Replay of a session recording (docs/recording.md): the recorded patient and settings
// re-simulated from the recorded device input (fingertip positions at 1 kHz), headless
// and deterministic, compared with the forces recorded.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "live/headless_run.h"
#include "store/recording.h"
#include "scenario.h"

namespace palpation::app::review {

using live::RunResult;
using store::Recording;

struct ReplayOptions {
  std::string backend;        // non-empty: override the recorded backend (the difference is then expected)
  bool progress = false;
  sim::LogFn log;
};

struct ReplayResult {
  RunResult run;              // samples in fingers.csv order, summary
  double max_force_diff = 0;  // N, largest |f_replay - f_recorded| over ticks and fingers
  double max_diff_t = 0;      // s, where
  int max_diff_finger = 0;
  double max_recorded_force = 0;  // N, for scale
  std::size_t compared = 0;       // finger ticks compared
};

/// The scenario a recording was made with, its finger paths replaced by the recorded
/// device input. Throws sim::ScenarioError naming the recording's header field.
sim::Scenario replay_scenario(const Recording& rec);

/// Re-simulates and compares. Throws sim::ScenarioError / std::runtime_error.
ReplayResult replay_recording(const Recording& rec, const ReplayOptions& opt);

}  // namespace palpation::app::review
