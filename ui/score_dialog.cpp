#include "score_dialog.h"

#include <cmath>

#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QPixmap>
#include <QPushButton>
#include <QTemporaryDir>
#include <QVBoxLayout>

namespace palpation::ui {

QString ScoreDialog::percent(double f) { return QStringLiteral("%1 %").arg(f * 100.0, 0, 'f', 0); }
QString ScoreDialog::percent(const std::optional<double>& f) { return f ? percent(*f) : QStringLiteral("-"); }

QString ScoreDialog::advice(const app::train::Advice& a) {
  using K = app::train::Advice::Kind;
  using app::train::Level;
  // The source strings are the English lines of Advice::text(), word for word.
  switch (a.kind) {
    case K::Coverage:
      switch (a.level) {
        case Level::Light: return tr("Cover the whole breast at light pressure: %1% of the skin was reached at that level.").arg(a.percent);
        case Level::Medium: return tr("Cover the whole breast at medium pressure: %1% of the skin was reached at that level.").arg(a.percent);
        case Level::Deep: return tr("Cover the whole breast at deep pressure: %1% of the skin was reached at that level.").arg(a.percent);
        case Level::None: break;
      }
      break;
    case K::Strips:
      return tr("Search in vertical strips, head to foot, overlapping each by about a third of a finger pad: "
                "%1 strips covered %2% of the path.")
          .arg(a.count)
          .arg(a.percent);
    case K::Overlap: return tr("Overlap neighbouring strips: they left gaps between them.");
    case K::PressDeep:
      return tr("Press deep at every spot: a lump %1 mm below the skin was missed where deep pressure was not reached.").arg(a.depth_mm);
    case K::FalsePositives:
      return tr("Check a suspected lump at all three pressure levels before marking it: %1 mark(s) found no lump.").arg(a.count);
    case K::Complete: return tr("A complete examination: keep this pattern and pressure.");
  }
  return QString::fromStdString(a.text());
}

QString ScoreDialog::criterion_name(const std::string& key) {
  if (key == "min_sensitivity") return tr("tumours found");
  if (key == "max_false_positives") return tr("false positives");
  if (key == "min_coverage.light") return tr("light coverage");
  if (key == "min_coverage.medium") return tr("medium coverage");
  if (key == "min_coverage.deep") return tr("deep coverage");
  if (key == "deep_over_each_tumour") return tr("deep pressure over each tumour");
  if (key == "max_exam_time") return tr("exam time");
  return QString::fromStdString(key);
}

ScoreDialog::ScoreDialog(app::train::ScoredExam exam, app::cli::ReportInfo info, QWidget* parent,
                         std::optional<app::train::Evaluation> evaluation)
    : QDialog(parent), exam_(std::move(exam)), info_(std::move(info)) {
  setObjectName(QStringLiteral("ScoreDialog"));
  setWindowTitle(tr("Exam score"));
  const auto& s = exam_.score;
  auto* form = new QFormLayout;
  if (evaluation) {
    QStringList missed;
    for (const auto& c : evaluation->criteria)
      if (!c.passed) missed << criterion_name(c.criterion);
    auto* r = add_figure(form, QStringLiteral("result"), tr("Curriculum case:"),
                         evaluation->passed ? tr("passed") : tr("not passed: %1").arg(missed.join(QStringLiteral(", "))));
    r->setStyleSheet(evaluation->passed ? QStringLiteral("color: #1b5e20; font-weight: bold")
                                        : QStringLiteral("color: #b00020; font-weight: bold"));
    r->setWordWrap(true);
  }
  const int n = int(s.tumours.size());
  add_figure(form, QStringLiteral("found"), tr("Tumours found:"), tr("%1 of %2").arg(s.hits).arg(n));
  add_figure(form, QStringLiteral("false_positives"), tr("False positives:"), QString::number(s.false_positives));
  add_figure(form, QStringLiteral("sensitivity"), tr("Sensitivity:"), percent(s.sensitivity));
  add_figure(form, QStringLiteral("ppv"), tr("Positive predictive value:"), percent(s.ppv));
  add_figure(form, QStringLiteral("error"), tr("Position error:"),
             s.hits > 0 ? tr("%1 mm (mean over the tumours found)").arg(s.mean_error * 1000.0, 0, 'f', 1) : QStringLiteral("-"));
  add_figure(form, QStringLiteral("time"), tr("Exam time:"), tr("%1 s").arg(s.exam_time, 0, 'f', 0));
  add_figure(form, QStringLiteral("coverage"), tr("Coverage:"),
             tr("light %1, medium %2, deep %3")
                 .arg(percent(s.coverage[0]), percent(s.coverage[1]), percent(s.coverage[2])));
  add_figure(form, QStringLiteral("strips"), tr("Vertical strips:"), QString::number(s.pattern.strips));
  QStringList deep;
  for (int i = 0; i < n; ++i)
    deep << tr("tumour %1: %2").arg(i + 1).arg(s.tumours[i].deep_reached ? tr("yes") : tr("no"));
  add_figure(form, QStringLiteral("deep"), tr("Deep pressure over each tumour:"), n ? deep.join(QStringLiteral("; ")) : QStringLiteral("-"));
  QStringList advice_lines;
  for (const auto& a : s.advice) advice_lines << advice(a);
  auto* adv = add_figure(form, QStringLiteral("advice"), tr("Advice:"), advice_lines.join(QLatin1Char('\n')));
  adv->setWordWrap(true);

  // The report's own coverage map: the skin from above, each face by its level, the
  // tumours' circles and the marks.
  image_ = new QLabel;
  image_->setObjectName(QStringLiteral("score_coverage_image"));
  QTemporaryDir tmp;
  const QString png = tmp.filePath(QStringLiteral("coverage.png"));
  if (tmp.isValid() && app::cli::write_coverage_png(exam_, png.toStdString(), 420)) image_->setPixmap(QPixmap(png));
  image_->setToolTip(tr("Skin from above: grey not pressed, yellow light, orange medium, red deep; "
                        "circles: the tumours (green: found); marks: green correct, red false"));

  auto* buttons = new QDialogButtonBox;
  save_ = buttons->addButton(tr("Save report..."), QDialogButtonBox::ActionRole);
  save_->setObjectName(QStringLiteral("save_report"));
  auto* close = buttons->addButton(QDialogButtonBox::Close);
  close->setText(tr("Close"));
  connect(close, &QPushButton::clicked, this, &QDialog::close);
  connect(save_, &QPushButton::clicked, this, [this] {
    QString dir = folder_;
    if (dir.isEmpty()) dir = QFileDialog::getExistingDirectory(this, tr("Save the exam report into"), QDir::homePath());
    if (dir.isEmpty()) return;
    QString err;
    const QStringList files = save_report(dir, &err);
    if (files.isEmpty()) QMessageBox::warning(this, tr("Save report"), err);
  });

  auto* top = new QHBoxLayout;
  top->addLayout(form, 1);
  top->addWidget(image_, 0, Qt::AlignTop);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top);
  layout->addWidget(buttons);
}

QLabel* ScoreDialog::add_figure(QFormLayout* form, const QString& name, const QString& label, const QString& value) {
  auto* l = new QLabel(value);
  l->setObjectName(QStringLiteral("score_") + name);
  l->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow(label, l);
  return l;
}

QString ScoreDialog::figure(const QString& name) const {
  auto* l = findChild<QLabel*>(QStringLiteral("score_") + name);
  return l ? l->text() : QString();
}

bool ScoreDialog::has_coverage_image() const { return image_ && !image_->pixmap().isNull(); }

QStringList ScoreDialog::save_report(const QString& dir, QString* error) {
  QStringList out;
  try {
    for (const auto& f : app::cli::write_exam_report(exam_, dir.toStdString(), info_)) out << QString::fromStdString(f);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return {};
  }
  emit reportSaved(dir, out);
  return out;
}

}  // namespace palpation::ui
