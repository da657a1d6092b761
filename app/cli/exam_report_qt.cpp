// The report's pictures and PDF with Qt Gui: QPainter on a QImage, QTextDocument printed
// by QPdfWriter (no widgets, no display).
#include <algorithm>
#include <cmath>
#include <numeric>

#include <QFileInfo>
#include <QImage>
#include <QPainter>
#include <QPageSize>
#include <QPdfWriter>
#include <QTextDocument>
#include <QUrl>

#include "cli/exam_report.h"
#include "cli/plot_png.h"

namespace palpation::app::cli {

bool write_coverage_png(const train::ScoredExam& exam, const std::string& path, int size) {
  ensure_gui_application();
  const train::SkinMap& skin = *exam.skin;
  const train::ExamScore& s = exam.score;
  QImage img(size, size, QImage::Format_ARGB32);
  img.fill(Qt::white);
  QPainter p(&img);
  p.setRenderHint(QPainter::Antialiasing);
  const double span = std::max(skin.hi.x() - skin.lo.x(), skin.hi.y() - skin.lo.y());
  const double scale = span > 0 ? (size - 40) / span : 1.0;
  const double cx = 0.5 * (skin.lo.x() + skin.hi.x()), cy = 0.5 * (skin.lo.y() + skin.hi.y());
  auto map = [&](const Eigen::Vector3d& v) { return QPointF(size / 2.0 + (v.x() - cx) * scale, size / 2.0 - (v.y() - cy) * scale); };
  // From above: lower faces first, so the skin nearest the viewer is drawn last.
  std::vector<int> order(skin.faces.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return skin.centroid[std::size_t(a)].z() < skin.centroid[std::size_t(b)].z(); });
  const QColor colours[4] = {QColor(215, 215, 215), QColor(250, 220, 90), QColor(245, 150, 50), QColor(200, 40, 40)};
  for (int f : order) {
    if (skin.normal[std::size_t(f)].z() <= 0) continue;
    const auto& t = skin.faces[std::size_t(f)];
    const QPointF tri[3] = {map(skin.nodes[std::size_t(t[0])]), map(skin.nodes[std::size_t(t[1])]), map(skin.nodes[std::size_t(t[2])])};
    const int l = f < int(exam.face_level.size()) ? std::min<int>(exam.face_level[std::size_t(f)], 3) : 0;
    p.setPen(QPen(colours[l].darker(115), 0.5));
    p.setBrush(colours[l]);
    p.drawPolygon(tri, 3);
  }
  p.setBrush(Qt::NoBrush);
  for (const auto& r : s.tumours) {
    p.setPen(QPen(r.found ? QColor(0, 120, 0) : QColor(30, 30, 160), 2, Qt::DashLine));
    p.drawEllipse(map(r.truth.skin_point), r.truth.tolerance * scale, r.truth.tolerance * scale);
  }
  for (std::size_t i = 0; i < s.marks.size(); ++i) {
    const bool fp = std::find(s.false_positive_marks.begin(), s.false_positive_marks.end(), int(i)) != s.false_positive_marks.end();
    p.setPen(QPen(fp ? QColor(210, 0, 0) : QColor(0, 150, 0), 3));
    const QPointF c = map(i < s.marks_on_skin.size() ? s.marks_on_skin[i] : s.marks[i].position);
    p.drawLine(c + QPointF(-7, -7), c + QPointF(7, 7));
    p.drawLine(c + QPointF(-7, 7), c + QPointF(7, -7));
  }
  p.setPen(Qt::black);
  p.drawText(QRectF(6, 4, size - 12, 20), Qt::AlignLeft, QStringLiteral("head (+y)"));
  p.drawText(QRectF(6, size - 22, size - 12, 20), Qt::AlignLeft, QStringLiteral("1 cm"));
  p.drawLine(QPointF(50, size - 12), QPointF(50 + 0.01 * scale, size - 12));
  p.end();
  return img.save(QString::fromStdString(path), "PNG");
}

bool write_report_pdf(const std::string& html_path, const std::string& html, const std::string& pdf_path) {
  ensure_gui_application();
  QTextDocument doc;
  // Images are resolved against the HTML's folder (coverage.png, forces.png beside it).
  doc.setBaseUrl(QUrl::fromLocalFile(QFileInfo(QString::fromStdString(html_path)).absolutePath() + "/"));
  doc.setHtml(QString::fromStdString(html));
  QPdfWriter pdf(QString::fromStdString(pdf_path));
  pdf.setPageSize(QPageSize(QPageSize::A4));
  pdf.setResolution(150);
  pdf.setTitle(QStringLiteral("Palpation exam report"));
  doc.print(&pdf);  // paginated
  return QFileInfo(QString::fromStdString(pdf_path)).size() > 0;
}

}  // namespace palpation::app::cli
