// The workstation's training mode (design.md section 8): who uses the station and what they
// may see. Qt-free; the GUI (ui/main_window) shows and hides its panels from it, the
// recorder keeps the mode in its settings and every change as an event.
//
//   Instructor      everything: patients, the tumour list and editor, moduli, colour maps,
//                   tumour outlines, parameters
//   GuidedPractice  a trainee practising: palpation, marks, the force feedback; nothing that
//                   shows where or how stiff the tumours are
//   Exam            a trainee examined: as guided practice, until the exam ends
//
// Going from a trainee mode back to Instructor (and leaving a running exam at all) is an
// instructor's deliberate act: the GUI asks for a confirmation
// (needs_instructor_confirmation). Ending the exam (end_exam) logs the event and tells the
// exam-end listeners (the score view hooks in there, app/train/exam.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "live/event.h"
#include "live/live_exam.h"
#include "train/curriculum.h"

namespace palpation::app::live {

class Workstation;

enum class TrainingMode { Instructor, GuidedPractice, Exam };

/// The mode's stable name (recordings' settings, --mode): "instructor", "guided-practice",
/// "exam"; and back (nothing for another name).
const char* training_mode_name(TrainingMode m);
std::optional<TrainingMode> training_mode_from_name(const std::string& name);
/// The Mode event's value for a training mode.
ModeChange mode_change_of(TrainingMode m);
/// Guided practice and exam: the trainee uses the station, the answer is hidden.
inline bool is_trainee(TrainingMode m) { return m != TrainingMode::Instructor; }

/// True when going from `from` to `to` takes an instructor's confirmation: back to
/// Instructor from a trainee mode, or out of an exam that has not ended.
bool needs_instructor_confirmation(TrainingMode from, TrainingMode to, bool exam_running);

/// What a trainee is told the case is called: an anonymous code from the patient's name
/// (stable: the same patient gets the same code), never the name itself, which may
/// describe the tumour (the library's "tumour-2.0cm-deep-hard"). E.g. "C-4F2A".
std::string anonymous_case_code(const std::string& patient_name);

/// Whether an event may be shown to a trainee as it happens: not the instructor's
/// (patient loading with its name, tumour edits with their moduli, parameter changes).
bool shown_to_trainee(const Event& e);

/// A mark's confidence levels the GUI offers: possible, likely, probable, certain.
inline constexpr double kMarkConfidence[4] = {0.25, 0.50, 0.75, 1.00};

/// The session's training state: the mode, whether an exam is running, the confidence
/// the next mark is given. GUI thread.
class TrainingSession {
 public:
  /// Starts in `mode` (an exam starts at once in a trainee mode); logs nothing.
  explicit TrainingSession(Workstation& ws, TrainingMode mode = TrainingMode::Instructor);

  TrainingMode mode() const { return mode_; }
  /// Changes the mode and logs it (a Mode event). A running exam ends first (logged:
  /// leaving its mode ends it); entering a trainee mode starts a new one.
  /// The caller asks for the confirmation (needs_instructor_confirmation) before.
  void set_mode(TrainingMode m);
  /// Whether set_mode(m) now takes an instructor's confirmation.
  bool needs_confirmation(TrainingMode m) const { return needs_instructor_confirmation(mode_, m, exam_running_); }

  /// A trainee's exam (or practice) is running: started by entering a trainee mode, not
  /// ended yet.
  bool exam_running() const { return exam_running_; }
  /// When the exam started (Workstation::now_s), -1 when none has.
  double exam_started_s() const { return exam_start_; }
  /// Ends the running exam: scores it (last_score), logs ExamEnded and calls the exam-end
  /// listeners with that event. False (nothing logged) when no exam is running.
  bool end_exam();
  void add_exam_end_listener(std::function<void(const Event&)> f) { exam_end_listeners_.push_back(std::move(f)); }
  /// Marks are taken except after an exam ended (until the next one or Instructor mode).
  bool accepts_marks() const { return !is_trainee(mode_) || exam_running_; }

  /// The live exam: coverage and marks since the exam (or, in Instructor mode, the last
  /// clear) started, fed by the workstation's steps; scored when the exam ends. The
  /// coverage overlay may be shown in Instructor and Guided practice, never in Exam.
  const LiveExam& exam() const { return exam_; }
  LiveExam& exam() { return exam_; }
  bool overlay_allowed() const { return mode_ != TrainingMode::Exam; }
  /// A mark the trainee placed (the GUI calls this with the recorder's add_mark): kept for
  /// the score with the current mark confidence.
  void note_mark(const Eigen::Vector3d& position);
  /// The same with a confidence of its own (a mark made with another than the current one).
  void note_mark(const Eigen::Vector3d& position, double confidence);
  /// The score of the exam that ended last (end_exam), if any.
  const std::optional<train::ScoredExam>& last_score() const { return last_score_; }
  /// Starts the coverage over (Instructor mode's "clear"; entering a trainee mode does it).
  void clear_coverage();

  /// Starts a new exam in the current trainee mode (a new case loaded after the last exam
  /// ended): logged as the mode's event, as entering the mode is. Nothing in Instructor
  /// mode; a running exam ends first.
  void start_exam();

  // Curricula (train/curriculum.h) -------------------------------------------------------
  /// The curriculum the trainee works through (none: free exams). Setting one forgets the
  /// case in progress.
  void set_curriculum(std::optional<train::Curriculum> c);
  const std::optional<train::Curriculum>& curriculum() const { return curriculum_; }
  /// The curriculum case loaded on the station (index into curriculum()->cases), set when
  /// the GUI loads it; none when the patient is not the curriculum's.
  void set_curriculum_case(std::optional<std::size_t> i);
  std::optional<std::size_t> curriculum_case() const { return case_; }
  /// The case's pass criteria applied to the exam that ended last: set by end_exam when a
  /// curriculum case was loaded.
  const std::optional<train::Evaluation>& last_evaluation() const { return last_evaluation_; }

  /// The confidence the next mark carries (0..1, clamped; 1: certain).
  void set_mark_confidence(double c);
  double mark_confidence() const { return confidence_; }

 private:
  Workstation& ws_;
  TrainingMode mode_;
  bool exam_running_ = false;
  double exam_start_ = -1;
  double confidence_ = 1.0;
  std::vector<std::function<void(const Event&)>> exam_end_listeners_;
  LiveExam exam_;
  std::optional<train::ScoredExam> last_score_;
  std::optional<train::Curriculum> curriculum_;
  std::optional<std::size_t> case_;
  std::optional<train::Evaluation> last_evaluation_;
  std::shared_ptr<bool> alive_;  // the step listener outlives nothing it points to
};

}  // namespace palpation::app::live
