// The workstation's main window: the 3-D view in the centre, instructor panels in docks,
// menus, toolbar, status bar (backend, step rate, haptic rate, device state). The GUI
// thread polls the workstation at 60 Hz and never waits on physics.
#pragma once

#include <memory>

#include <QMainWindow>
#include <QTranslator>

#include <QPointer>

#include "live/workstation.h"

namespace palpation::app::store {
class PatientLibrary;
}
namespace palpation::app::review {
class WorkstationRecorder;
}

class QAction;
class QActionGroup;
class QDockWidget;
class QLabel;
class QMenu;
class QTimer;
class QToolBar;

namespace palpation::ui {

class DevicePanel;
class ImportDialog;
class ReviewWindow;
class ForcePlots;
class PatientPanel;
class SimulationPanel;
class TumourEditor;
class TumourPanel;
class VtkView;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  /// Starts `ws` (the window owns it) and records the session into
  /// `record_path`, or, when empty, a new file in the recordings folder
  /// (recordings_folder()); interrupted recordings there are recovered first.
  explicit MainWindow(std::unique_ptr<app::live::Workstation> ws, QWidget* parent = nullptr, const QString& record_path = {});
  ~MainWindow() override;

  app::live::Workstation& workstation() { return *ws_; }
  VtkView* view() const { return view_; }
  TumourEditor* editor() const { return editor_; }
  ForcePlots* plots() const { return plots_; }
  QList<QDockWidget*> instructor_docks() const;
  QDockWidget* forces_dock() const { return forces_dock_; }
  TumourPanel* tumour_panel() const { return tumour_panel_; }
  PatientPanel* patient_panel() const { return patient_panel_; }

  // Issue 6 -------------------------------------------------------------------------
  /// Where GUI sessions record: $PALPATION_RECORDINGS, else <app data>/recordings.
  static QString recordings_folder();
  /// The patient library (null when it could not be opened; the reason is in library_error()).
  app::store::PatientLibrary* library() const { return library_.get(); }
  QString library_error() const { return library_error_; }
  app::review::WorkstationRecorder* recorder() const { return recorder_.get(); }
  /// Chooses a patient (library name or "phantom:breast" / "phantom:box") and loads it.
  /// False (and `error` set) when it is unknown or cannot be built.
  bool choose_patient(const QString& name, QString* error = nullptr);
  /// The trainee's "I feel a lump here": marks the index fingertip's position in the
  /// recording. Returns the mark's number, 0 when no fingertip is on the body.
  int mark_lump();
  /// Opens a recording for review (a separate window). Null, with `error` set (file,
  /// chunk, offset, reason), for a bad file; nothing is written.
  ReviewWindow* open_recording(const QString& path, QString* error = nullptr);
  ReviewWindow* review_window() const;
  ImportDialog* open_import_dialog();
  void refresh_patients();

  /// Trainee mode: tumours hidden, instructor panels locked, mouse palpation.
  void set_trainee(bool on);
  bool trainee() const { return trainee_; }
  /// "en" or "ja". False when the translation is missing.
  bool set_language(const QString& code);
  QString language() const { return language_; }
  /// True once the first patient is on screen.
  bool patient_ready() const { return generation_ != 0; }
  /// Frames drawn per second over the last second.
  double frame_rate() const { return fps_; }

 public slots:
  void tick();

 protected:
  void closeEvent(QCloseEvent* e) override;
  void changeEvent(QEvent* e) override;

 private:
  void build_actions();
  void retranslate();
  void update_status();

  std::unique_ptr<app::live::Workstation> ws_;
  VtkView* view_ = nullptr;
  TumourEditor* editor_ = nullptr;
  ForcePlots* plots_ = nullptr;
  PatientPanel* patient_panel_ = nullptr;
  TumourPanel* tumour_panel_ = nullptr;
  SimulationPanel* sim_panel_ = nullptr;
  DevicePanel* device_panel_ = nullptr;
  QDockWidget *patient_dock_ = nullptr, *tumour_dock_ = nullptr, *forces_dock_ = nullptr, *sim_dock_ = nullptr,
              *device_dock_ = nullptr;
  QLabel *st_backend_ = nullptr, *st_step_ = nullptr, *st_haptic_ = nullptr, *st_device_ = nullptr, *st_fps_ = nullptr;
  QMenu *file_menu_ = nullptr, *edit_menu_ = nullptr, *view_menu_ = nullptr, *stereo_menu_ = nullptr, *camera_menu_ = nullptr,
        *mode_menu_ = nullptr, *lang_menu_ = nullptr, *panels_menu_ = nullptr;
  QToolBar* toolbar_ = nullptr;
  QAction *a_screenshot_ = nullptr, *a_quit_ = nullptr, *a_undo_ = nullptr, *a_redo_ = nullptr, *a_colour_ = nullptr, *a_stress_ = nullptr,
          *a_tumours_ = nullptr, *a_mirror_ = nullptr, *a_fast_ = nullptr, *a_eye_ = nullptr, *a_trainee_ = nullptr, *a_instructor_ = nullptr,
          *a_camera_tool_ = nullptr, *a_palpate_tool_ = nullptr, *a_en_ = nullptr, *a_ja_ = nullptr;
  QAction* a_stereo_[5] = {};
  QAction* a_cam_[4] = {};
  QTimer* timer_ = nullptr;
  QTranslator translator_;
  QString language_ = QStringLiteral("en");
  std::uint64_t generation_ = 0;
  bool trainee_ = false;
  int frame_count_ = 0;
  qint64 fps_t0_ = 0, last_status_ = 0, last_plot_ = 0;
  double fps_ = 0;
  sim::Scenario scenario_;
  sim::Scenario chosen_;  // the chosen patient, before the panel's resolution and tissue
  std::unique_ptr<app::store::PatientLibrary> library_;
  QString library_error_;
  std::unique_ptr<app::review::WorkstationRecorder> recorder_;
  QPointer<ReviewWindow> review_;
  QPointer<ImportDialog> import_;
  QAction *a_open_rec_ = nullptr, *a_mark_ = nullptr;
  QLabel* st_rec_ = nullptr;
  qint64 last_flush_ = 0;
};

}  // namespace palpation::ui
