#include "review_window.h"

#include <QChart>
#include <QChartView>
#include <QCloseEvent>
#include <QComboBox>
#include <QCoreApplication>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineSeries>
#include <QListWidget>
#include <QMessageBox>
#include <QMouseEvent>
#include <QPainter>
#include <QPushButton>
#include <QStatusBar>
#include <QTimer>
#include <QValueAxis>
#include <QVBoxLayout>

#include "cli/exam_report.h"
#include "event_text.h"
#include "score_dialog.h"
#include "vtk_view.h"

namespace palpation::ui {

namespace {
const char* const kFinger[5] = {QT_TRANSLATE_NOOP("ReviewWindow", "thumb"), QT_TRANSLATE_NOOP("ReviewWindow", "index"),
                                QT_TRANSLATE_NOOP("ReviewWindow", "middle"), QT_TRANSLATE_NOOP("ReviewWindow", "ring"),
                                QT_TRANSLATE_NOOP("ReviewWindow", "little")};
const QColor kColour[5] = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44), QColor(148, 103, 189),
                           QColor(255, 127, 14)};
QColor marker_colour(const std::string& kind) {
  if (kind == "mark") return QColor(220, 30, 30);
  if (kind == "parameter") return QColor(30, 90, 200);
  return QColor(90, 90, 90);
}
QString clock(double t) {
  const int m = int(t / 60);
  return QStringLiteral("%1:%2").arg(m).arg(t - 60 * m, 6, 'f', 3, QLatin1Char('0'));
}
}  // namespace

// ---------------------------------------------------------------------------------------
Timeline::Timeline(QWidget* parent) : QWidget(parent) {
  setMinimumHeight(40);
  setMouseTracking(false);
  setObjectName(QStringLiteral("Timeline"));
}

double Timeline::time_at(int x) const {
  if (!session_) return 0;
  const int w = std::max(1, width() - 16);
  return std::clamp(double(x - 8) / w, 0.0, 1.0) * session_->duration();
}

int Timeline::x_at(double t) const {
  const double d = session_ ? std::max(1e-9, session_->duration()) : 1.0;
  return 8 + int(std::lround(std::clamp(t / d, 0.0, 1.0) * (width() - 16)));
}

void Timeline::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const int y0 = 14, h = height() - 22;
  p.fillRect(QRect(8, y0, width() - 16, h), QColor(225, 225, 225));
  if (!session_) return;
  // Re-simulated part.
  p.fillRect(QRect(8, y0, x_at(session_->resimulated_until()) - 8, h), QColor(160, 200, 235));
  for (const auto& m : session_->markers()) {
    const int x = x_at(m.t);
    p.setPen(QPen(marker_colour(m.kind), m.kind == "mark" ? 3 : 2));
    p.drawLine(x, y0, x, y0 + h);
    if (m.kind == "mark") {
      p.setBrush(marker_colour(m.kind));
      const QPointF tri[3] = {QPointF(x - 5, 2), QPointF(x + 5, 2), QPointF(x, y0 - 1)};
      p.drawPolygon(tri, 3);
    }
  }
  const int xc = x_at(session_->time());
  p.setPen(QPen(Qt::black, 2));
  p.drawLine(xc, y0 - 4, xc, y0 + h + 4);
  p.setPen(Qt::black);
  p.drawText(QRect(8, y0 + h, width() - 16, 10), Qt::AlignRight | Qt::AlignVCenter, QString());
}

void Timeline::mousePressEvent(QMouseEvent* e) { emit seekRequested(time_at(int(e->position().x()))); }
void Timeline::mouseMoveEvent(QMouseEvent* e) {
  if (e->buttons() & Qt::LeftButton) emit seekRequested(time_at(int(e->position().x())));
}

