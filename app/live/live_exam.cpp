#include "live/live_exam.h"

#include "live/workstation.h"

namespace palpation::app::live {

namespace {
constexpr double kPlotPeriod = 0.02;  // s between the report's force-plot points
}

LiveExam::LiveExam(train::PressureThresholds t) : t_(t) { t_.validate(); }

void LiveExam::set_patient(std::shared_ptr<const PatientGeometry> g) {
  g_ = std::move(g);
  skin_ = g_ ? g_->skin : nullptr;
  tracker_ = skin_ ? std::make_unique<train::ExamTracker>(skin_, t_) : nullptr;
  restart(t0_);
}

void LiveExam::set_thresholds(const train::PressureThresholds& t) {
  t.validate();
  t_ = t;
  tracker_ = skin_ ? std::make_unique<train::ExamTracker>(skin_, t_) : nullptr;
  restart(t0_);
}

void LiveExam::restart(double t0) {
  t0_ = t0;
  if (tracker_) tracker_->reset();
  marks_.clear();
  plot_t_.clear();
  plot_f_.assign(dv::kMaxFingers, {});
}

void LiveExam::add_step(const StepSample& s) {
  if (!tracker_ || s.t < t0_) return;
  for (int d = 0; d < dv::kMaxFingers; ++d) {
    const sim::FingerInput& in = s.in[std::size_t(d)];
    if (in.active) tracker_->add({s.t - t0_, d, in.position, in.radius, s.force[std::size_t(d)].norm()});
  }
  if (plot_t_.empty() || s.t - t0_ - plot_t_.back() >= kPlotPeriod) {
    plot_t_.push_back(s.t - t0_);
    for (int d = 0; d < dv::kMaxFingers; ++d) plot_f_[std::size_t(d)].push_back(s.force[std::size_t(d)].norm());
  }
}

void LiveExam::add_mark(double t, const Eigen::Vector3d& p, double confidence) {
  marks_.push_back({t - t0_, p, std::clamp(confidence, 0.0, 1.0)});
}

std::vector<unsigned char> LiveExam::surface_levels() const {
  std::vector<unsigned char> out(g_ ? g_->surface.size() : 0, 0);
  if (!tracker_) return out;
  const auto& lv = tracker_->face_level();
  for (std::size_t i = 0; i < lv.size(); ++i) {
    const int f = skin_->model_face[i];
    if (f >= 0 && std::size_t(f) < out.size()) out[std::size_t(f)] = lv[i];
  }
  return out;
}

std::array<double, train::kLevels> LiveExam::coverage() const {
  return tracker_ ? tracker_->coverage() : std::array<double, train::kLevels>{};
}

train::ScoredExam LiveExam::score(const std::vector<double>& young, double now, const std::string& patient) const {
  train::ScoredExam e;
  if (!tracker_ || !g_) return e;
  const auto tumours = train::find_tumours(g_->rest, g_->tets, young, g_->base_moduli(), *skin_, train::kPadRadius);
  e.score = train::score_exam(*tracker_, tumours, marks_, std::max(0.0, now - t0_));
  e.skin = skin_;
  e.face_level = tracker_->face_level();
  e.plot_t = plot_t_;
  e.plot_force = plot_f_;
  e.patient = patient;
  return e;
}

}  // namespace palpation::app::live
