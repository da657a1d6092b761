// The running exam's feedback, live (docs/training.md): the workstation's simulation steps
// feed a train::ExamTracker on the loaded patient's skin (coverage at each pressure level,
// the search path), the trainee's marks are kept, and the end of the exam scores them
// against the tumours the tumour document holds then. The same tracker and score as
// `palpation score` (app/train). GUI thread; Qt-free.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "train/exam.h"
#include "train/score_recording.h"

namespace palpation::app::live {

struct PatientGeometry;
struct StepSample;

class LiveExam {
 public:
  explicit LiveExam(train::PressureThresholds t = {});

  /// A new patient: its skin, coverage and marks from nothing. Null: none loaded.
  void set_patient(std::shared_ptr<const PatientGeometry> g);
  const std::shared_ptr<const PatientGeometry>& patient() const { return g_; }
  /// Starts over (a new exam) at `t0` (s, Workstation::now_s): coverage, path, marks.
  void restart(double t0);
  double started() const { return t0_; }
  /// One simulation step (Workstation's step listener): every active finger's sphere and
  /// the simulated force on it.
  void add_step(const StepSample& s);
  /// A trainee's mark at `t` (Workstation::now_s), world m.
  void add_mark(double t, const Eigen::Vector3d& p, double confidence);
  const std::vector<train::Mark>& marks() const { return marks_; }

  /// The highest pressure level (0 none .. 3 deep) on each of the patient's boundary faces,
  /// in PatientGeometry::surface's order (chest wall faces 0): the coverage overlay.
  std::vector<unsigned char> surface_levels() const;
  /// Area fractions of the skin at least light, medium, deep.
  std::array<double, train::kLevels> coverage() const;
  /// Scores the exam at `now` (s, Workstation::now_s) against the tumours of `young` (the
  /// tumour document's moduli); `patient` names the case in the report.
  train::ScoredExam score(const std::vector<double>& young, double now, const std::string& patient = {}) const;
  const train::PressureThresholds& thresholds() const { return t_; }
  void set_thresholds(const train::PressureThresholds& t);

 private:
  train::PressureThresholds t_;
  std::shared_ptr<const PatientGeometry> g_;
  std::shared_ptr<const train::SkinMap> skin_;
  std::unique_ptr<train::ExamTracker> tracker_;
  std::vector<train::Mark> marks_;
  double t0_ = 0;
  std::vector<double> plot_t_;
  std::vector<std::vector<double>> plot_f_;
};

}  // namespace palpation::app::live
