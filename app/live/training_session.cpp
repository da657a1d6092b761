#include "live/training_session.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "live/workstation.h"

namespace palpation::app::live {

const char* training_mode_name(TrainingMode m) {
  switch (m) {
    case TrainingMode::Instructor: return "instructor";
    case TrainingMode::GuidedPractice: return "guided-practice";
    case TrainingMode::Exam: return "exam";
  }
  return "";
}

std::optional<TrainingMode> training_mode_from_name(const std::string& name) {
  for (TrainingMode m : {TrainingMode::Instructor, TrainingMode::GuidedPractice, TrainingMode::Exam})
    if (name == training_mode_name(m)) return m;
  return std::nullopt;
}

ModeChange mode_change_of(TrainingMode m) {
  switch (m) {
    case TrainingMode::Instructor: return ModeChange::Instructor;
    case TrainingMode::GuidedPractice: return ModeChange::GuidedPractice;
    case TrainingMode::Exam: return ModeChange::Exam;
  }
  return ModeChange::Instructor;
}

bool needs_instructor_confirmation(TrainingMode from, TrainingMode to, bool exam_running) {
  if (from == to) return false;
  if (to == TrainingMode::Instructor) return is_trainee(from);
  return from == TrainingMode::Exam && exam_running;
}

std::string anonymous_case_code(const std::string& patient_name) {
  // FNV-1a over the name, folded to 16 bits: a short code that tells cases apart and says
  // nothing of what the name says.
  std::uint32_t h = 2166136261u;
  for (unsigned char c : patient_name) {
    h ^= c;
    h *= 16777619u;
  }
  char buf[16];
  std::snprintf(buf, sizeof buf, "C-%04X", unsigned((h >> 16) ^ (h & 0xffffu)));
  return buf;
}

bool shown_to_trainee(const Event& e) {
  switch (e.kind) {
    case EventKind::Mode:
    case EventKind::Mark:
    case EventKind::ExamEnded:
    case EventKind::Fallback:
    case EventKind::Reset:
    case EventKind::Stopped: return true;
    default: return false;
  }
}

TrainingSession::TrainingSession(Workstation& ws, TrainingMode mode)
    : ws_(ws), mode_(mode), alive_(std::make_shared<bool>(true)) {
  if (is_trainee(mode_)) {
    exam_running_ = true;
    exam_start_ = 0;
  }
  // Steps arrive on the GUI thread (Workstation::poll); a new patient brings a new skin.
  std::weak_ptr<bool> alive = alive_;
  ws_.add_step_listener([this, alive](const StepSample& s) {
    if (alive.expired()) return;
    const auto g = ws_.geometry();
    if (g != exam_.patient()) exam_.set_patient(g);
    if (!is_trainee(mode_) || exam_running_) exam_.add_step(s);
  });
}

void TrainingSession::note_mark(const Eigen::Vector3d& position) { exam_.add_mark(ws_.now_s(), position, confidence_); }

void TrainingSession::note_mark(const Eigen::Vector3d& position, double confidence) {
  exam_.add_mark(ws_.now_s(), position, std::clamp(confidence, 0.0, 1.0));
}

void TrainingSession::clear_coverage() { exam_.restart(ws_.now_s()); }

void TrainingSession::set_mode(TrainingMode m) {
  if (m == mode_) return;
  // A practice or exam belongs to its mode: leaving it ends it (logged), a trainee mode
  // entered starts a new one.
  if (exam_running_) end_exam();
  mode_ = m;
  if (is_trainee(m)) {
    exam_running_ = true;
    exam_start_ = ws_.now_s();
    exam_.restart(exam_start_);
  }
  ws_.log_event(Event::mode_change(mode_change_of(m)));
}

bool TrainingSession::end_exam() {
  if (!exam_running_) return false;
  exam_running_ = false;
  last_score_ = exam_.score(ws_.tumours().young(), ws_.now_s());
  last_evaluation_.reset();
  if (curriculum_ && case_) last_evaluation_ = train::evaluate(curriculum_->cases[*case_].pass, last_score_->score);
  Event e = Event::exam_ended(mode_change_of(mode_ == TrainingMode::Instructor ? TrainingMode::Exam : mode_));
  e.t = ws_.now_s();
  ws_.log_event(e);
  for (const auto& f : exam_end_listeners_) f(e);
  return true;
}

void TrainingSession::start_exam() {
  if (!is_trainee(mode_)) return;
  if (exam_running_) end_exam();
  exam_running_ = true;
  exam_start_ = ws_.now_s();
  exam_.restart(exam_start_);
  ws_.log_event(Event::mode_change(mode_change_of(mode_)));
}

void TrainingSession::set_curriculum(std::optional<train::Curriculum> c) {
  curriculum_ = std::move(c);
  case_.reset();
}

void TrainingSession::set_curriculum_case(std::optional<std::size_t> i) {
  case_ = curriculum_ && i && *i < curriculum_->cases.size() ? i : std::nullopt;
}

void TrainingSession::set_mark_confidence(double c) { confidence_ = std::clamp(c, 0.0, 1.0); }

}  // namespace palpation::app::live