// ---------------------------------------------------------------------------------------
ReviewWindow::ReviewWindow(std::unique_ptr<app::review::ReviewSession> session, QWidget* parent)
    : QMainWindow(parent), session_(std::move(session)) {
  setObjectName(QStringLiteral("ReviewWindow"));
  setAttribute(Qt::WA_DeleteOnClose, false);
  view_ = new VtkView(this);
  view_->set_tumours_visible(true);

  chart_ = new QChart;
  t_axis_ = new QValueAxis;
  f_axis_ = new QValueAxis;
  chart_->addAxis(t_axis_, Qt::AlignBottom);
  chart_->addAxis(f_axis_, Qt::AlignLeft);
  for (int k = 0; k < 5; ++k) {
    rec_[k] = new QLineSeries;
    resim_[k] = new QLineSeries;
    rec_[k]->setPen(QPen(kColour[k], 1.5));
    QPen dashed(kColour[k].darker(140), 1.5, Qt::DashLine);
    resim_[k]->setPen(dashed);
    for (auto* s : {rec_[k], resim_[k]}) {
      chart_->addSeries(s);
      s->attachAxis(t_axis_);
      s->attachAxis(f_axis_);
    }
  }
  cursor_ = new QLineSeries;
  cursor_->setPen(QPen(Qt::black, 1.5));
  chart_->addSeries(cursor_);
  cursor_->attachAxis(t_axis_);
  cursor_->attachAxis(f_axis_);
  chart_->legend()->setAlignment(Qt::AlignRight);
  chart_->setMargins(QMargins(2, 2, 2, 2));
  chart_view_ = new QChartView(chart_);
  chart_view_->setRenderHint(QPainter::Antialiasing);
  chart_view_->setMinimumHeight(190);

  timeline_ = new Timeline;
  timeline_->show_session(session_.get());
  play_ = new QPushButton;
  play_->setObjectName(QStringLiteral("Play"));
  speed_ = new QComboBox;
  for (double s : {0.25, 0.5, 1.0, 2.0, 4.0}) speed_->addItem(QStringLiteral("%1x").arg(s), s);
  speed_->setCurrentIndex(2);
  speed_label_ = new QLabel;
  time_label_ = new QLabel;
  time_label_->setMinimumWidth(150);
  diff_label_ = new QLabel;
  diff_label_->setWordWrap(true);
  diff_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  csv_ = new QPushButton;
  png_ = new QPushButton;
  markers_ = new QListWidget;
  markers_title_ = new QLabel;
  score_title_ = new QLabel;
  score_label_ = new QLabel;
  score_label_->setObjectName(QStringLiteral("ReviewScore"));
  score_label_->setWordWrap(true);
  score_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  coverage_ = new QPushButton;
  coverage_->setObjectName(QStringLiteral("ReviewCoverage"));
  coverage_->setCheckable(true);
  coverage_->setEnabled(false);  // until the score is computed
  report_ = new QPushButton;
  report_->setObjectName(QStringLiteral("ReviewSaveReport"));
  report_->setEnabled(false);
  coverage_now_ = new QLabel;
  coverage_now_->setObjectName(QStringLiteral("ReviewCoverageNow"));
  coverage_now_->setWordWrap(true);
  coverage_now_->setVisible(false);  // with the overlay

  auto* controls = new QHBoxLayout;
  controls->addWidget(play_);
  controls->addWidget(speed_label_);
  controls->addWidget(speed_);
  controls->addWidget(time_label_);
  controls->addStretch();
  controls->addWidget(csv_);
  controls->addWidget(png_);
  auto* bottom = new QWidget;
  auto* bl = new QVBoxLayout(bottom);
  bl->setContentsMargins(4, 2, 4, 2);
  bl->addWidget(chart_view_, 1);
  bl->addWidget(timeline_);
  bl->addLayout(controls);
  bl->addWidget(diff_label_);

  auto* central = new QWidget;
  auto* cl = new QVBoxLayout(central);
  cl->setContentsMargins(0, 0, 0, 0);
  cl->addWidget(view_, 3);
  cl->addWidget(bottom, 2);
  setCentralWidget(central);
  auto* side = new QWidget;
  auto* sl = new QVBoxLayout(side);
  sl->addWidget(markers_title_);
  sl->addWidget(markers_, 1);
  sl->addWidget(score_title_);
  sl->addWidget(score_label_);
  auto* score_buttons = new QHBoxLayout;
  score_buttons->addWidget(coverage_);
  score_buttons->addWidget(report_);
  score_buttons->addStretch();
  sl->addLayout(score_buttons);
  sl->addWidget(coverage_now_);
  auto* dock = new QDockWidget(this);
  dock->setObjectName(QStringLiteral("ReviewEventsDock"));
  dock->setWidget(side);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  for (const auto& m : session_->markers()) {
    auto* it = new QListWidgetItem(markers_);  // the text: retranslate()
    it->setData(Qt::UserRole, m.t);
    it->setForeground(marker_colour(m.kind));
  }

  connect(timeline_, &Timeline::seekRequested, this, &ReviewWindow::seek);
  connect(play_, &QPushButton::clicked, this, [this] { set_playing(!session_->playing()); });
  connect(speed_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { session_->set_speed(speed_->itemData(i).toDouble()); });
  connect(markers_, &QListWidget::itemActivated, this, [this](QListWidgetItem* it) { seek(it->data(Qt::UserRole).toDouble()); });
  connect(markers_, &QListWidget::itemClicked, this, [this](QListWidgetItem* it) { seek(it->data(Qt::UserRole).toDouble()); });
  connect(csv_, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getSaveFileName(this, tr("Export the session as CSV"), QStringLiteral("session.csv"), tr("CSV files (*.csv)"));
    QString err;
    if (!f.isEmpty() && !export_csv(f, &err)) QMessageBox::warning(this, tr("Export CSV"), err);
  });
  connect(coverage_, &QPushButton::toggled, this, &ReviewWindow::set_coverage_visible);
  connect(report_, &QPushButton::clicked, this, [this] {
    const QString d = report_folder_.isEmpty() ? QFileDialog::getExistingDirectory(this, tr("Folder for the exam report")) : report_folder_;
    if (d.isEmpty()) return;
    QString err;
    const QStringList files = save_report(d, &err);
    if (files.isEmpty()) QMessageBox::warning(this, tr("Save report"), err);
    else statusBar()->showMessage(tr("Report written to %1 (%2)").arg(QDir::toNativeSeparators(d), files.join(QStringLiteral(", "))), 8000);
  });
  connect(png_, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Folder for the PNG frames"));
    if (d.isEmpty()) return;
    const int n = export_frames(d, 0.0, session_->duration(), 10.0);
    statusBar()->showMessage(tr("%n frame(s) written to %1", nullptr, n).arg(d), 8000);
  });

  const auto& rec = session_->recording();
  t_axis_->setRange(0, std::max(0.1, session_->duration()));
  const double fmax = std::max(0.5, session_->max_recorded_force());
  f_axis_->setRange(0, fmax * 1.1);
  for (int k = 0; k < 5; ++k) {
    const bool used = k < rec.fingers;
    rec_[k]->setVisible(used);
    resim_[k]->setVisible(used);
  }
  // Only the fingers that touched anything get a line (the others stay at zero).
  for (int k = 0; k < rec.fingers && k < 5; ++k) {
    auto pts = session_->recorded_series(k, 0.01);
    bool any = false;
    QList<QPointF> q;
    q.reserve(int(pts.size()));
    for (const auto& [t, f] : pts) {
      q.append(QPointF(t, f));
      any = any || f > 1e-3;
    }
    rec_[k]->replace(q);
    if (!any) {
      rec_[k]->setVisible(false);
      resim_[k]->setVisible(false);
    }
  }
  retranslate();
  resize(1200, 860);
  session_->start();
  timer_ = new QTimer(this);
  timer_->setTimerType(Qt::PreciseTimer);
  connect(timer_, &QTimer::timeout, this, &ReviewWindow::tick);
  timer_->start(33);
  last_tick_ms_ = QDateTime::currentMSecsSinceEpoch();
  show_time();
}

