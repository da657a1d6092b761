#include "force_plots.h"

#include <algorithm>
#include <cmath>

#include <QChart>
#include <QCoreApplication>
#include <QChartView>
#include <QEvent>
#include <QFile>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLegendMarker>
#include <QLineSeries>
#include <QPen>
#include <QPushButton>
#include <QTabWidget>
#include <QTextStream>
#include <QValueAxis>
#include <QVBoxLayout>

namespace palpation::ui {

namespace {
const char* const kFingerName[5] = {QT_TRANSLATE_NOOP("ForcePlots", "thumb"), QT_TRANSLATE_NOOP("ForcePlots", "index"),
                                    QT_TRANSLATE_NOOP("ForcePlots", "middle"), QT_TRANSLATE_NOOP("ForcePlots", "ring"),
                                    QT_TRANSLATE_NOOP("ForcePlots", "little")};

// Solid: sent to the device; dashed, same colour: simulated. Only the solid series
// appear in the legend (the title says what dashed means).
QChart* make_chart(std::array<QLineSeries*, 5>& series, std::array<QLineSeries*, 5>& simulated, QLineSeries** limit,
                   QValueAxis** xaxis, QValueAxis** yaxis_out) {
  auto* chart = new QChart;
  auto* x = new QValueAxis;
  auto* y = new QValueAxis;
  chart->addAxis(x, Qt::AlignBottom);
  chart->addAxis(y, Qt::AlignLeft);
  static const QColor kColour[5] = {QColor(0x20, 0x77, 0xb4), QColor(0x2c, 0xa0, 0x2c), QColor(0xff, 0x7f, 0x0e),
                                    QColor(0x94, 0x67, 0xbd), QColor(0xd6, 0x27, 0x28)};
  for (int f = 0; f < 5; ++f) {
    series[f] = new QLineSeries;
    simulated[f] = new QLineSeries;
    QPen solid(kColour[f], 2.0);
    series[f]->setPen(solid);
    QPen dashed(kColour[f], 1.5, Qt::DashLine);
    simulated[f]->setPen(dashed);
    for (QLineSeries* s : {series[f], simulated[f]}) {
      chart->addSeries(s);
      s->attachAxis(x);
      s->attachAxis(y);
    }
    for (auto* m : chart->legend()->markers(simulated[f])) m->setVisible(false);
  }
  if (limit) {
    *limit = new QLineSeries;
    (*limit)->setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DotLine));
    chart->addSeries(*limit);
    (*limit)->attachAxis(x);
    (*limit)->attachAxis(y);
    for (auto* m : chart->legend()->markers(*limit)) m->setVisible(false);  // the title says "dotted"
  }
  chart->legend()->setAlignment(Qt::AlignRight);
  chart->setMargins(QMargins(2, 2, 2, 2));
  if (xaxis) *xaxis = x;
  if (yaxis_out) *yaxis_out = y;
  return chart;
}
}  // namespace

ForcePlots::ForcePlots(QWidget* parent) : QWidget(parent) {
  QValueAxis* xx = nullptr;
  mag_chart_ = make_chart(mag_, sim_mag_, &mag_limit_, &mag_t_, &mag_y_);
  fz_chart_ = make_chart(fz_, sim_fz_, &fz_limit_, &fz_t_, &fz_y_);
  fx_chart_ = make_chart(fx_, sim_fx_, nullptr, &xx, &fx_y_);
  mag_y_->setRange(0, 4.5);
  fz_y_->setRange(-1, 4.5);
  fx_y_->setRange(-1, 4.5);
  xx->setRange(0.08, 0.17);
  mag_view_ = new QChartView(mag_chart_);
  fz_view_ = new QChartView(fz_chart_);
  fx_view_ = new QChartView(fx_chart_);
  for (auto* v : {mag_view_, fz_view_, fx_view_}) v->setRenderHint(QPainter::Antialiasing);
  tabs_ = new QTabWidget;
  tabs_->addTab(mag_view_, QString());
  tabs_->addTab(fz_view_, QString());
  tabs_->addTab(fx_view_, QString());
  connect(tabs_, &QTabWidget::currentChanged, this, &ForcePlots::refresh);
  pause_ = new QPushButton;
  pause_->setCheckable(true);
  png_ = new QPushButton;
  csv_ = new QPushButton;
  scale_ = new QLabel;
  scale_->setObjectName(QStringLiteral("forceScale"));
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(pause_);
  buttons->addWidget(scale_, 1);
  buttons->addStretch();
  buttons->addWidget(png_);
  buttons->addWidget(csv_);
  auto* lay = new QVBoxLayout(this);
  lay->setContentsMargins(2, 2, 2, 2);
  lay->addWidget(tabs_, 1);
  lay->addLayout(buttons);
  connect(pause_, &QPushButton::toggled, this, &ForcePlots::set_paused);
  connect(png_, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getSaveFileName(this, tr("Export plot as PNG"), QStringLiteral("forces.png"), tr("PNG images (*.png)"));
    if (!f.isEmpty()) export_png(f);
  });
  connect(csv_, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getSaveFileName(this, tr("Export forces as CSV"), QStringLiteral("forces.csv"), tr("CSV files (*.csv)"));
    if (!f.isEmpty()) export_csv(f);
  });
  retranslate();
}

