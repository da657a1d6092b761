// "Import scan...": a scanned breast (STL, OBJ, PLY) made into a library patient.
// File, name, resolution, scale, base plane (found automatically, or given by hand),
// progress with Cancel (the import runs on app::scan::ScanImportJob's thread, never on the GUI
// thread), a preview of the tetrahedral mesh in a 3-D view, "Save as patient". Errors
// from the importer are shown as they come: the file and what is wrong with it.
#pragma once

#include <QDialog>

#include "scan/scan_import_job.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTimer;

namespace palpation::app::store {
class PatientLibrary;
}

namespace palpation::ui {

class VtkView;

class ImportDialog : public QDialog {
  Q_OBJECT
 public:
  /// `library` may be null (then Save is disabled and says why).
  ImportDialog(app::store::PatientLibrary* library, QWidget* parent = nullptr);
  ~ImportDialog() override;

  QLineEdit *file = nullptr, *name = nullptr;
  QComboBox *resolution = nullptr, *scale = nullptr;
  QCheckBox* base_auto = nullptr;
  std::array<QDoubleSpinBox*, 4> base{};  // nx, ny, nz, d (m)
  QProgressBar* progress = nullptr;
  QLabel *stage = nullptr, *report = nullptr, *error = nullptr;
  QPushButton *browse = nullptr, *import = nullptr, *cancel = nullptr, *save = nullptr, *close_button = nullptr;
  VtkView* preview = nullptr;

  /// Starts the import with the form's values (what the Import button does).
  void start_import();
  /// True from start_import() until the dialog has shown the job's outcome (the job
  /// ends on its thread before poll() puts its result or error on screen).
  bool importing() const;
  /// The name saved last (empty before).
  QString saved_name() const { return saved_; }

 signals:
  void patientSaved(const QString& name);

 protected:
  void changeEvent(QEvent* e) override;
  void reject() override;

 private:
  void retranslate();
  void poll();
  void save_patient();
  double edge() const;

  app::store::PatientLibrary* library_;
  app::scan::ScanImportJob job_;
  QTimer* timer_ = nullptr;
  QString saved_, imported_file_;
  double imported_edge_ = 0;
  std::uint64_t generation_ = 0;
};

}  // namespace palpation::ui
