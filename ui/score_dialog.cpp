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

ScoreDialog::ScoreDialog(app::train::ScoredExam exam, app::cli::ReportInfo info, QWidget* parent)
    : QDialog(parent), exam_(std::move(exam)), info_(std::move(info)) {
  setObjectName(QStringLiteral("ScoreDialog"));
  setWindowTitle(tr("Exam score"));
  const auto& s = exam_.score;
  auto* form = new QFormLayout;
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
  QStringList advice;
  for (const auto& a : s.advice) advice << QString::fromStdString(a);  // the scorer's English lines
  auto* adv = add_figure(form, QStringLiteral("advice"), tr("Advice:"), advice.join(QLatin1Char('\n')));
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