void ForcePlots::retranslate() {
  tabs_->setTabText(0, tr("|F| vs time"));
  tabs_->setTabText(1, tr("Fz vs time"));
  tabs_->setTabText(2, tr("Fz vs x (Fig. 6)"));
  const QString key = tr("solid: sent to the device (limit %1 N, dotted); dashed: simulated contact force").arg(limit_, 0, 'f', 1);
  mag_chart_->setTitle(tr("Force magnitude per finger (N)") + QStringLiteral("<br><small>") + key + QStringLiteral("</small>"));
  fz_chart_->setTitle(tr("Fz per finger (N)") + QStringLiteral("<br><small>") + key + QStringLiteral("</small>"));
  fx_chart_->setTitle(tr("Fz (N) against finger x (m)") + QStringLiteral("<br><small>") + key + QStringLiteral("</small>"));
  for (int f = 0; f < 5; ++f) {
    const QString n = QCoreApplication::translate("ForcePlots", kFingerName[f]);
    mag_[f]->setName(n);
    fz_[f]->setName(n);
    fx_[f]->setName(n);
    const QString sim = tr("%1 (simulated)").arg(n);
    sim_mag_[f]->setName(sim);
    sim_fz_[f]->setName(sim);
    sim_fx_[f]->setName(sim);
  }
  mag_limit_->setName(tr("device limit"));
  fz_limit_->setName(tr("device limit"));
  pause_->setText(paused_ ? tr("Resume") : tr("Pause"));
  png_->setText(tr("Export PNG..."));
  csv_->setText(tr("Export CSV..."));
  scale_->setText(force_scale_text());
  scale_->setToolTip(have_mapping_ ? tr("The device renders the simulated force times the force scale, chosen when the patient "
                                        "loads: a deep press (%1 % of the tissue thickness) over the stiffest part of the "
                                        "patient maps to %2 % of the device's limit, so that the tumour's extra force stays "
                                        "within the device's range. Device limit %3 N = %4 N simulated. Solid lines: sent "
                                        "(device units); dashed: simulated.")
                                         .arg(100.0 * mapping_.deep_press_depth, 0, 'f', 0)
                                         .arg(100.0 * mapping_.deep_press_share, 0, 'f', 0)
                                         .arg(mapping_.device_limit_n, 0, 'f', 1)
                                         .arg(mapping_.simulated_at_limit_n, 0, 'f', 1)
                                   : QString());
}

QString ForcePlots::force_scale_text() const {
  if (!have_mapping_) return QString();
  const app::live::ForceMapping& m = mapping_;
  if (m.rule == app::live::ForceScaleRule::Configured)
    return tr("Force scale %1 (device configuration): %2 N simulated -> %3 N at the device")
        .arg(m.scale, 0, 'f', 2)
        .arg(m.simulated_at_limit_n, 0, 'f', 1)
        .arg(m.device_limit_n, 0, 'f', 1);
  if (m.rule == app::live::ForceScaleRule::Patient)
    return tr("Force scale %1: deep press %2 N simulated -> %3 N at the device (limit %4 N)")
        .arg(m.scale, 0, 'f', 2)
        .arg(m.deep_press_n, 0, 'f', 1)
        .arg(m.deep_press_device_n, 0, 'f', 1)
        .arg(m.device_limit_n, 0, 'f', 1);
  return tr("Force scale 1: simulated forces sent unscaled");
}

void ForcePlots::set_force_mapping(const app::live::ForceMapping& m) {
  if (have_mapping_ && m.scale == mapping_.scale && m.rule == mapping_.rule && m.deep_press_n == mapping_.deep_press_n &&
      m.device_limit_n == mapping_.device_limit_n)
    return;
  mapping_ = m;
  have_mapping_ = true;
  retranslate();
}

void ForcePlots::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

