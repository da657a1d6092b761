// The instructor's progress window (docs/training.md, "The workstation's training views"):
// a trainee's exams over time from the patient library (a table: date, case, sensitivity,
// false positives, coverage light/medium/deep, deep pressure over the tumours, exam time,
// passed; and line plots over the sessions of sensitivity, false positives, coverage and
// exam time, built by app::train::progress_series), and the class: every trainee's latest
// and best result (PatientLibrary::class_summary). Reads the library when shown or
// refreshed; holds nothing else.
#pragma once

#include <QWidget>

namespace palpation::app::store {
class PatientLibrary;
}

class QComboBox;
class QLabel;
class QTabWidget;
class QTableWidget;
class QChartView;

namespace palpation::ui {

class ProgressWindow : public QWidget {
  Q_OBJECT

 public:
  /// `library` must outlive the window (the main window's).
  explicit ProgressWindow(app::store::PatientLibrary* library, QWidget* parent = nullptr);

  /// Reads the trainees and the class again (keeps the chosen trainee when still there).
  void refresh();
  /// Shows `name`'s exams; false when there is no such trainee.
  bool select_trainee(const QString& name);
  QString trainee() const;
  QTableWidget* sessions_table() const { return sessions_; }
  QTableWidget* class_table() const { return class_; }
  QTabWidget* tabs() const { return tabs_; }
  /// The plots: sensitivity, false positives, coverage, exam time.
  QList<QChartView*> charts() const { return charts_; }

 private:
  void show_trainee();

  app::store::PatientLibrary* library_;
  QTabWidget* tabs_ = nullptr;
  QComboBox* trainees_ = nullptr;
  QTableWidget *sessions_ = nullptr, *class_ = nullptr;
  QLabel* message_ = nullptr;
  QList<QChartView*> charts_;
};

}  // namespace palpation::ui