ReviewWindow::~ReviewWindow() { session_->cancel(); }

void ReviewWindow::retranslate() {
  const QString file = QDir::toNativeSeparators(QString::fromStdString(session_->recording().path));
  setWindowTitle(tr("Review: %1").arg(QFileInfo(file).fileName()));
  play_->setText(session_->playing() ? tr("Pause") : tr("Play"));
  speed_label_->setText(tr("Speed"));
  csv_->setText(tr("Export CSV..."));
  png_->setText(tr("Export PNG frames..."));
  markers_title_->setText(tr("Instructor events and trainee marks (click to go there)"));
  score_title_->setText(tr("<b>Exam score</b>"));
  coverage_->setText(tr("Coverage"));
  coverage_->setToolTip(tr("The skin coloured by the highest pressure reached: grey none, yellow light, orange medium, red deep"));
  report_->setText(tr("Save report..."));
  if (score_shown_) show_score();
  else score_label_->setText(tr("Scoring the exam..."));
  // The events in the chosen language from their data (EventText); those recorded without
  // their arguments (older recordings) as recorded.
  const auto& markers = session_->markers();
  for (int i = 0; i < markers_->count() && i < int(markers.size()); ++i) {
    const auto& m = markers[std::size_t(i)];
    markers_->item(i)->setText(QStringLiteral("%1  %2").arg(clock(m.t), m.event ? EventText::event(*m.event) : QString::fromStdString(m.text)));
  }
  chart_->setTitle(session_->has_steps()
                       ? tr("Force on each fingertip (N): sent to the device (solid), re-simulated simulation force (dashed)")
                       : tr("Force on each fingertip (N): recorded (solid), re-simulated (dashed)"));
  for (int k = 0; k < 5; ++k) {
    const QString n = QCoreApplication::translate("ReviewWindow", kFinger[k]);
    rec_[k]->setName(n);
    resim_[k]->setName(tr("%1 (re-sim.)").arg(n));
  }
  cursor_->setName(tr("now"));
  if (auto* d = findChild<QDockWidget*>(QStringLiteral("ReviewEventsDock"))) d->setWindowTitle(tr("Events"));
  update_difference();
}

