// Live force plots per finger (Qt Charts): force magnitude and fz against time over a
// sliding window, and fz against finger x (the paper's Fig. 6); pause, PNG and CSV export.
// Fed with the workstation's tick telemetry (app::TickSample), decimated to 50 Hz.
#pragma once

#include <array>
#include <deque>

#include <QWidget>

#include "workstation.h"

class QChart;
class QChartView;
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
  void add_sample(const app::TickSample& s);
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
  };
  std::array<std::deque<Point>, 5> data_;
  std::array<double, 5> last_t_{};
  std::array<QLineSeries*, 5> mag_{}, fz_{}, fx_{};
  QChart *mag_chart_ = nullptr, *fz_chart_ = nullptr, *fx_chart_ = nullptr;
  QValueAxis *mag_t_ = nullptr, *fz_t_ = nullptr;
  QChartView *mag_view_ = nullptr, *fz_view_ = nullptr, *fx_view_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QPushButton *pause_ = nullptr, *png_ = nullptr, *csv_ = nullptr;
  bool paused_ = false;
  double window_ = 10.0;  // s
  double newest_ = 0;
};

}  // namespace palpation::ui
