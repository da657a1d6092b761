// The score of an exam that ended (docs/training.md, "The workstation's training views"):
// tumours found, false positives, sensitivity, positive predictive value, position error,
// exam time, coverage per pressure level, the search pattern's strips, deep pressure over
// each tumour, the advice, and the coverage map with the tumours and the marks (the answer
// may be shown once the exam has ended). "Save report..." writes the same report as
// `palpation score` (cli::write_exam_report) into a folder. Holds the score it shows and
// nothing else; the main window opens it from TrainingSession::last_score().
#pragma once

#include <QDialog>
#include <QString>
#include <QStringList>

#include "cli/exam_report.h"
#include "train/curriculum.h"
#include "train/score_recording.h"

class QFormLayout;
class QLabel;
class QPushButton;

namespace palpation::ui {

class ScoreDialog : public QDialog {
  Q_OBJECT

 public:
  /// `evaluation`: the curriculum case's pass criteria applied (shown as passed / not
  /// passed with the criteria missed); none for a free exam.
  ScoreDialog(app::train::ScoredExam exam, app::cli::ReportInfo info, QWidget* parent = nullptr,
              std::optional<app::train::Evaluation> evaluation = std::nullopt);

  const app::train::ScoredExam& exam() const { return exam_; }
  const app::cli::ReportInfo& info() const { return info_; }
  /// Writes the report (score.json, report.html, report.pdf, the pictures) into `dir`;
  /// the files written, or none with `error` set.
  QStringList save_report(const QString& dir, QString* error = nullptr);
  /// The folder "Save report..." writes into without asking; empty (the default): it asks.
  void set_report_folder(const QString& dir) { folder_ = dir; }
  QPushButton* save_button() const { return save_; }
  /// The text of one figure, by its name: "found", "false_positives", "sensitivity", "ppv",
  /// "error", "time", "coverage", "strips", "deep", "advice", and "result" for a
  /// curriculum case.
  QString figure(const QString& name) const;
  /// Whether the coverage map was drawn (Qt builds of the report draw it).
  bool has_coverage_image() const;

  /// A pass criterion's name as the dialog shows it ("min_coverage.deep" -> "deep coverage").
  static QString criterion_name(const std::string& key);
  /// How the dialog writes a fraction (0.5 -> "50 %") and an optional one ("-" for none).
  static QString percent(double f);
  static QString percent(const std::optional<double>& f);
  /// One line of advice in the chosen language, composed from its kind and figures (the
  /// scorer keeps the English line, Advice::text(), for the report and score.json).
  static QString advice(const app::train::Advice& a);

 signals:
  void reportSaved(const QString& dir, const QStringList& files);

 private:
  QLabel* add_figure(QFormLayout* form, const QString& name, const QString& label, const QString& value);

  app::train::ScoredExam exam_;
  app::cli::ReportInfo info_;
  QString folder_;
  QPushButton* save_ = nullptr;
  QLabel* image_ = nullptr;
};

}  // namespace palpation::ui