void ReviewWindow::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange && play_) retranslate();
  QMainWindow::changeEvent(e);
}

void ReviewWindow::closeEvent(QCloseEvent* e) {
  timer_->stop();
  session_->cancel();
  QMainWindow::closeEvent(e);
}

double ReviewWindow::plot_cursor() const { return cursor_->count() ? cursor_->at(0).x() : -1.0; }

int ReviewWindow::plot_points() const {
  int n = 0;
  for (int k = 0; k < 5; ++k) n += int(rec_[k]->count() + resim_[k]->count());
  return n;
}

void ReviewWindow::seek(double t) {
  session_->seek(t);
  show_time();
}

void ReviewWindow::set_playing(bool on) {
  session_->set_playing(on);
  last_tick_ms_ = QDateTime::currentMSecsSinceEpoch();
  play_->setText(session_->playing() ? tr("Pause") : tr("Play"));
}

void ReviewWindow::tick() {
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  const double wall = double(now - last_tick_ms_) * 1e-3;
  last_tick_ms_ = now;
  if (session_->playing()) {
    session_->advance(std::min(wall, 0.2));
    if (!session_->playing()) play_->setText(tr("Play"));
    show_time();
  }
  const bool final_pending = session_->finished() && series_done_ != std::size_t(-1);
  if ((now - last_series_ms_ >= 500 && series_done_ != session_->done()) || final_pending) {
    last_series_ms_ = now;
    refresh_series();
    if (final_pending) series_done_ = std::size_t(-1);  // the whole re-simulation is shown
    update_difference();
    timeline_->update();
  }
  if (!session_->playing() && shown_ == nullptr) show_time();  // first frame as soon as it is computed
  if (!score_shown_ && session_->score_ready()) show_score();
}

