// Live force plots per finger (Qt Charts): force magnitude and fz against time over a
// sliding window, and fz against finger x (the paper's Fig. 6); pause, PNG and CSV export.
// Two forces per finger, told apart by line style: solid, the force sent to the device
// (after the haptic loop's safety filter: clamped to the device limit, drawn as a dotted
// line, and rate-limited); dashed, the simulated contact force (the FEM's, per
// simulation step). Fed with the workstation's tick telemetry (app::live::TickSample,
// decimated to 50 Hz) and step telemetry (app::live::StepSample).
#pragma once

#include <array>
#include <deque>

#include <QWidget>

#include "live/workstation.h"

class QChart;
class QChartView;
class QLabel;
class QLineSeries;
class QValueAxis;
class QPushButton;
class QTabWidget;

namespace palpation::ui {

class ForcePlots : public QWidget {
  Q_OBJECT

 public:
  explicit ForcePlots(QWidget* parent = nullptr);
  /// A tick sample (GUI thread). Kept at most every 20 ms per finger.
  void add_sample(const app::live::TickSample& s);
  /// A simulation step (GUI thread): the simulated contact forces, shown with the next
  /// tick samples.
  void add_step_sample(const app::live::StepSample& s);
  /// The device's force limit (N), drawn as a line; default 4 N.
  void set_device_limit(double newtons);
  /// The force scale between simulation and device (app::live::ForceMapping, chosen by
  /// the workstation per patient), shown under the plots; add_step_sample passes each
  /// step's.
  void set_force_mapping(const app::live::ForceMapping& m);
  /// The line shown for it (tests).
  QString force_scale_text() const;
  /// Largest force held for finger f (N): sent to the device, and simulated.
  double max_sent(int finger) const;
  double max_simulated(int finger) const;
  /// Points held for finger f (for tests and export).
  int point_count(int finger) const { return int(data_[finger].size()); }
  /// Points the charts show now (all fingers, magnitude series).
  int shown_points() const;
  bool paused() const { return paused_; }
  void set_paused(bool on);
  bool export_png(const QString& path);
  bool export_csv(const QString& path) const;
  double window_s() const { return window_; }

 public slots:
  /// Moves the sliding window and refreshes the series (called at ~10 Hz).
  void refresh();

 protected:
  void changeEvent(QEvent* e) override;

 private:
  void retranslate();
  struct Point {
    double t, fmag, fz, x;
    double sim_mag, sim_z;  // simulated contact force (N) at that time
  };
  std::array<std::deque<Point>, 5> data_;
  std::array<double, 5> last_t_{};
  std::array<Eigen::Vector3d, 5> sim_force_{};  // newest simulated force per finger
  std::array<QLineSeries*, 5> mag_{}, fz_{}, fx_{};
  std::array<QLineSeries*, 5> sim_mag_{}, sim_fz_{}, sim_fx_{};
  QLineSeries *mag_limit_ = nullptr, *fz_limit_ = nullptr;
  QValueAxis *mag_y_ = nullptr, *fz_y_ = nullptr, *fx_y_ = nullptr;
  double limit_ = 4.0;
  QChart *mag_chart_ = nullptr, *fz_chart_ = nullptr, *fx_chart_ = nullptr;
  QValueAxis *mag_t_ = nullptr, *fz_t_ = nullptr;
  QChartView *mag_view_ = nullptr, *fz_view_ = nullptr, *fx_view_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QPushButton *pause_ = nullptr, *png_ = nullptr, *csv_ = nullptr;
  QLabel* scale_ = nullptr;
  app::live::ForceMapping mapping_;
  bool have_mapping_ = false;
  bool paused_ = false;
  double window_ = 10.0;  // s
  double newest_ = 0;
};

}  // namespace palpation::ui