void ForcePlots::add_sample(const app::live::TickSample& s) {
  if (paused_ || s.finger < 0 || s.finger >= 5) return;
  if (!data_[s.finger].empty() && s.t - last_t_[s.finger] < 0.02) return;  // 50 Hz is plenty for the eye
  last_t_[s.finger] = s.t;
  const Eigen::Vector3d& sim = sim_force_[s.finger];
  data_[s.finger].push_back({s.t, s.force.norm(), s.force.z(), s.position.x(), sim.norm(), sim.z()});
  newest_ = std::max(newest_, s.t);
  while (!data_[s.finger].empty() && data_[s.finger].front().t < s.t - window_) data_[s.finger].pop_front();
}

void ForcePlots::add_step_sample(const app::live::StepSample& s) {
  for (int f = 0; f < 5; ++f) sim_force_[f] = s.in[f].active ? s.force[f] : Eigen::Vector3d::Zero();
  set_force_mapping(s.mapping);
}

void ForcePlots::set_device_limit(double newtons) {
  limit_ = newtons;
  retranslate();
}

double ForcePlots::max_sent(int finger) const {
  double m = 0;
  for (const auto& p : data_[finger]) m = std::max(m, p.fmag);
  return m;
}

double ForcePlots::max_simulated(int finger) const {
  double m = 0;
  for (const auto& p : data_[finger]) m = std::max(m, p.sim_mag);
  return m;
}

int ForcePlots::shown_points() const {
  int n = 0;
  for (auto* s : mag_) n += int(s->count());
  return n;
}

void ForcePlots::set_paused(bool on) {
  paused_ = on;
  if (pause_->isChecked() != on) pause_->setChecked(on);
  retranslate();
}

void ForcePlots::refresh() {
  if (paused_) return;
  // Only the chart on show is refilled (the others when their tab comes up).
  const int tab = tabs_->currentIndex();
  double top = 0, bottom = 0;
  for (int f = 0; f < 5; ++f) {
    QList<QPointF> pts, sim;
    pts.reserve(int(data_[f].size()));
    sim.reserve(int(data_[f].size()));
    for (const auto& p : data_[f]) {
      pts.append(tab == 0 ? QPointF(p.t, p.fmag) : tab == 1 ? QPointF(p.t, p.fz) : QPointF(p.x, p.fz));
      sim.append(tab == 0 ? QPointF(p.t, p.sim_mag) : tab == 1 ? QPointF(p.t, p.sim_z) : QPointF(p.x, p.sim_z));
      top = std::max({top, pts.back().y(), sim.back().y()});
      bottom = std::min({bottom, pts.back().y(), sim.back().y()});
    }
    (tab == 0 ? mag_ : tab == 1 ? fz_ : fx_)[f]->replace(pts);
    (tab == 0 ? sim_mag_ : tab == 1 ? sim_fz_ : sim_fx_)[f]->replace(sim);
  }
  const double t1 = std::max(newest_, window_);
  mag_t_->setRange(t1 - window_, t1);
  fz_t_->setRange(t1 - window_, t1);
  mag_limit_->replace(QList<QPointF>{{t1 - window_, limit_}, {t1, limit_}});
  fz_limit_->replace(QList<QPointF>{{t1 - window_, limit_}, {t1, limit_}});
  // The y range follows the simulated force above the device limit (in 2 N steps, so
  // that it does not jitter), never below the limit and at most 3x the limit: single-step
  // spikes of the simulated force at real-time dt (docs/stability.md) are clipped rather
  // than squeezing what the device sends into the bottom of the plot.
  const double cap = 3.0 * limit_;
  const double hi = std::clamp(2.0 * std::ceil(top * 1.05 / 2.0), limit_ + 0.5, cap);
  const double lo = std::max(-cap, std::min(-1.0, -2.0 * std::ceil(-bottom * 1.05 / 2.0)));
  (tab == 0 ? mag_y_ : tab == 1 ? fz_y_ : fx_y_)->setRange(tab == 0 ? 0.0 : lo, hi);
}

bool ForcePlots::export_png(const QString& path) {
  auto* v = qobject_cast<QChartView*>(tabs_->currentWidget());
  return v && v->grab().save(path, "PNG");
}

bool ForcePlots::export_csv(const QString& path) const {
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text)) return false;
  QTextStream out(&file);
  // fmag, fz: sent to the device; sim_fmag, sim_fz: the simulated contact force.
  out << "t,finger,x,fmag,fz,sim_fmag,sim_fz\n";
  for (int f = 0; f < 5; ++f)
    for (const auto& p : data_[f])
      out << p.t << ',' << f << ',' << p.x << ',' << p.fmag << ',' << p.fz << ',' << p.sim_mag << ',' << p.sim_z << '\n';
  return true;
}

}  // namespace palpation::ui
