// QPainter on a QImage: no widgets, no display needed.
#include <algorithm>
#include <cmath>

#include <memory>

#include <QFont>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <QString>

#include "cli/plot_png.h"

namespace palpation::app::cli {

bool can_plot() { return true; }

namespace {
struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  void fit(const std::vector<double>& v) {
    for (double d : v)
      if (std::isfinite(d) && (!log || d > 0)) {
        lo = std::min(lo, log ? std::log10(d) : d);
        hi = std::max(hi, log ? std::log10(d) : d);
      }
  }
  double map(double d) const { return ((log ? std::log10(d) : d) - lo) / (hi - lo); }
  void finish() {
    if (!(hi > lo)) {
      lo -= 0.5;
      hi += 0.5;
    }
    if (!log) {
      const double pad = 0.05 * (hi - lo);
      lo -= pad;
      hi += pad;
    }
  }
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log) {
      for (double e = std::floor(lo); e <= std::ceil(hi); e += 1)
        if (e >= lo - 1e-9 && e <= hi + 1e-9) t.push_back(std::pow(10.0, e));
      return t;
    }
    const double span = hi - lo, raw = span / 6;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * mag >= raw) {
        step = m * mag;
        break;
      }
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-12; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0 : v);
    return t;
  }
};
}  // namespace

void ensure_gui_application() {
  // Text needs Qt's font database, which needs a QGuiApplication: the command line makes
  // an offscreen one on first use (no display needed).
  // Deliberately never destroyed: Qt's own statics may be gone by then at exit.
  [[maybe_unused]] static QGuiApplication* app = nullptr;
  if (!QCoreApplication::instance()) {
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
    static int argc = 1;
    static char arg0[] = "palpation";
    static char* argv[] = {arg0, nullptr};
    app = new QGuiApplication(argc, argv);
  }
}

bool write_plot_png(const std::string& path, const PlotSpec& spec, std::string* why) {
  ensure_gui_application();
  QImage img(spec.width, spec.height, QImage::Format_RGB32);
  img.fill(Qt::white);
  QPainter p(&img);
  p.setRenderHint(QPainter::Antialiasing);
  QFont font("DejaVu Sans", 10);
  p.setFont(font);
  const bool right = std::any_of(spec.series.begin(), spec.series.end(), [](auto& s) { return s.right_axis; });
  const QRectF area(80, 40, spec.width - (right ? 170 : 110), spec.height - 100);
  Axis ax, ayl, ayr;
  ax.log = spec.log_x;
  ayl.log = ayr.log = spec.log_y;
  ax.lo = ayl.lo = ayr.lo = 1e300;
  ax.hi = ayl.hi = ayr.hi = -1e300;
  for (const auto& s : spec.series) {
    ax.fit(s.x);
    (s.right_axis ? ayr : ayl).fit(s.y);
  }
  ax.finish();
  ayl.finish();
  ayr.finish();
  p.setPen(QPen(Qt::black, 1));
  p.drawRect(area);
  auto px = [&](double x) { return area.left() + ax.map(x) * area.width(); };
  auto py = [&](const Axis& a, double y) { return area.bottom() - a.map(y) * area.height(); };
  auto label = [](double v) { return QString::number(v, 'g', 4); };
  p.setPen(QPen(QColor(220, 220, 220), 1));
  for (double t : ax.ticks()) p.drawLine(QPointF(px(t), area.top()), QPointF(px(t), area.bottom()));
  for (double t : ayl.ticks()) p.drawLine(QPointF(area.left(), py(ayl, t)), QPointF(area.right(), py(ayl, t)));
  p.setPen(Qt::black);
  for (double t : ax.ticks()) p.drawText(QRectF(px(t) - 40, area.bottom() + 4, 80, 18), Qt::AlignCenter, label(t));
  for (double t : ayl.ticks()) p.drawText(QRectF(0, py(ayl, t) - 9, area.left() - 6, 18), Qt::AlignRight | Qt::AlignVCenter, label(t));
  if (right)
    for (double t : ayr.ticks()) p.drawText(QRectF(area.right() + 6, py(ayr, t) - 9, 80, 18), Qt::AlignLeft | Qt::AlignVCenter, label(t));
  p.drawText(QRectF(area.left(), area.bottom() + 24, area.width(), 20), Qt::AlignCenter, QString::fromStdString(spec.xlabel));
  p.save();
  p.translate(14, area.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-area.height() / 2, -10, area.height(), 20), Qt::AlignCenter, QString::fromStdString(spec.ylabel));
  p.restore();
  if (right) {
    p.save();
    p.translate(spec.width - 14, area.center().y());
    p.rotate(90);
    p.drawText(QRectF(-area.height() / 2, -10, area.height(), 20), Qt::AlignCenter, QString::fromStdString(spec.ylabel_right));
    p.restore();
  }
  QFont bold = font;
  bold.setBold(true);
  bold.setPointSize(12);
  p.setFont(bold);
  p.drawText(QRectF(0, 6, spec.width, 26), Qt::AlignCenter, QString::fromStdString(spec.title));
  p.setFont(font);
  static const QColor kColours[] = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44), QColor(255, 127, 14),
                                    QColor(148, 103, 189), QColor(140, 86, 75), QColor(227, 119, 194), QColor(127, 127, 127)};
  p.setClipRect(area);
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const auto& s = spec.series[i];
    const Axis& ay = s.right_axis ? ayr : ayl;
    QPen pen(kColours[i % 8], 1.6);
    if (s.dashed) pen.setStyle(Qt::DashLine);
    p.setPen(pen);
    QPainterPath line;
    bool started = false;
    for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k]) || (ay.log && s.y[k] <= 0) || (ax.log && s.x[k] <= 0)) {
        started = false;
        continue;
      }
      const QPointF q(px(s.x[k]), py(ay, s.y[k]));
      if (started) line.lineTo(q); else line.moveTo(q);
      started = true;
      if (s.markers) p.drawEllipse(q, 3, 3);
    }
    p.drawPath(line);
  }
  p.setClipping(false);
  // Legend.
  double ly = area.top() + 8;
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    QPen pen(kColours[i % 8], 2);
    if (spec.series[i].dashed) pen.setStyle(Qt::DashLine);
    p.setPen(pen);
    p.drawLine(QPointF(area.left() + 10, ly + 7), QPointF(area.left() + 40, ly + 7));
    p.setPen(Qt::black);
    p.drawText(QPointF(area.left() + 46, ly + 11), QString::fromStdString(spec.series[i].name));
    ly += 18;
  }
  p.end();
  if (!img.save(QString::fromStdString(path), "PNG")) {
    if (why) *why = path + ": cannot be written";
    return false;
  }
  return true;
}

}  // namespace palpation::app::cli
