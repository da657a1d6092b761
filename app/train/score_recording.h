// An exam scored from a recording (`palpation score`, the review): the patient rebuilt
// from the recording's scenario, the fingertips from its steps (the simulation's own
// spheres and forces) or, for recordings without steps, its 1 kHz ticks, the marks from
// its mark events and its scenario's "marks". Qt-free.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "store/recording.h"
#include "train/exam.h"

namespace palpation::app::train {

/// Input the scorer refuses: what() names the recording and what is wrong.
class ScoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Marks further than this from the skin are outside the body (a mark is placed on the
/// skin; 2 cm allows for a fingertip's radius and a pressed-in skin).
inline constexpr double kMarkMaxDistance = 0.02;

struct ScoredExam {
  ExamScore score;
  std::shared_ptr<const SkinMap> skin;
  std::vector<unsigned char> face_level;          // highest level on each skin face
  /// When each skin face first reached each level, recording time (ExamTracker::face_reached):
  /// levels_at(face_reached, t) and coverage_at(*skin, face_reached, t) are the exam as it
  /// stood at time t, face_level and the score's coverage at its end.
  std::vector<LevelTimes> face_reached;
  /// |force| on each finger against time, the simulation's (steps) or as sent (ticks),
  /// decimated to 50 Hz: the report's force plot.
  std::vector<double> plot_t;
  std::vector<std::vector<double>> plot_force;     // per finger
  std::string patient;                             // what the recording's scenario calls the patient
  int samples = 0;                                 // fingertip samples scored
};

/// The pressure thresholds a workstation session used: the last "thresholds" event, else
/// the header's settings.thresholds, else the defaults. A recorded value that does not
/// validate throws std::invalid_argument naming the field.
PressureThresholds recorded_thresholds(const store::RecordingInfo& rec);

/// Scores a recording. Throws ScoreError for one cut short (no end chunk: recover it first),
/// a scenario that cannot be read, or marks outside the body.
ScoredExam score_recording(const store::Recording& rec, const PressureThresholds& thresholds = {});
/// The same from a recording kept coded (the review's): the steps or ticks decoded a chunk at a time.
ScoredExam score_recording(const store::CompactRecording& rec, const PressureThresholds& thresholds = {});
}  // namespace palpation::app::train
