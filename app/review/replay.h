// Replay of a session recording (docs/recording.md): the recorded patient and settings
// re-simulated headless and deterministic, compared with the forces recorded.
//
// Two kinds of recording, two comparisons, each saying which force it compares:
//  - with steps (the workstation's, version 2): the simulation thread's steps re-run with
//    their recorded dt, fingertip inputs and changes; the re-simulated force of every step
//    against the simulated force the recording kept for it (simulated vs simulated: zero up
//    to rounding on the same backend and thread count). The forces sent at 1 kHz are
//    compared separately: the re-simulated steps through the device's force path as the
//    workstation ran it (the force scale, live/force_mapping.h; the spike guard and the
//    local contact model, live/; the haptic loop with its virtual coupling, fades and
//    safety filter, device/HapticLoop) against the recorded ticks.
//  - without steps (`palpation session`, version 1): the recorded device input (fingertip
//    positions at 1 kHz) as finger paths at the scenario's dt; the forces times the
//    recorded force scale against the forces recorded (sent).
#pragma once

#include <cmath>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

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

/// What a replay compares (ReplayResult::compared_force).
enum class ReplayForce {
  Simulated,  // recorded step forces against re-simulated ones (recordings with steps)
  Sent,       // recorded 1 kHz forces against re-simulated ones times the recorded scale (without steps)
};
/// "simulated", "sent".
const char* replay_force_name(ReplayForce f);

/// The largest difference of one comparison.
struct ForceDiff {
  double max_diff = 0;            // N, largest |f_replay - f_recorded| over samples and fingers
  double at_t = 0;                // s, where
  int finger = 0;
  double max_recorded_force = 0;  // N, for scale
  std::size_t compared = 0;       // finger samples compared
  double sum_sq_diff = 0;         // N^2, sum of |f_replay - f_recorded|^2 (finite ones)
  void add(double t, int k, const Eigen::Vector3d& replayed, const Eigen::Vector3d& recorded);
  /// N, the root mean square of the differences: a path that differs wherever the force
  /// is large stands apart from one that differs at a few samples (a step's force reaching
  /// the device a tick late or early under load).
  double rms_diff() const { return compared ? std::sqrt(sum_sq_diff / double(compared)) : 0.0; }
};

struct ReplayResult {
  RunResult run;              // samples in fingers.csv order, summary
  ReplayForce compared_force = ReplayForce::Sent;
  /// The comparison of `compared_force` (the headline, `palpation replay` prints it first).
  double max_force_diff = 0;  // N
  double max_diff_t = 0;      // s, where
  int max_diff_finger = 0;
  double max_recorded_force = 0;  // N, for scale
  std::size_t compared = 0;       // finger steps (Simulated) or finger ticks (Sent) compared
  /// Recordings with steps: the forces sent at 1 kHz, recorded against the re-simulated
  /// steps through the device's force path (see above); `sent.compared` is 0 otherwise.
  ForceDiff sent;
  double force_scale = 1.0;          // device force per simulated force (the first patient's)
  std::string force_scale_source;    // "recorded" (the header or the session's events), "re-measured" (the
                                     // patient's deep press again, as the workstation chose it), "none" (1)
  /// Makes `d` the headline comparison, of force `f`.
  void set_headline(ReplayForce f, const ForceDiff& d);
};

/// The scenario a recording was made with, its finger paths replaced by the recorded
/// device input. Throws sim::ScenarioError naming the recording's header field.
sim::Scenario replay_scenario(const Recording& rec);

/// A change the workstation's simulation thread applied between steps, from a recording's
/// "parameter" events: `index` is its place in the command queue (a step applied those
/// with index < RecordedStep::commands_applied).
struct RecordedCommand {
  std::uint64_t index = 0;
  std::string kind;                           // "young", "params", "patient"
  std::vector<std::pair<int, double>> young;  // element, Pa
  nlohmann::json scenario;                    // params / patient
  // The elements of `young` are numbered in the order of the patient's mesh, not the
  // model's: a recording whose header's session names no "element_numbering" (made before
  // build_model renumbered meshes for locality).
  bool young_in_mesh_order = false;
};
/// The recording's commands in queue order.
std::vector<RecordedCommand> recorded_commands(const store::RecordingInfo& rec);
/// Applies a "young" command to the simulation's current patient, its elements taken to
/// the model's numbering where the recording names them in the mesh's (Model::mesh_tet).
/// An index outside the mesh stays outside it (Simulation::set_element_young skips it).
void apply_recorded_young(sim::Simulation& s, const RecordedCommand& c);

/// Re-simulates and compares. Throws sim::ScenarioError / std::runtime_error.
ReplayResult replay_recording(const Recording& rec, const ReplayOptions& opt);

}  // namespace palpation::app::review
