// Mode > Pressure levels... (Instructor mode): the thresholds that divide a touch into
// light, medium and deep pressure (train::PressureThresholds, docs/training.md "Pressure
// levels"): by indentation as a share of the tissue's thickness under the pad, or by the
// force on the pad, whichever is reached first. The dialog edits a copy and hands it back
// validated; the live exam holds the thresholds, the main window keeps them in QSettings and
// the recording.
#pragma once

#include <QDialog>

#include "train/exam.h"

class QDoubleSpinBox;
class QLabel;

namespace palpation::ui {

class PressureDialog : public QDialog {
  Q_OBJECT

 public:
  explicit PressureDialog(const app::train::PressureThresholds& t, QWidget* parent = nullptr);

  /// The thresholds the fields show (not validated).
  app::train::PressureThresholds thresholds() const;
  void set_thresholds(const app::train::PressureThresholds& t);
  /// OK: accepted only when the thresholds validate; otherwise the reason is shown in the
  /// dialog (error_text()) and it stays open.
  void accept() override;
  QString error_text() const;

 private:
  QDoubleSpinBox* depth_[3] = {};  // % of the thickness
  QDoubleSpinBox* force_[3] = {};  // N
  QLabel* error_ = nullptr;
};

}  // namespace palpation::ui
