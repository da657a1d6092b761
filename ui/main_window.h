// The workstation's main window: the 3-D view in the centre, instructor panels in docks,
// menus, toolbar, status bar (backend, step rate, haptic rate, device state, training mode).
// The GUI thread polls the workstation at 60 Hz and never waits on physics.
//
// Training modes (app/live/training_session.h): in Instructor mode everything shows; in
// Guided practice and Exam whatever reveals where or how stiff the tumours are is hidden,
// not greyed: the instructor docks (patient, tumours, simulation, device), the tumour
// outlines and colour maps of the 3-D view, undo/redo (its text names the edits), opening
// recordings, the instructor's events in the status bar, and the patient's name (the
// trainee reads an anonymous case code).
#pragma once

#include <memory>

#include <QMainWindow>
#include <QTranslator>

#include <QPointer>

#include "live/training_session.h"
#include "live/workstation.h"

namespace palpation::app::store {
class PatientLibrary;
}
namespace palpation::app::review {
class WorkstationRecorder;
}

class QAction;
class QActionGroup;
class QComboBox;
class QDockWidget;
class QLabel;
class QMenu;
class QTimer;
class QToolBar;

namespace palpation::ui {

class DevicePanel;
class ImportDialog;
class PressureDialog;
class ProgressWindow;
class ReviewWindow;
class ScoreDialog;
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
  /// The session starts in training mode `mode` (recorded in the recording's settings).
  explicit MainWindow(std::unique_ptr<app::live::Workstation> ws, QWidget* parent = nullptr, const QString& record_path = {},
                      app::live::TrainingMode mode = app::live::TrainingMode::Instructor);
  ~MainWindow() override;

  app::live::Workstation& workstation() { return *ws_; }
  VtkView* view() const { return view_; }
  TumourEditor* editor() const { return editor_; }
  ForcePlots* plots() const { return plots_; }
  QList<QDockWidget*> instructor_docks() const;
  QDockWidget* forces_dock() const { return forces_dock_; }
  QDockWidget* tumour_dock() const { return tumour_dock_; }
  TumourPanel* tumour_panel() const { return tumour_panel_; }
  PatientPanel* patient_panel() const { return patient_panel_; }

  // Sessions, recordings, marks ------------------------------------------------------
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
  /// recording with the confidence chosen in the toolbar (training().mark_confidence()).
  /// Returns the mark's number, 0 when no fingertip is on the body or the exam has ended.
  int mark_lump();
  /// The same with a confidence of its own (0..1).
  int mark_lump(double confidence);
  /// Opens a recording for review (a separate window). Null, with `error` set (file,
  /// chunk, offset, reason), for a bad file; nothing is written.
  ReviewWindow* open_recording(const QString& path, QString* error = nullptr);
  ReviewWindow* review_window() const;
  ImportDialog* open_import_dialog();
  void refresh_patients();

  /// The training mode, set at once (no confirmation: the command line, tests). Trainee
  /// modes hide the instructor's panels and switch to mouse palpation.
  void set_mode(app::live::TrainingMode m);
  app::live::TrainingMode mode() const { return training_->mode(); }
  /// What the Mode menu does: asks the instructor to confirm where the change needs it
  /// (back to Instructor, out of a running exam); true when the mode changed.
  bool request_mode(app::live::TrainingMode m);
  app::live::TrainingSession& training() { return *training_; }
  /// Ends the running exam (the End exam action, after its confirmation): logged, the
  /// training session's exam-end listeners and examEnded() told. False when none runs.
  bool end_exam();
  /// Guided practice (on) or Instructor (off), at once.
  void set_trainee(bool on);
  bool trainee() const { return app::live::is_trainee(training_->mode()); }
  /// The toolbar's confidence choice for the next mark.
  QComboBox* confidence_box() const { return confidence_; }
  /// No dock/toolbar toggle menu in trainee modes (it would bring the docks back).
  QMenu* createPopupMenu() override;
  // Training feedback -------------------------------------------------------------------
  /// View > Coverage overlay: the skin coloured by the pressure level reached, shown in
  /// Instructor mode and Guided practice while checked, never in Exam.
  QAction* coverage_action() const { return a_coverage_; }
  /// The coverage figures and legend, a toolbar row of their own (hidden in Exam).
  QLabel* coverage_label() const { return st_coverage_; }
  /// The score of the exam that ended last, shown when it ended (null once closed, or
  /// when a new exam started).
  ScoreDialog* score_dialog() const;
  /// Whose session this is (the library's trainee the results are stored under); empty:
  /// anonymous. Entering a trainee mode from the Mode menu asks when none is set.
  void set_trainee_name(const QString& name);
  QString trainee_name() const { return trainee_name_; }
  /// The instructor's progress window (Mode > Trainee progress..., Instructor mode only):
  /// null in a trainee mode or without a library.
  ProgressWindow* open_progress_window();
  ProgressWindow* progress_window() const;
  /// Mode > Pressure levels... (Instructor mode): the dialog, opened non-modal; null in a
  /// trainee mode.
  PressureDialog* open_pressure_dialog();
  /// The thresholds for the exams from now on: the live exam's, kept in QSettings and, as
  /// a "thresholds" event, in the recording (palpation score and the review use them).
  void set_pressure_thresholds(const app::train::PressureThresholds& t);
  /// Mode > Curriculum: works through a curriculum file (train/curriculum.h; ":/curricula/..."
  /// for the built-in ones) and loads the trainee's first case not yet passed. False with
  /// `error` set for a bad file or a case that cannot be loaded (the running patient stays).
  bool set_curriculum(const QString& path, QString* error = nullptr);
  /// No curriculum: free exams again.
  void clear_curriculum();
  /// Mode > Next curriculum case: the trainee's first case of the curriculum not yet passed
  /// (by the library's results), loaded as the patient; in a trainee mode whose exam has
  /// ended a new exam starts on it. False with `error` when there is no curriculum, every
  /// case is passed, or the case cannot be loaded.
  bool next_curriculum_case(QString* error = nullptr);
  /// The patient as results, recordings and the anonymous case code name it: the patient
  /// panel's choice, or the case's name for a case that is not in the library (a generated
  /// curriculum case, or `palpation-trainer --case FILE`: set_case_name).
  QString patient_name() const;
  void set_case_name(const QString& name) { case_name_ = name; }
  /// The curriculum status line ("Curriculum cbe-basics: case 2 of 6"), empty without one.
  QString curriculum_text() const;