void ReviewWindow::show_score() {
  score_shown_ = true;
  const app::train::ScoredExam* ex = session_->score();
  coverage_->setEnabled(ex != nullptr);
  report_->setEnabled(ex != nullptr);
  if (!ex) {
    score_label_->setText(tr("No score: %1").arg(QString::fromStdString(session_->score_error())));
    return;
  }
  const auto& s = ex->score;
  QStringList lines;
  lines << tr("Tumours found: %1 of %2").arg(s.hits).arg(s.tumours.size());
  lines << tr("False positives: %1").arg(s.false_positives);
  lines << tr("Coverage: light %1, medium %2, deep %3")
               .arg(ScoreDialog::percent(s.coverage[0]), ScoreDialog::percent(s.coverage[1]), ScoreDialog::percent(s.coverage[2]));
  lines << tr("Vertical strips: %1").arg(s.pattern.strips);
  for (const auto& a : s.advice) lines << QStringLiteral("- ") + ScoreDialog::advice(a);
  score_label_->setText(lines.join(QLatin1Char('\n')));
  if (view_->coverage_visible()) apply_coverage();
}

void ReviewWindow::set_coverage_visible(bool on) {
  if (coverage_->isChecked() != on) coverage_->setChecked(on);  // toggled() comes back here
  if (on) apply_coverage();
  coverage_now_->setVisible(on);
  view_->set_coverage_visible(on);
  view_->request_render();
}

void ReviewWindow::apply_coverage() {
  // The levels reached up to the playback time on the patient the view shows (the scorer's
  // skin is the same model's surface), and their skin fractions beside the toggle.
  if (!session_->score_ready()) return;
  const double t = session_->time();
  if (const auto c = session_->coverage_at(t))
    coverage_now_->setText(tr("Coverage up to %1: light %2, medium %3, deep %4")
                               .arg(clock(t), ScoreDialog::percent((*c)[0]), ScoreDialog::percent((*c)[1]), ScoreDialog::percent((*c)[2])));
  if (surface_faces_ == 0) return;
  view_->set_coverage(session_->surface_levels(surface_faces_, t));
}

QStringList ReviewWindow::save_report(const QString& dir, QString* error) {
  const app::train::ScoredExam* ex = session_->score_ready() ? session_->score() : nullptr;
  if (!ex) {
    if (error)
      *error = session_->score_ready() ? tr("No score: %1").arg(QString::fromStdString(session_->score_error()))
                                       : tr("The exam is still being scored.");
    return {};
  }
  app::cli::ReportInfo info;
  info.recording = session_->recording().path;
  info.case_name = ex->patient;
  info.created = QDateTime::currentDateTimeUtc().toString(Qt::ISODate).toStdString();
  try {
    QStringList out;
    for (const auto& f : app::cli::write_exam_report(*ex, dir.toStdString(), info)) out << QString::fromStdString(f);
    return out;
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return {};
  }
}

void ReviewWindow::refresh_series() {
  series_done_ = session_->done();
  double top = f_axis_->max();
  for (int k = 0; k < session_->fingers() && k < 5; ++k) {
    if (!rec_[k]->isVisible()) continue;
    QList<QPointF> q;
    for (const auto& [t, f] : session_->resim_series(k, 0.01)) {
      q.append(QPointF(t, f));
      top = std::max(top, f * 1.05);
    }
    resim_[k]->replace(q);
  }
  if (top > f_axis_->max()) {
    f_axis_->setRange(0, top);
    show_time();  // the cursor spans the new range
  }
}

