// Review mode for students: a recorded session played back. The 3-D view shows
// the session re-simulated from the recorded input (app::review::ReviewSession's worker thread),
// the force plots follow the timeline, instructor events and trainee marks sit on the
// timeline and in a list; play, pause, scrub, speed 0.25x to 4x; CSV and PNG-frame export;
// the exam's score, its coverage overlay and its report.
// The widgets display app::review::ReviewSession; they hold no state of their own.
#pragma once

#include <array>
#include <memory>

#include <QMainWindow>
#include <QStringList>
#include <QWidget>

#include "review/review_session.h"

class QChart;
class QChartView;
class QComboBox;
class QLabel;
class QLineSeries;
class QListWidget;
class QPushButton;
class QTimer;
class QValueAxis;

namespace palpation::ui {

class VtkView;

/// The timeline: the session's length, the re-simulated part, markers, the cursor. Click
/// or drag to scrub.
class Timeline : public QWidget {
  Q_OBJECT
 public:
  explicit Timeline(QWidget* parent = nullptr);
  void show_session(const app::review::ReviewSession* s) { session_ = s; update(); }
  /// Time at a widget x (s).
  double time_at(int x) const;
  int x_at(double t) const;
  QSize sizeHint() const override { return {600, 46}; }
 signals:
  void seekRequested(double t);
 protected:
  void paintEvent(QPaintEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
 private:
  const app::review::ReviewSession* session_ = nullptr;
};

class ReviewWindow : public QMainWindow {
  Q_OBJECT
 public:
  /// Opens the review of `session` and starts its re-simulation.
  explicit ReviewWindow(std::unique_ptr<app::review::ReviewSession> session, QWidget* parent = nullptr);
  ~ReviewWindow() override;

  app::review::ReviewSession& session() { return *session_; }
  VtkView* view() const { return view_; }
  Timeline* timeline() const { return timeline_; }
  QPushButton* play_button() const { return play_; }
  QComboBox* speed_box() const { return speed_; }
  QLabel* time_label() const { return time_label_; }
  QLabel* difference_label() const { return diff_label_; }
  QListWidget* marker_list() const { return markers_; }
  /// The exam's score (ReviewSession::score): "Coverage" shows the pressure levels reached on
  /// the skin over the patient, the summary the figures and the advice, "Save report..."
  /// writes the report as `palpation score` does. Review comes after the exam: the answer
  /// (where the tumours are) may be shown.
  QPushButton* coverage_button() const { return coverage_; }
  QPushButton* report_button() const { return report_; }
  QLabel* score_label() const { return score_label_; }
  /// Shows or hides the coverage overlay (the "Coverage" toggle). The overlay and the
  /// figures beside the toggle (coverage_now_label) follow the playback time: the levels
  /// reached up to it (ReviewSession::surface_levels, coverage_at).
  void set_coverage_visible(bool on);
  QLabel* coverage_now_label() const { return coverage_now_; }
  /// Writes the report (cli::write_exam_report) into `dir`: the files written, or none with
  /// `error` set (no score, or a file that cannot be written).
  QStringList save_report(const QString& dir, QString* error = nullptr);
  /// The folder "Save report..." writes into without asking; empty (the default): it asks.
  void set_report_folder(const QString& dir) { report_folder_ = dir; }
  /// The time the plots' cursor stands at (s) and the points they show.
  double plot_cursor() const;
  int plot_points() const;

  void seek(double t);
  void set_playing(bool on);
  /// Writes frames (the view, the plots and the timeline) every 1/fps s from t0 to t1 as
  /// DIR/frame-0001.png ...; returns how many were written.
  int export_frames(const QString& dir, double t0, double t1, double fps);
  bool export_csv(const QString& path, QString* error = nullptr);

 public slots:
  void tick();

 protected:
  void changeEvent(QEvent* e) override;
  void closeEvent(QCloseEvent* e) override;

 private:
  void retranslate();
  void show_time();
  void refresh_series();
  void update_difference();
  void show_score();
  void apply_coverage();

  std::unique_ptr<app::review::ReviewSession> session_;
  VtkView* view_ = nullptr;
  Timeline* timeline_ = nullptr;
  QPushButton *play_ = nullptr, *csv_ = nullptr, *png_ = nullptr, *coverage_ = nullptr, *report_ = nullptr;
  QComboBox* speed_ = nullptr;
  QLabel *time_label_ = nullptr, *diff_label_ = nullptr, *speed_label_ = nullptr, *markers_title_ = nullptr;
  QLabel *score_title_ = nullptr, *score_label_ = nullptr, *coverage_now_ = nullptr;
  QString report_folder_;
  bool score_shown_ = false;            // the summary shows the computed score (or why there is none)
  std::size_t surface_faces_ = 0;       // faces of the patient surface the view shows
  QListWidget* markers_ = nullptr;
  QChart* chart_ = nullptr;
  QChartView* chart_view_ = nullptr;
  QValueAxis *t_axis_ = nullptr, *f_axis_ = nullptr;
  std::array<QLineSeries*, 5> rec_{}, resim_{};
  QLineSeries* cursor_ = nullptr;
  QTimer* timer_ = nullptr;
  qint64 last_tick_ms_ = 0, last_series_ms_ = 0;
  std::uint64_t generation_ = 0;
  std::size_t series_done_ = 0;
  // The frame the view shows, held: the review decodes frames on demand and frees those it
  // no longer keeps, so a new frame may reuse a shown one's address.
  std::shared_ptr<const app::review::ReviewFrame> shown_;
};

}  // namespace palpation::ui
