// The instructor panels (dock contents). Widgets only: they show state and emit requests;
// the main window turns requests into workstation commands / undo steps.
#pragma once

#include <array>

#include <QWidget>

#include "live/workstation.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QLineEdit;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QToolButton;
class QGroupBox;

namespace palpation::ui {

class TumourEditor;

/// Patient: a patient from the library (built-in shapes and tumour cases, imported
/// scans) or a built-in phantom, resolution, tissue parameters; "Load patient" loads it;
/// "Import scan..." opens the import dialog.
class PatientPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PatientPanel(QWidget* parent = nullptr);
  struct Entry {
    QString name;         // library name, or "phantom:breast" / "phantom:box"
    QString category;     // "breast", "tumour", "imported", "phantom"
    QString description;  // as stored (English for the built-in patients)
    bool builtin = false;  // a built-in patient: its description is data (app::store::builtin_description)
  };
  /// Fills the chooser (the current choice is kept when still there).
  void set_patients(const QList<Entry>& entries);
  /// Selects an entry by name without emitting patientChosen; false when absent.
  bool select_patient(const QString& name);
  QString chosen() const;
  void show_scenario(const sim::Scenario& s);
  /// `base` (the chosen patient) with the panel's resolution (phantoms) and tissue.
  sim::Scenario scenario(const sim::Scenario& base) const;
  QComboBox *phantom = nullptr, *resolution = nullptr;  // phantom: the patient chooser
  QDoubleSpinBox *young = nullptr, *poisson = nullptr;
  QPushButton *apply = nullptr, *import_scan = nullptr;
  QLabel *info = nullptr, *description = nullptr;
 signals:
  void loadRequested();
  void patientChosen(const QString& name);
  void importRequested();
 protected:
  void changeEvent(QEvent* e) override;
 private:
  void retranslate();
  QFormLayout* form_ = nullptr;
};

/// Tumours: list, add by shape, brush painting/erase, presets with sources, undo/redo.
class TumourPanel : public QWidget {
  Q_OBJECT
 public:
  TumourPanel(TumourEditor* editor, QWidget* parent = nullptr);
  void refresh_list();
  double preset_young() const;
  app::live::TumourShape chosen_shape() const;
  QListWidget* list = nullptr;
  QComboBox *preset = nullptr, *shape = nullptr;
  QLabel* source = nullptr;
  std::array<QDoubleSpinBox*, 3> centre{}, radii{};
  QDoubleSpinBox *young = nullptr, *brush_radius = nullptr, *brush_depth = nullptr;
  QPushButton *add = nullptr, *remove = nullptr;
  QToolButton *paint = nullptr, *erase = nullptr, *undo = nullptr, *redo = nullptr;
 signals:
  void toolRequested(int tool);  // VtkView::Tool
 protected:
  void changeEvent(QEvent* e) override;
 private:
  void retranslate();
  TumourEditor* editor_;
  QGroupBox *shape_box_ = nullptr, *brush_box_ = nullptr;
  QFormLayout *shape_form_ = nullptr, *brush_form_ = nullptr, *top_form_ = nullptr;
  QWidget *centre_label_widget_ = nullptr, *radii_label_widget_ = nullptr;
};

/// Simulation: backend, solver quality, live step time, CG iterations, rates.
class SimulationPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SimulationPanel(QWidget* parent = nullptr);
  void show_stats(const app::live::LiveStats& s, const QString& backend);
  QComboBox* backend = nullptr;
  QDoubleSpinBox* tolerance = nullptr;
  QSpinBox* iterations = nullptr;
  QDoubleSpinBox* force_error = nullptr;  // percent; 0: the tolerance fixed
  QPushButton* apply = nullptr;
  QLabel *step_ms = nullptr, *cg = nullptr, *step_rate = nullptr, *haptic_rate = nullptr, *state = nullptr;
  QLabel* pace = nullptr;    // the tissue's pace against the wall clock, and the mean dt
  QLabel* safety = nullptr;  // fallbacks / divergence resets and the newest reason
 protected:
  void changeEvent(QEvent* e) override;
 private:
  void retranslate();
  QFormLayout* form_ = nullptr;
};

/// Device: simulated / mouse / HandHIRO address; per-finger force bars, attached, jitter.
class DevicePanel : public QWidget {
  Q_OBJECT
 public:
  explicit DevicePanel(double max_force, QWidget* parent = nullptr);
  void show_stats(const app::live::LiveStats& s);
  QComboBox* mode = nullptr;
  QLineEdit* address = nullptr;
  std::array<QProgressBar*, 5> bars{};
  std::array<QLabel*, 5> attached{};
  QLabel *jitter = nullptr, *note = nullptr;
 protected:
  void changeEvent(QEvent* e) override;
 private:
  void retranslate();
  QFormLayout* form_ = nullptr;
  std::array<QLabel*, 5> names_{};
  double max_force_;
};

}  // namespace palpation::ui
