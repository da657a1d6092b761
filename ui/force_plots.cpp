#include "force_plots.h"

#include <QChart>
#include <QCoreApplication>
#include <QChartView>
#include <QEvent>
#include <QFile>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLineSeries>
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

QChart* make_chart(std::array<QLineSeries*, 5>& series, QValueAxis** xaxis, QValueAxis** yaxis_out) {
  auto* chart = new QChart;
  auto* x = new QValueAxis;
  auto* y = new QValueAxis;
  chart->addAxis(x, Qt::AlignBottom);
  chart->addAxis(y, Qt::AlignLeft);
  for (int f = 0; f < 5; ++f) {
    series[f] = new QLineSeries;
    chart->addSeries(series[f]);
    series[f]->attachAxis(x);
    series[f]->attachAxis(y);
  }
  chart->legend()->setAlignment(Qt::AlignRight);
  chart->setMargins(QMargins(2, 2, 2, 2));
  if (xaxis) *xaxis = x;
  if (yaxis_out) *yaxis_out = y;
  return chart;
}
}  // namespace

ForcePlots::ForcePlots(QWidget* parent) : QWidget(parent) {
  QValueAxis *my = nullptr, *fy = nullptr, *xx = nullptr, *xy = nullptr;
  mag_chart_ = make_chart(mag_, &mag_t_, &my);
  fz_chart_ = make_chart(fz_, &fz_t_, &fy);
  fx_chart_ = make_chart(fx_, &xx, &xy);
  my->setRange(0, 4.5);
  fy->setRange(-1, 4.5);
  xy->setRange(-1, 4.5);
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
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(pause_);
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
  mag_chart_->setTitle(tr("Force magnitude per finger (N)"));
  fz_chart_->setTitle(tr("Fz per finger (N)"));
  fx_chart_->setTitle(tr("Fz (N) against finger x (m)"));
  for (int f = 0; f < 5; ++f) {
    const QString n = QCoreApplication::translate("ForcePlots", kFingerName[f]);
    mag_[f]->setName(n);
    fz_[f]->setName(n);
    fx_[f]->setName(n);
  }
  pause_->setText(paused_ ? tr("Resume") : tr("Pause"));
  png_->setText(tr("Export PNG..."));
  csv_->setText(tr("Export CSV..."));
}

void ForcePlots::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

void ForcePlots::add_sample(const app::TickSample& s) {
  if (paused_ || s.finger < 0 || s.finger >= 5) return;
  if (!data_[s.finger].empty() && s.t - last_t_[s.finger] < 0.02) return;  // 50 Hz is plenty for the eye
  last_t_[s.finger] = s.t;
  data_[s.finger].push_back({s.t, s.force.norm(), s.force.z(), s.position.x()});
  newest_ = std::max(newest_, s.t);
  while (!data_[s.finger].empty() && data_[s.finger].front().t < s.t - window_) data_[s.finger].pop_front();
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
  for (int f = 0; f < 5; ++f) {
    QList<QPointF> pts;
    pts.reserve(int(data_[f].size()));
    for (const auto& p : data_[f]) pts.append(tab == 0 ? QPointF(p.t, p.fmag) : tab == 1 ? QPointF(p.t, p.fz) : QPointF(p.x, p.fz));
    (tab == 0 ? mag_ : tab == 1 ? fz_ : fx_)[f]->replace(pts);
  }
  const double t1 = std::max(newest_, window_);
  mag_t_->setRange(t1 - window_, t1);
  fz_t_->setRange(t1 - window_, t1);
}

bool ForcePlots::export_png(const QString& path) {
  auto* v = qobject_cast<QChartView*>(tabs_->currentWidget());
  return v && v->grab().save(path, "PNG");
}

bool ForcePlots::export_csv(const QString& path) const {
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text)) return false;
  QTextStream out(&file);
  out << "t,finger,x,fmag,fz\n";
  for (int f = 0; f < 5; ++f)
    for (const auto& p : data_[f]) out << p.t << ',' << f << ',' << p.x << ',' << p.fmag << ',' << p.fz << '\n';
  return true;
}

}  // namespace palpation::ui