  /// "en" or "ja". False when the translation is missing.
  bool set_language(const QString& code);
  QString language() const { return language_; }
  /// True once the first patient is on screen.
  bool patient_ready() const { return generation_ != 0; }
  /// Frames drawn per second over the last second.
  double frame_rate() const { return fps_; }

 public slots:
  void tick();

 signals:
  /// A trainee's exam (or guided practice) ended (end_exam, or leaving its mode).
  void examEnded();

 protected:
  void closeEvent(QCloseEvent* e) override;
  void changeEvent(QEvent* e) override;

 private:
  void build_actions();
  void retranslate();
  void update_status();
  /// Shows and hides what the mode allows (no event logged).
  void apply_mode();
  QString mode_text() const;
  /// The coverage overlay and figures as the mode and the toggle allow (no event logged).
  void update_coverage();
  /// The end of an exam: stores the result for the trainee and shows the score.
  void exam_scored();
  /// Asks who the trainee is (the library's trainees, or a new name); false when cancelled.
  bool ask_trainee();

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
          *a_tumours_ = nullptr, *a_mirror_ = nullptr, *a_fast_ = nullptr, *a_eye_ = nullptr, *a_instructor_ = nullptr,
          *a_camera_tool_ = nullptr, *a_palpate_tool_ = nullptr, *a_en_ = nullptr, *a_ja_ = nullptr;
  QAction* a_stereo_[5] = {};
  QAction* a_cam_[4] = {};
  QTimer* timer_ = nullptr;
  QTranslator translator_;
  QString language_ = QStringLiteral("en");
  std::uint64_t generation_ = 0;
  std::unique_ptr<app::live::TrainingSession> training_;
  QAction *a_practice_ = nullptr, *a_exam_ = nullptr, *a_end_exam_ = nullptr;
  QComboBox* confidence_ = nullptr;
  QAction* a_confidence_ = nullptr;  // the toolbar's confidence_
  QLabel* st_mode_ = nullptr;
  QList<bool> docks_shown_;  // the instructor docks' visibility when a trainee mode hid them
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
  QPointer<ScoreDialog> score_;
  QPointer<ProgressWindow> progress_;
  QAction *a_coverage_ = nullptr, *a_clear_coverage_ = nullptr, *a_progress_ = nullptr;
  QAction *a_thresholds_ = nullptr, *a_next_case_ = nullptr, *a_no_curriculum_ = nullptr, *a_open_curriculum_ = nullptr;
  QList<QAction*> a_builtin_curricula_;
  QMenu* curriculum_menu_ = nullptr;
  QLabel* st_curriculum_ = nullptr;
  QPointer<PressureDialog> pressure_;
  QString case_name_;  // patient_name() of a case outside the library
  /// Loads curriculum case `i` as the patient (library patient or generated case).
  bool load_curriculum_case(std::size_t i, QString* error);
  QLabel* st_coverage_ = nullptr;
  QToolBar* coverage_bar_ = nullptr;  // st_coverage_'s row
  QString trainee_name_;
  QAction *a_open_rec_ = nullptr, *a_mark_ = nullptr;
  QLabel* st_rec_ = nullptr;
  qint64 last_flush_ = 0;
};

}  // namespace palpation::ui