void ReviewWindow::show_time() {
  const double t = session_->time();
  time_label_->setText(QStringLiteral("%1 / %2").arg(clock(t), clock(session_->duration())));
  const double top = f_axis_->max();
  cursor_->replace(QList<QPointF>{QPointF(t, 0), QPointF(t, top)});
  timeline_->update();
  if (view_->coverage_visible()) apply_coverage();  // the coverage grows with the playback time
  auto fr = session_->frame_at(t);
  if (!fr) return;
  if (fr->geometry && fr->geometry->generation != generation_) {
    generation_ = fr->geometry->generation;
    view_->set_patient(fr->geometry);  // clears the coverage overlay's levels
    surface_faces_ = fr->geometry->surface.size();
    if (view_->coverage_visible()) apply_coverage();
    // The recorded patient's tumours as it was loaded.
    view_->show_tumours(app::live::TumourDocument(fr->geometry));
  }
  if (fr != shown_) {
    shown_ = fr;
    view_->show_snapshot(fr->snapshot);
  }
}

void ReviewWindow::update_difference() {
  const auto c = session_->compare();
  const QString be = QString::fromStdString(session_->backend());
  QString s;
  if (!session_->error().empty()) {
    s = tr("Re-simulation stopped: %1").arg(QString::fromStdString(session_->error()));
  } else if (session_->has_steps()) {
    s = c.max_diff > 0
            ? tr("Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation "
                 "forces: %4 N (%5 finger at %6 s; largest recorded force %7 N).")
                  .arg(session_->done())
                  .arg(session_->total())
                  .arg(be)
                  .arg(c.max_diff, 0, 'g', 3)
                  .arg(QCoreApplication::translate("ReviewWindow", kFinger[std::clamp(c.finger, 0, 4)]))
                  .arg(c.at_t, 0, 'f', 3)
                  .arg(c.max_force, 0, 'g', 3)
            : tr("Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation "
                 "forces: 0 N (largest recorded force %4 N).")
                  .arg(session_->done())
                  .arg(session_->total())
                  .arg(be)
                  .arg(c.max_force, 0, 'g', 3);
    s += QLatin1Char(' ');
    s += c.max_diff <= 1e-9 ? tr("Reproduced: same backend and settings give the same forces.")
                            : tr("Not reproduced exactly (another backend or settings).");
    if (session_->finished())
      s += QLatin1Char(' ') + tr("The forces sent at 1 kHz differ from the simulation's by up to %1 N (the haptic loop's "
                                 "local contact model, coupling and safety filter).")
                                  .arg(c.max_sent_diff, 0, 'g', 3);
  } else {
    s = tr("Re-simulated %1 of %2 ticks (backend %3) from the recorded device input at the scenario's time step. Largest "
           "difference from the recorded forces: %4 N (largest recorded force %5 N).")
            .arg(session_->done())
            .arg(session_->total())
            .arg(be)
            .arg(c.max_diff, 0, 'g', 3)
            .arg(c.max_force, 0, 'g', 3);
  }
  const auto& rec = session_->recording();
  if (!rec.complete) s += QLatin1Char(' ') + tr("The recording was interrupted: %1").arg(QString::fromStdString(rec.interrupted));
  else if (rec.recovered) s += QLatin1Char(' ') + tr("The recording was recovered after an interruption.");
  diff_label_->setText(s);
}

bool ReviewWindow::export_csv(const QString& path, QString* error) {
  try {
    session_->export_csv(path.toStdString());
    statusBar()->showMessage(tr("Written: %1").arg(path), 6000);
    return true;
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
}

int ReviewWindow::export_frames(const QString& dir, double t0, double t1, double fps) {
  const bool was = session_->playing();
  const double keep = session_->time();
  session_->set_playing(false);
  QDir().mkpath(dir);
  int n = 0;
  const double dt = 1.0 / std::max(0.1, fps);
  for (double t = t0; t <= t1 + 1e-9; t += dt) {
    seek(t);
    view_->request_render();
    QCoreApplication::processEvents();
    // The view's frame read back and painted in (its native window is not in a grab).
    const QImage img = VtkView::grab_with_views(centralWidget());
    if (!img.save(QDir(dir).filePath(QStringLiteral("frame-%1.png").arg(n + 1, 4, 10, QLatin1Char('0'))))) break;
    ++n;
  }
  seek(keep);
  session_->set_playing(was);
  return n;
}

}  // namespace palpation::ui
