#include "main_window.h"

#include <algorithm>

#include <QActionGroup>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QListWidget>
#include <QPushButton>
#include <QSpinBox>
#include <QToolButton>
#include <QApplication>
#include <QCloseEvent>
#include <QDateTime>
#include <QFile>
#include <QFileInfo>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QInputDialog>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QUndoStack>

#include <QStandardPaths>

#include "event_text.h"
#include "force_plots.h"
#include "live/patient_choice.h"
#include "import_dialog.h"
#include "panels.h"
#include "pressure_dialog.h"
#include "progress_window.h"
#include "score_dialog.h"
#include "train/case_generator.h"
#include "train/curriculum.h"
#include "store/patient_library.h"
#include "review_window.h"
#include "scan/scan_import_job.h"
#include "review/workstation_recorder.h"
#include "tumour_editor.h"
#include "vtk_view.h"

// resources/palpation.qrc (icons, the built-in curricula) is compiled into this static
// library; an archive member nothing refers to is not linked, so the executables had no
// icons and no curricula. Q_INIT_RESOURCE refers to it (it must be called outside any
// namespace).
static void init_palpation_resources() { Q_INIT_RESOURCE(palpation); }

namespace palpation::ui {

MainWindow::MainWindow(std::unique_ptr<app::live::Workstation> ws, QWidget* parent, const QString& record_path,
                       app::live::TrainingMode mode)
    : QMainWindow(parent), ws_(std::move(ws)), training_(std::make_unique<app::live::TrainingSession>(*ws_, mode)) {
  init_palpation_resources();
  setObjectName(QStringLiteral("MainWindow"));
  setWindowIcon(QIcon(QStringLiteral(":/icons/palpation.png")));
  scenario_ = ws_->options().scenario;
  chosen_ = scenario_;
  view_ = new VtkView(this);
  setCentralWidget(view_);
  editor_ = new TumourEditor(ws_.get(), this);

  auto dock = [this](QWidget* w, const char* name, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(this);
    d->setObjectName(QString::fromLatin1(name));
    d->setWidget(w);
    addDockWidget(area, d);
    return d;
  };
  patient_panel_ = new PatientPanel;
  try {
    // The CLI's library (palpation patient ...): $PALPATION_DB, else <data>/palpation/patients.sqlite.
    app::store::PatientLibrary::Options lo;
    if (qEnvironmentVariableIsEmpty("PALPATION_DB"))
      lo.db = (QStandardPaths::writableLocation(QStandardPaths::GenericDataLocation) + QStringLiteral("/palpation/patients.sqlite"))
                  .toStdString();
    library_ = std::make_unique<app::store::PatientLibrary>(lo);
  } catch (const std::exception& e) {
    library_error_ = QString::fromStdString(e.what());
  }
  refresh_patients();
  if (!patient_panel_->select_patient(QString::fromStdString(scenario_.source)))
    patient_panel_->select_patient(scenario_.patient.phantom == "box" ? QStringLiteral("phantom:box") : QStringLiteral("phantom:breast"));
  patient_panel_->show_scenario(scenario_);
  tumour_panel_ = new TumourPanel(editor_);
  sim_panel_ = new SimulationPanel;
  // What runs (the default patient's real-time settings, app/live/workstation.cpp), not the
  // scenario defaults.
  sim_panel_->tolerance->setValue(scenario_.params.solver.cg_tolerance);
  sim_panel_->iterations->setValue(scenario_.params.solver.cg_max_iterations);
  sim_panel_->force_error->setValue(100 * scenario_.params.solver.force_error);
  device_panel_ = new DevicePanel(ws_->device_config().hand.capabilities.max_force);
  if (!ws_->simulated_device()) {
    // A link (emulator or robot): fixed at start (--device); the mouse needs the simulated device.
    device_panel_->mode->setEnabled(false);
    device_panel_->address->setText(QString::fromStdString(ws_->device_description()));
  }
  plots_ = new ForcePlots;
  patient_dock_ = dock(patient_panel_, "PatientDock", Qt::LeftDockWidgetArea);
  tumour_dock_ = dock(tumour_panel_, "TumourDock", Qt::LeftDockWidgetArea);
  sim_dock_ = dock(sim_panel_, "SimulationDock", Qt::RightDockWidgetArea);
  device_dock_ = dock(device_panel_, "DeviceDock", Qt::RightDockWidgetArea);
  forces_dock_ = dock(plots_, "ForcesDock", Qt::BottomDockWidgetArea);
  tabifyDockWidget(patient_dock_, tumour_dock_);
  tumour_dock_->raise();
  tabifyDockWidget(sim_dock_, device_dock_);
  sim_dock_->raise();
  resizeDocks({forces_dock_}, {260}, Qt::Vertical);
  resizeDocks({tumour_dock_, sim_dock_}, {330, 260}, Qt::Horizontal);

  st_backend_ = new QLabel;
  st_step_ = new QLabel;
  st_haptic_ = new QLabel;
  st_device_ = new QLabel;
  st_fps_ = new QLabel;
  st_rec_ = new QLabel;
  st_mode_ = new QLabel;
  st_mode_->setObjectName(QStringLiteral("TrainingModeLabel"));
  st_curriculum_ = new QLabel;
  st_curriculum_->setObjectName(QStringLiteral("CurriculumLabel"));
  st_coverage_ = new QLabel;
  st_coverage_->setObjectName(QStringLiteral("CoverageLabel"));
  st_coverage_->setTextFormat(Qt::RichText);
  for (auto* l : {st_mode_, st_curriculum_, st_backend_, st_step_, st_haptic_, st_device_, st_fps_, st_rec_}) statusBar()->addPermanentWidget(l);

  build_actions();

  // Panels -> commands.
  connect(patient_panel_, &PatientPanel::loadRequested, this, [this] {
    scenario_ = patient_panel_->scenario(chosen_);
    scenario_.backend = sim_panel_->backend->currentText().toStdString();
    ws_->load_patient(scenario_);
    QSettings().setValue(QStringLiteral("patient/resolution"), QString::fromStdString(scenario_.patient.resolution));
    QSettings().setValue(QStringLiteral("patient/name"), patient_panel_->chosen());
  });
  connect(patient_panel_, &PatientPanel::patientChosen, this, [this](const QString& name) {
    QString err;
    if (!choose_patient(name, &err)) QMessageBox::warning(this, tr("Patient"), err);
  });
  connect(patient_panel_, &PatientPanel::importRequested, this, [this] { open_import_dialog(); });
  connect(sim_panel_->apply, &QPushButton::clicked, this, [this] {
    sim::SimParams p = scenario_.params;
    p.solver.cg_tolerance = sim_panel_->tolerance->value();
    p.solver.cg_max_iterations = sim_panel_->iterations->value();
    p.solver.force_error = sim_panel_->force_error->value() / 100;
    scenario_.params = p;
    ws_->set_params(p);
  });
  connect(device_panel_->mode, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) {
    ws_->device().set_mode(i == 1 ? app::live::HandMode::Mouse : app::live::HandMode::Script);
    if (i == 1) ws_->set_mouse_finger(Eigen::Vector3d::Zero(), false);
    view_->set_tool(i == 1 ? VtkView::Tool::Palpate : VtkView::Tool::Camera);
    if (i == 1)
      statusBar()->showMessage(tr("Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in."), 8000);
    ws_->log_event(app::live::Event::mode_change(i == 1 ? app::live::ModeChange::MousePalpation : app::live::ModeChange::ScriptedHand));
  });
  connect(tumour_panel_->add, &QPushButton::clicked, this, [this] {
    Eigen::Vector3d c, r;
    for (int i = 0; i < 3; ++i) {
      c[i] = tumour_panel_->centre[i]->value() * 0.01;
      r[i] = tumour_panel_->radii[i]->value() * 0.01;
    }
    const int n = editor_->add_shape(tumour_panel_->chosen_shape(), c, r, tumour_panel_->preset_young());
    if (n == 0) statusBar()->showMessage(tr("No element lies inside that shape: nothing added."), 5000);
  });
  connect(tumour_panel_->remove, &QPushButton::clicked, this, [this] { editor_->remove_tumour(tumour_panel_->list->currentRow()); });
  connect(tumour_panel_, &TumourPanel::toolRequested, this, [this](int t) {
    view_->set_tool(t == 1 ? VtkView::Tool::Paint : t == 2 ? VtkView::Tool::Erase : VtkView::Tool::Camera);
  });
  connect(view_, &VtkView::brushStrokeStarted, this, [this] {
    if (trainee()) return;
    editor_->set_brush(tumour_panel_->brush_radius->value() * 0.01, tumour_panel_->brush_depth->value() * 0.01,
                       tumour_panel_->preset_young());
    editor_->begin_stroke(view_->tool() == VtkView::Tool::Erase);
  });
  connect(view_, &VtkView::brushDab, this, [this](const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    if (!trainee()) editor_->dab(p, n);
  });
  connect(view_, &VtkView::brushStrokeEnded, this, [this] { editor_->end_stroke(); });
  connect(view_, &VtkView::palpateTarget, this, [this](const Eigen::Vector3d& c, bool present) {
    if (ws_->device().mode() != app::live::HandMode::Mouse) {
      ws_->device().set_mode(app::live::HandMode::Mouse);
    }
    ws_->set_mouse_finger(c, present);
  });
  connect(editor_, &TumourEditor::changed, this, [this] { view_->show_tumours(ws_->tumours()); });
  ws_->add_tick_listener([this](const app::live::TickSample& s) { plots_->add_sample(s); });
  ws_->add_step_listener([this](const app::live::StepSample& s) { plots_->add_step_sample(s); });
  plots_->set_device_limit(std::min(ws_->device_config().loop.safety.max_force, ws_->device_config().hand.capabilities.max_force));
  ws_->add_event_listener([this](const app::live::Event& e) {
    // A trainee does not read the instructor's events (a patient's name, a tumour's modulus).
    if (!trainee() || app::live::shown_to_trainee(e)) statusBar()->showMessage(EventText::event(e), 4000);
  });
  training_->add_exam_end_listener([this](const app::live::Event&) {
    apply_mode();
    exam_scored();
    emit examEnded();
  });

  QSettings settings;
  restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
  restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
  const int stereo = settings.value(QStringLiteral("view/stereo"), 0).toInt();
  if (stereo > 0 && stereo < 4) a_stereo_[stereo]->trigger();
  a_mirror_->setChecked(settings.value(QStringLiteral("view/mirrored"), false).toBool());
  a_coverage_->setChecked(settings.value(QStringLiteral("view/coverage_overlay"), false).toBool());
  // The pressure levels the instructor set last (Mode > Pressure levels...); stored ones that
  // no longer validate are dropped with a message, the defaults apply.
  const QString stored_levels = settings.value(QStringLiteral("training/thresholds")).toString();
  if (!stored_levels.isEmpty()) {
    try {
      training_->exam().set_thresholds(app::train::thresholds_from_json(nlohmann::json::parse(stored_levels.toStdString())));
    } catch (const std::exception& e) {
      statusBar()->showMessage(tr("Stored pressure levels not used (defaults apply): %1").arg(QString::fromStdString(e.what())), 10000);
    }
  }
  // PALPATION_FAST_RENDER=0/1 (the view bench, docs/gui.md) overrides the stored choice.
  const QByteArray fast_env = qgetenv("PALPATION_FAST_RENDER");
  if (!fast_env.isEmpty())
    view_->set_render_style(fast_env == "0" ? VtkView::RenderStyle::Full : VtkView::RenderStyle::Light);
  else if (settings.contains(QStringLiteral("view/fast_rendering")))
    view_->set_render_style(settings.value(QStringLiteral("view/fast_rendering")).toBool() ? VtkView::RenderStyle::Light
                                                                                          : VtkView::RenderStyle::Full);
  set_language(settings.value(QStringLiteral("language"), QStringLiteral("en")).toString());
  retranslate();
  apply_mode();  // after restoreState: a trainee mode hides what it brought back

  timer_ = new QTimer(this);
  timer_->setTimerType(Qt::PreciseTimer);
  connect(timer_, &QTimer::timeout, this, &MainWindow::tick);
  timer_->start(16);
  fps_t0_ = QDateTime::currentMSecsSinceEpoch();

  // Every session records: interrupted recordings of earlier sessions first.
  const QString folder = recordings_folder();
  QDir().mkpath(folder);
  QStringList recovered;
  for (const auto& line : app::review::recover_interrupted_recordings(folder.toStdString())) recovered << QString::fromStdString(line);
  QString path = record_path;
  if (path.isEmpty())
    path = QDir(folder).filePath(QStringLiteral("session-%1.palrec").arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-HHmmss-zzz"))));
  try {
    nlohmann::json recorded_settings{{"language", language_.toStdString()},
                            {"trainee", trainee()},
                            {"mode", app::live::training_mode_name(training_->mode())},
                            {"stereo", int(view_->stereo())},
                            {"patient", patient_name().toStdString()},
                            {"library", library_ ? library_->location() : std::string()},
                            {"thresholds", app::train::to_json(training_->exam().thresholds())}};
    recorder_ = std::make_unique<app::review::WorkstationRecorder>(*ws_, path.toStdString(), recorded_settings);
    // A session started in a trainee mode: its exam starts with the recording.
    if (trainee()) ws_->log_event(app::live::Event::mode_change(app::live::mode_change_of(training_->mode())));
  } catch (const std::exception& e) {
    statusBar()->showMessage(tr("This session is not recorded: %1").arg(QString::fromStdString(e.what())));
  }
  if (!recovered.isEmpty()) statusBar()->showMessage(tr("Recovered interrupted recordings: %1").arg(recovered.join(QStringLiteral("; "))), 15000);
  if (!library_error_.isEmpty())
    statusBar()->showMessage(tr("Patient library not available (built-in phantoms only): %1").arg(library_error_), 15000);
  ws_->start();
}

MainWindow::~MainWindow() {
  ws_->stop();
  if (recorder_) {
    ws_->poll();  // the last telemetry into the recording
    recorder_->close();
  }
  delete review_.data();
  delete import_.data();
}

QString MainWindow::recordings_folder() {
  const QString env = qEnvironmentVariable("PALPATION_RECORDINGS");
  if (!env.isEmpty()) return env;
  return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/recordings");
}

void MainWindow::refresh_patients() {
  QList<PatientPanel::Entry> entries;
  if (library_) {
    try {
      for (const auto& p : library_->list())
        entries.append({QString::fromStdString(p.name), QString::fromStdString(p.category), QString::fromStdString(p.description),
                        p.builtin});
    } catch (const std::exception& e) {
      library_error_ = QString::fromStdString(e.what());
    }
  }
  patient_panel_->set_patients(entries);
}

bool MainWindow::choose_patient(const QString& name, QString* error) {
  sim::Scenario s;
  try {
    if (auto phantom = app::live::phantom_patient(name.toStdString())) {
      s = *phantom;
    } else {
      if (!library_) throw std::runtime_error(tr("no patient library is open: %1").arg(library_error_).toStdString());
      const auto rec = library_->find(name.toStdString());
      if (!rec) throw std::runtime_error(library_->location() + ": no patient named \"" + name.toStdString() + "\"");
      s = app::scan::library_patient_scenario(
          *rec, (QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/meshes")).toStdString());
      // The workstation's resolution, not the library's default (phantoms only).
      app::live::set_phantom_resolution(s, patient_panel_->resolution->currentData().toString().toStdString());
    }
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  // The solver settings are the workstation's (Simulation panel), not the patient's.
  s.params.solver = scenario_.params.solver;
  chosen_ = s;
  case_name_.clear();
  patient_panel_->select_patient(name);
  patient_panel_->show_scenario(s);
  scenario_ = patient_panel_->scenario(chosen_);
  scenario_.backend = sim_panel_->backend->currentText().toStdString();
  ws_->load_patient(scenario_);
  QSettings().setValue(QStringLiteral("patient/name"), name);
  QSettings().setValue(QStringLiteral("patient/resolution"), QString::fromStdString(scenario_.patient.resolution));
  return true;
}

int MainWindow::mark_lump() { return mark_lump(training_->mark_confidence()); }

int MainWindow::mark_lump(double confidence) {
  if (!training_->accepts_marks()) {
    statusBar()->showMessage(tr("The exam has ended: nothing marked."), 5000);
    return 0;
  }
  const auto& snap = ws_->snapshot();
  const int k = device::kIndex;
  if (!snap.finger_active[k] || !recorder_) {
    statusBar()->showMessage(recorder_ ? tr("No fingertip on the breast: nothing marked.") : tr("This session is not recorded: nothing marked."), 5000);
    return 0;
  }
  confidence = std::clamp(confidence, 0.0, 1.0);
  const Eigen::Vector3d p = snap.finger_position[k];
  const int n = recorder_->add_mark(p, {}, confidence);
  // The same mark into the live exam: scored with it when the exam ends.
  training_->note_mark(p, confidence);
  ws_->log_event(app::live::Event::trainee_mark(n, std::nullopt, {}, confidence));
  statusBar()->showMessage(tr("Mark %1: \"I feel a lump here\" at (%2, %3, %4) cm, %5 % confident, recorded.")
                               .arg(n)
                               .arg(p.x() * 100, 0, 'f', 1)
                               .arg(p.y() * 100, 0, 'f', 1)
                               .arg(p.z() * 100, 0, 'f', 1)
                               .arg(confidence * 100, 0, 'f', 0),
                           6000);
  return n;
}

ReviewWindow* MainWindow::open_recording(const QString& path, QString* error) {
  std::unique_ptr<app::review::ReviewSession> s;
  try {
    s = std::make_unique<app::review::ReviewSession>(path.toStdString());
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return nullptr;
  }
  delete review_.data();
  review_ = new ReviewWindow(std::move(s), this);
  review_->setWindowFlag(Qt::Window);
  review_->show();
  return review_;
}

ReviewWindow* MainWindow::review_window() const { return review_.data(); }

ImportDialog* MainWindow::open_import_dialog() {
  if (!import_) {
    import_ = new ImportDialog(library_.get(), this);
    connect(import_, &ImportDialog::patientSaved, this, [this](const QString& name) {
      refresh_patients();
      patient_panel_->select_patient(name);
      statusBar()->showMessage(tr("Patient \"%1\" saved; choose it and Load patient to palpate it.").arg(name), 8000);
    });
  }
  import_->show();
  import_->raise();
  return import_;
}

QList<QDockWidget*> MainWindow::instructor_docks() const { return {patient_dock_, tumour_dock_, sim_dock_, device_dock_}; }

void MainWindow::build_actions() {
  file_menu_ = menuBar()->addMenu(QString());
  a_open_rec_ = file_menu_->addAction(QString(), this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Open a session recording"), recordings_folder(),
                                                   tr("Session recordings (*.palrec *.prec);;All files (*)"));
    if (f.isEmpty()) return;
    QString err;
    if (!open_recording(f, &err)) QMessageBox::critical(this, tr("Cannot open the recording"), err);
  });
  a_open_rec_->setShortcut(QKeySequence::Open);
  a_screenshot_ = file_menu_->addAction(QString(), this, [this] {
    const QString f = QFileDialog::getSaveFileName(this, tr("Save screenshot"), QStringLiteral("screenshot.png"), tr("PNG images (*.png)"));
    if (!f.isEmpty()) VtkView::grab_with_views(this).save(f);
  });
  file_menu_->addSeparator();
  a_quit_ = file_menu_->addAction(QString(), this, &QWidget::close);
  a_quit_->setShortcut(QKeySequence::Quit);

  edit_menu_ = menuBar()->addMenu(QString());
  a_undo_ = editor_->undo_stack()->createUndoAction(this);
  a_undo_->setShortcut(QKeySequence::Undo);
  a_redo_ = editor_->undo_stack()->createRedoAction(this);
  a_redo_->setShortcut(QKeySequence::Redo);
  a_undo_->setIcon(QIcon(QStringLiteral(":/icons/undo.png")));
  a_redo_->setIcon(QIcon(QStringLiteral(":/icons/redo.png")));
  edit_menu_->addAction(a_undo_);
  edit_menu_->addAction(a_redo_);

  view_menu_ = menuBar()->addMenu(QString());
  camera_menu_ = view_menu_->addMenu(QString());
  for (int i = 0; i < 4; ++i)
    a_cam_[i] = camera_menu_->addAction(QString(), this, [this, i] { view_->set_camera(VtkView::CameraPreset(i)); });
  stereo_menu_ = view_menu_->addMenu(QString());
  auto* sg = new QActionGroup(this);
  for (int i = 0; i < 5; ++i) {
    a_stereo_[i] = stereo_menu_->addAction(QString());
    a_stereo_[i]->setCheckable(true);
    sg->addAction(a_stereo_[i]);
    connect(a_stereo_[i], &QAction::triggered, this, [this, i] {
      QString why;
      if (!view_->set_stereo(VtkView::Stereo(i), &why)) {
        QMessageBox::information(this, tr("Stereo"), why);
        a_stereo_[int(view_->stereo())]->setChecked(true);
        return;
      }
      QSettings().setValue(QStringLiteral("view/stereo"), i);
    });
  }
  a_stereo_[0]->setChecked(true);
  a_eye_ = stereo_menu_->addAction(QString(), this, [this] {
    bool ok = false;
    const double v = QInputDialog::getDouble(this, tr("Eye separation"), tr("Eye angle (degrees):"), 2.0, 0.1, 10.0, 1, &ok);
    if (ok) view_->set_eye_angle(v);
  });
  a_mirror_ = view_menu_->addAction(QString());
  a_mirror_->setCheckable(true);
  connect(a_mirror_, &QAction::toggled, this, [this](bool on) {
    view_->set_mirrored(on);
    QSettings().setValue(QStringLiteral("view/mirrored"), on);
  });
  // The light rendering style (docs/gui.md): on by itself under software OpenGL; the
  // user's choice, once made, is stored and wins.
  a_fast_ = view_menu_->addAction(QString());
  a_fast_->setObjectName(QStringLiteral("fast_rendering"));
  a_fast_->setCheckable(true);
  connect(a_fast_, &QAction::triggered, this, [this](bool on) {
    view_->set_render_style(on ? VtkView::RenderStyle::Light : VtkView::RenderStyle::Full);
    QSettings().setValue(QStringLiteral("view/fast_rendering"), on);
  });
  connect(view_, &VtkView::lightStyleChanged, a_fast_, &QAction::setChecked);
  a_colour_ = view_menu_->addAction(QString());
  a_colour_->setCheckable(true);
  // Colour maps, at most one: displacement, or stress (the simulation thread computes
  // nodal von Mises stress only while that one is on).
  a_stress_ = view_menu_->addAction(QString());
  a_stress_->setCheckable(true);
  auto* colour_group = new QActionGroup(this);
  colour_group->setExclusionPolicy(QActionGroup::ExclusionPolicy::ExclusiveOptional);
  colour_group->addAction(a_colour_);
  colour_group->addAction(a_stress_);
  auto apply_colour = [this] {
    ws_->set_stress_enabled(a_stress_->isChecked());
    view_->set_colour_mode(a_stress_->isChecked()   ? VtkView::ColourMap::Stress
                           : a_colour_->isChecked() ? VtkView::ColourMap::Displacement
                                                    : VtkView::ColourMap::None);
  };
  connect(a_colour_, &QAction::toggled, this, apply_colour);
  connect(a_stress_, &QAction::toggled, this, apply_colour);
  a_tumours_ = view_menu_->addAction(QString());
  a_tumours_->setCheckable(true);
  a_tumours_->setChecked(true);
  connect(a_tumours_, &QAction::toggled, view_, &VtkView::set_tumours_visible);
  // The coverage overlay (Instructor and Guided practice; never in Exam: update_coverage).
  view_menu_->addSeparator();
  a_coverage_ = view_menu_->addAction(QString());
  a_coverage_->setObjectName(QStringLiteral("coverage_overlay"));
  a_coverage_->setCheckable(true);
  a_coverage_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+C")));
  connect(a_coverage_, &QAction::toggled, this, [this](bool on) {
    QSettings().setValue(QStringLiteral("view/coverage_overlay"), on);
    update_coverage();
  });
  a_clear_coverage_ = view_menu_->addAction(QString(), this, [this] {
    training_->clear_coverage();
    update_coverage();
  });
  a_clear_coverage_->setObjectName(QStringLiteral("clear_coverage"));
  view_menu_->addSeparator();
  panels_menu_ = view_menu_->addMenu(QString());
  for (auto* d : {patient_dock_, tumour_dock_, forces_dock_, sim_dock_, device_dock_}) panels_menu_->addAction(d->toggleViewAction());

  // The training modes, one checked: the menu and the toolbar show the mode. Leaving a
  // trainee mode for Instructor asks for a confirmation (request_mode).
  mode_menu_ = menuBar()->addMenu(QString());
  using app::live::TrainingMode;
  auto* mg = new QActionGroup(this);
  const std::pair<QAction**, TrainingMode> modes[] = {
      {&a_instructor_, TrainingMode::Instructor}, {&a_practice_, TrainingMode::GuidedPractice}, {&a_exam_, TrainingMode::Exam}};
  for (const auto& [a, m] : modes) {
    *a = mode_menu_->addAction(QString());
    (*a)->setCheckable(true);
    (*a)->setObjectName(QStringLiteral("mode_%1").arg(QString::fromLatin1(app::live::training_mode_name(m))));
    mg->addAction(*a);
    connect(*a, &QAction::triggered, this, [this, m = m] { request_mode(m); });
  }
  a_instructor_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+I")));
  a_instructor_->setShortcutContext(Qt::ApplicationShortcut);
  a_practice_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+T")));
  a_exam_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+E")));
  a_end_exam_ = mode_menu_->addAction(QString(), this, [this] {
    QMessageBox box(QMessageBox::Question, a_end_exam_->text(), tr("End the exam now? No more marks can be made after it."),
                    QMessageBox::Yes | QMessageBox::No, this);
    box.setObjectName(QStringLiteral("ConfirmEndExam"));
    box.setDefaultButton(QMessageBox::No);
    if (box.exec() == QMessageBox::Yes) end_exam();
  });
  a_end_exam_->setObjectName(QStringLiteral("end_exam"));
  mode_menu_->addSeparator();
  a_progress_ = mode_menu_->addAction(QString(), this, [this] { open_progress_window(); });
  a_progress_->setObjectName(QStringLiteral("trainee_progress"));
  a_thresholds_ = mode_menu_->addAction(QString(), this, [this] { open_pressure_dialog(); });
  a_thresholds_->setObjectName(QStringLiteral("pressure_levels"));
  // Curricula: the built-in ones (resources/curricula, embedded), a file, or none.
  curriculum_menu_ = mode_menu_->addMenu(QString());
  curriculum_menu_->setObjectName(QStringLiteral("curriculum_menu"));
  for (const QString& f : QDir(QStringLiteral(":/curricula")).entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name)) {
    const QString path = QStringLiteral(":/curricula/") + f;
    QAction* a = curriculum_menu_->addAction(QFileInfo(f).completeBaseName(), this, [this, path] {
      QString err;
      if (!set_curriculum(path, &err)) QMessageBox::warning(this, tr("Curriculum"), err);
    });
    a->setObjectName(QStringLiteral("curriculum_") + QFileInfo(f).completeBaseName());
    a_builtin_curricula_ << a;
  }
  a_open_curriculum_ = curriculum_menu_->addAction(QString(), this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open a curriculum"), QDir::homePath(), tr("Curricula (*.json)"));
    if (path.isEmpty()) return;
    QString err;
    if (!set_curriculum(path, &err)) QMessageBox::warning(this, tr("Curriculum"), err);
  });
  a_no_curriculum_ = curriculum_menu_->addAction(QString(), this, [this] { clear_curriculum(); });
  a_next_case_ = mode_menu_->addAction(QString(), this, [this] {
    QString err;
    if (!next_curriculum_case(&err)) QMessageBox::information(this, tr("Curriculum"), err);
  });
  a_next_case_->setObjectName(QStringLiteral("next_case"));
  a_next_case_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+N")));
  mode_menu_->addSeparator();

  lang_menu_ = menuBar()->addMenu(QStringLiteral("Language / 言語"));
  a_en_ = lang_menu_->addAction(QStringLiteral("English"), this, [this] { set_language(QStringLiteral("en")); });
  a_ja_ = lang_menu_->addAction(QStringLiteral("日本語"), this, [this] { set_language(QStringLiteral("ja")); });

  toolbar_ = addToolBar(QString());
  toolbar_->setObjectName(QStringLiteral("MainToolBar"));
  toolbar_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  toolbar_->addAction(a_undo_);
  toolbar_->addAction(a_redo_);
  toolbar_->addSeparator();
  auto* tg = new QActionGroup(this);
  a_camera_tool_ = toolbar_->addAction(QIcon(QStringLiteral(":/icons/camera.png")), QString());
  a_palpate_tool_ = toolbar_->addAction(QIcon(QStringLiteral(":/icons/finger.png")), QString());
  for (auto* a : {a_camera_tool_, a_palpate_tool_}) {
    a->setCheckable(true);
    tg->addAction(a);
  }
  a_camera_tool_->setChecked(true);
  connect(a_camera_tool_, &QAction::triggered, this, [this] { device_panel_->mode->setCurrentIndex(0); });
  connect(a_palpate_tool_, &QAction::triggered, this, [this] { device_panel_->mode->setCurrentIndex(1); });
  a_mark_ = toolbar_->addAction(QString(), this, [this] { mark_lump(); });
  a_mark_->setShortcut(QKeySequence(Qt::Key_M));
  mode_menu_->addAction(a_mark_);
  // How sure the trainee is of the next mark: recorded with it.
  confidence_ = new QComboBox;
  confidence_->setObjectName(QStringLiteral("MarkConfidence"));
  for (double c : app::live::kMarkConfidence) confidence_->addItem(QString(), c);
  confidence_->setCurrentIndex(confidence_->count() - 1);  // certain, as marks were before they had a confidence
  connect(confidence_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { training_->set_mark_confidence(confidence_->itemData(i).toDouble()); });
  a_confidence_ = toolbar_->addWidget(confidence_);
  toolbar_->addSeparator();
  toolbar_->addAction(a_instructor_);
  toolbar_->addAction(a_practice_);
  toolbar_->addAction(a_exam_);
  toolbar_->addAction(a_end_exam_);
  // The coverage figures with the overlay's legend, a row of their own under the tools
  // (update_coverage shows it where the mode allows).
  addToolBarBreak(Qt::TopToolBarArea);
  coverage_bar_ = addToolBar(QString());
  coverage_bar_->setObjectName(QStringLiteral("CoverageToolBar"));
  coverage_bar_->addWidget(st_coverage_);
}

void MainWindow::retranslate() {
  setWindowTitle(tr("Palpation Trainer"));
  file_menu_->setTitle(tr("&File"));
  a_open_rec_->setText(tr("&Open recording..."));
  a_mark_->setText(tr("Mark lump here (M)"));
  a_mark_->setToolTip(tr("Trainee: \"I feel a lump here\": marks the index fingertip's position in the recording"));
  a_screenshot_->setText(tr("Save &screenshot..."));
  a_quit_->setText(tr("&Quit"));
  edit_menu_->setTitle(tr("&Edit"));
  a_undo_->setText(tr("Undo"));
  a_redo_->setText(tr("Redo"));
  view_menu_->setTitle(tr("&View"));
  camera_menu_->setTitle(tr("Camera"));
  const QString cams[4] = {tr("Oblique"), tr("Top"), tr("Side"), tr("Front")};
  for (int i = 0; i < 4; ++i) a_cam_[i]->setText(cams[i]);
  stereo_menu_->setTitle(tr("Stereo"));
  const QString st[5] = {tr("Mono"), tr("Anaglyph (red/cyan)"), tr("Side by side"), tr("Interlaced"), tr("Quad-buffer (shutter glasses)")};
  for (int i = 0; i < 5; ++i) a_stereo_[i]->setText(st[i]);
  a_eye_->setText(tr("Eye separation..."));
  a_mirror_->setText(tr("Mirrored (half-mirror display)"));
  a_fast_->setText(tr("Fast rendering (software OpenGL)"));
  a_fast_->setToolTip(tr("A lighter 3-D view: plain background, no highlights on the skin, an unlit chest. "
                         "On by itself when the computer draws OpenGL in software."));
  a_colour_->setText(tr("Displacement colour map"));
  a_stress_->setText(tr("Stress colour map (von Mises)"));
  a_tumours_->setText(tr("Show tumours"));
  panels_menu_->setTitle(tr("Panels"));
  mode_menu_->setTitle(tr("&Mode"));
  a_instructor_->setText(tr("Instructor mode"));
  a_instructor_->setToolTip(tr("The instructor's view: every panel, the answer included. "
                               "From a trainee mode it asks for a confirmation."));
  a_practice_->setText(tr("Guided practice"));
  a_practice_->setToolTip(tr("Trainee: palpate and mark; the instructor's panels are hidden."));
  a_exam_->setText(tr("Exam"));
  a_exam_->setToolTip(tr("Trainee examined: palpate and mark; the answer stays hidden until the exam ends."));
  a_end_exam_->setText(tr("End exam"));
  a_end_exam_->setToolTip(tr("Stops the exam: no more marks."));
  a_coverage_->setText(tr("Coverage overlay"));
  a_coverage_->setToolTip(tr("Colours the skin by the highest pressure reached: yellow light, orange medium, red deep. "
                             "Not shown in an exam."));
  a_clear_coverage_->setText(tr("Clear coverage"));
  a_progress_->setText(tr("Trainee progress..."));
  a_progress_->setToolTip(tr("Each trainee's exams over time and the class's results"));
  a_thresholds_->setText(tr("Pressure levels..."));
  a_thresholds_->setToolTip(tr("What counts as light, medium and deep pressure in the coverage and the score"));
  curriculum_menu_->setTitle(tr("Curriculum"));
  a_open_curriculum_->setText(tr("Open curriculum file..."));
  a_no_curriculum_->setText(tr("No curriculum (free exams)"));
  a_next_case_->setText(tr("Next curriculum case"));
  a_next_case_->setToolTip(tr("Loads the trainee's first case of the curriculum not yet passed"));
  const QString conf[4] = {tr("Possible (25 %)"), tr("Likely (50 %)"), tr("Probable (75 %)"), tr("Certain (100 %)")};
  for (int i = 0; i < 4; ++i) confidence_->setItemText(i, conf[i]);
  confidence_->setToolTip(tr("How sure you are of the next mark"));
  toolbar_->setWindowTitle(tr("Tools"));
  coverage_bar_->setWindowTitle(tr("Coverage"));
  a_camera_tool_->setText(tr("Camera / scripted hand"));
  a_palpate_tool_->setText(tr("Palpate with the mouse"));
  patient_dock_->setWindowTitle(tr("Patient"));
  tumour_dock_->setWindowTitle(tr("Tumours"));
  forces_dock_->setWindowTitle(tr("Forces"));
  sim_dock_->setWindowTitle(tr("Simulation"));
  device_dock_->setWindowTitle(tr("Device"));
  update_status();
}

void MainWindow::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange && file_menu_) retranslate();
  QMainWindow::changeEvent(e);
}

bool MainWindow::set_language(const QString& code) {
  qApp->removeTranslator(&translator_);
  bool ok = true;
  if (code != QLatin1String("en")) {
    ok = translator_.load(QStringLiteral(":/i18n/palpation_%1.qm").arg(code));
    if (ok) qApp->installTranslator(&translator_);
  }
  language_ = ok ? code : QStringLiteral("en");
  QSettings().setValue(QStringLiteral("language"), language_);
  retranslate();
  return ok;
}

void MainWindow::set_trainee(bool on) { set_mode(on ? app::live::TrainingMode::GuidedPractice : app::live::TrainingMode::Instructor); }

void MainWindow::set_mode(app::live::TrainingMode m) {
  if (m == training_->mode()) return;
  training_->set_mode(m);  // logs the change (and the end of a running exam: its result stored)
  // Back with the instructor: the next trainee says who they are.
  if (m == app::live::TrainingMode::Instructor) trainee_name_.clear();
  apply_mode();
}

bool MainWindow::request_mode(app::live::TrainingMode m) {
  if (m == training_->mode()) {
    apply_mode();  // the menu's check back on the current mode
    return false;
  }
  if (training_->needs_confirmation(m)) {
    const QString text = m == app::live::TrainingMode::Instructor
                             ? tr("Return to instructor mode? This ends the trainee's session and shows the answer, "
                                  "the patient's details and every panel. For the instructor only.")
                             : tr("Leave the exam? This ends it: no more marks can be made in it.");
    QMessageBox box(QMessageBox::Warning, tr("Change of mode"), text, QMessageBox::Yes | QMessageBox::No, this);
    box.setObjectName(QStringLiteral("ConfirmModeChange"));
    box.setDefaultButton(QMessageBox::No);
    if (box.exec() != QMessageBox::Yes) {
      apply_mode();
      return false;
    }
  }
  // Whose session it is, when nobody said yet (results are stored under the name).
  if (app::live::is_trainee(m) && !trainee() && trainee_name_.isEmpty() && !ask_trainee()) {
    apply_mode();
    return false;
  }
  set_mode(m);
  return true;
}

bool MainWindow::ask_trainee() {
  QStringList names;
  if (library_) {
    try {
      for (const auto& t : library_->trainees()) names << QString::fromStdString(t.name);
    } catch (const std::exception&) {
    }
  }
  QInputDialog d(this);
  d.setObjectName(QStringLiteral("AskTrainee"));
  d.setWindowTitle(tr("Trainee"));
  d.setLabelText(tr("Who is the trainee? Choose a name or type a new one (empty: anonymous, no result stored)."));
  d.setInputMode(QInputDialog::TextInput);
  if (!names.isEmpty()) {
    d.setComboBoxItems(names);
    d.setComboBoxEditable(true);
  }
  d.setTextValue(QString());
  if (d.exec() != QDialog::Accepted) return false;
  set_trainee_name(d.textValue().trimmed());
  return true;
}

void MainWindow::set_trainee_name(const QString& name) {
  trainee_name_ = name.trimmed();
  if (!trainee_name_.isEmpty() && library_) {
    try {
      if (!library_->find_trainee(trainee_name_.toStdString())) library_->add_trainee(trainee_name_.toStdString());
    } catch (const std::exception& e) {
      statusBar()->showMessage(tr("Trainee not added to the library: %1").arg(QString::fromStdString(e.what())), 8000);
    }
  }
  update_status();
}

ScoreDialog* MainWindow::score_dialog() const { return score_.data(); }
ProgressWindow* MainWindow::progress_window() const { return progress_.data(); }

ProgressWindow* MainWindow::open_progress_window() {
  if (trainee() || !library_) {
    if (!library_) statusBar()->showMessage(tr("Patient library not available: %1").arg(library_error_), 8000);
    return nullptr;
  }
  if (!progress_) {
    progress_ = new ProgressWindow(library_.get(), this);
    progress_->setWindowFlag(Qt::Window);
    progress_->setAttribute(Qt::WA_DeleteOnClose);
  } else {
    progress_->refresh();
  }
  progress_->show();
  progress_->raise();
  return progress_;
}

void MainWindow::exam_scored() {
  const auto& last = training_->last_score();
  if (!last) return;
  const std::string code = app::live::anonymous_case_code(patient_name().toStdString());
  const std::string recording = recorder_ ? recorder_->path() : std::string();
  const QDateTime now = QDateTime::currentDateTimeUtc();
  // A curriculum case is recorded under the case's name and judged by its pass criteria;
  // any other exam is a free exam (no curriculum, recorded as not passed).
  const auto& cur = training_->curriculum();
  const auto case_index = training_->curriculum_case();
  const bool in_curriculum = cur && case_index && training_->last_evaluation();
  const std::string case_name = in_curriculum ? cur->cases[*case_index].name() : patient_name().toStdString();
  if (!trainee_name_.isEmpty() && library_) {
    const QString started =
        now.addMSecs(-qint64(last->score.duration * 1000.0)).toString(QStringLiteral("yyyy-MM-dd'T'HH:mm:ss'Z'"));
    try {
      // Kept on this station when the classroom server is away (sent when it is back).
      const auto out = library_->store_result(
          app::train::exam_result(last->score, in_curriculum ? training_->last_evaluation() : std::nullopt, trainee_name_.toStdString(),
                                  case_name, in_curriculum ? cur->name : std::string(), started.toStdString(), recording),
          /*add_missing_trainee=*/true);
      if (out.id == 0)
        statusBar()->showMessage(tr("The exam's result is kept on this station: %1").arg(QString::fromStdString(out.message)), 15000);
      if (progress_) progress_->refresh();
    } catch (const std::exception& e) {
      statusBar()->showMessage(tr("The exam's result is not stored: %1").arg(QString::fromStdString(e.what())), 10000);
    }
  }
  app::cli::ReportInfo info{recording, trainee_name_.toStdString(), code, now.toString(Qt::ISODate).toStdString()};
  delete score_.data();
  score_ = new ScoreDialog(*last, info, this, in_curriculum ? training_->last_evaluation() : std::nullopt);
  score_->setAttribute(Qt::WA_DeleteOnClose);
  score_->setModal(false);
  score_->show();
}

PressureDialog* MainWindow::open_pressure_dialog() {
  if (trainee()) return nullptr;
  if (!pressure_) {
    pressure_ = new PressureDialog(training_->exam().thresholds(), this);
    pressure_->setAttribute(Qt::WA_DeleteOnClose);
    connect(pressure_, &QDialog::accepted, this, [this] {
      if (pressure_) set_pressure_thresholds(pressure_->thresholds());
    });
  }
  pressure_->show();
  pressure_->raise();
  return pressure_;
}

void MainWindow::set_pressure_thresholds(const app::train::PressureThresholds& t) {
  t.validate();
  training_->exam().set_thresholds(t);
  const nlohmann::json j = app::train::to_json(t);
  QSettings().setValue(QStringLiteral("training/thresholds"), QString::fromStdString(j.dump()));
  if (recorder_) recorder_->add_event("thresholds", j);
  update_coverage();
  statusBar()->showMessage(tr("Pressure levels set: they apply to the exams that start from now on."), 5000);
}

bool MainWindow::set_curriculum(const QString& path, QString* error) {
  app::train::Curriculum c;
  try {
    // Qt resources (the built-in curricula) are read through QFile; files by the parser.
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) throw std::runtime_error(path.toStdString() + ": cannot be read: " + f.errorString().toStdString());
    c = app::train::parse_curriculum(f.readAll().toStdString(), path.toStdString());
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  auto previous = training_->curriculum();
  training_->set_curriculum(std::move(c));
  if (!next_curriculum_case(error)) {
    training_->set_curriculum(std::move(previous));
    apply_mode();
    return false;
  }
  return true;
}

void MainWindow::clear_curriculum() {
  training_->set_curriculum(std::nullopt);
  apply_mode();
}

bool MainWindow::next_curriculum_case(QString* error) {
  const auto& cur = training_->curriculum();
  if (!cur) {
    if (error) *error = tr("No curriculum is chosen (Mode > Curriculum).");
    return false;
  }
  std::vector<std::string> passed;
  if (library_ && !trainee_name_.isEmpty()) {
    try {
      passed = app::train::passed_case_names(library_->results(trainee_name_.toStdString()), &*cur);
    } catch (const std::exception& e) {
      statusBar()->showMessage(tr("The trainee's results could not be read: %1").arg(QString::fromStdString(e.what())), 10000);
    }
  }
  const auto next = app::train::next_case(*cur, passed);
  if (!next) {
    if (error) *error = tr("%1 has passed every case of %2.").arg(trainee_name_, QString::fromStdString(cur->name));
    return false;
  }
  if (!load_curriculum_case(*next, error)) return false;
  // A trainee whose exam ended goes on with a new one on the new case.
  if (trainee() && !training_->exam_running()) training_->start_exam();
  apply_mode();
  return true;
}

bool MainWindow::load_curriculum_case(std::size_t i, QString* error) {
  const auto& cur = *training_->curriculum();
  const app::train::CurriculumCase& c = cur.cases[i];
  if (!c.generated()) {
    if (!choose_patient(QString::fromStdString(c.patient), error)) return false;
  } else {
    try {
      const app::train::GeneratedCase g = app::train::generate_case(*c.seed, c.ranges, cur.source);
      sim::Scenario s = app::live::case_patient(g.scenario, g.name, patient_panel_->resolution->currentData().toString().toStdString());
      s.params.solver = scenario_.params.solver;
      chosen_ = s;
      case_name_ = QString::fromStdString(g.name);
      patient_panel_->show_scenario(s);
      scenario_ = patient_panel_->scenario(chosen_);
      scenario_.backend = sim_panel_->backend->currentText().toStdString();
      ws_->load_patient(scenario_);
    } catch (const std::exception& e) {
      if (error) *error = QString::fromStdString(e.what());
      return false;
    }
  }
  training_->set_curriculum_case(i);
  return true;
}

QString MainWindow::patient_name() const { return case_name_.isEmpty() ? patient_panel_->chosen() : case_name_; }

QString MainWindow::curriculum_text() const {
  const auto& cur = training_->curriculum();
  if (!cur) return {};
  const auto i = training_->curriculum_case();
  return i ? tr("Curriculum %1: case %2 of %3").arg(QString::fromStdString(cur->name)).arg(*i + 1).arg(cur->cases.size())
           : tr("Curriculum %1").arg(QString::fromStdString(cur->name));
}

void MainWindow::update_coverage() {
  if (!a_coverage_ || !coverage_bar_) return;
  const bool allowed = training_->overlay_allowed();
  const bool on = allowed && a_coverage_->isChecked();
  if (on) view_->set_coverage(training_->exam().surface_levels());
  view_->set_coverage_visible(on);
  coverage_bar_->setVisible(allowed);
  coverage_bar_->toggleViewAction()->setVisible(allowed);
  if (!allowed) return;
  // The figures with the overlay's legend: a square of each level's colour.
  auto square = [](int l) {
    const auto* c = VtkView::kCoverageColour[l];
    return QStringLiteral("<span style=\"color:rgb(%1,%2,%3)\">&#9632;</span>").arg(c[0]).arg(c[1]).arg(c[2]);
  };
  const auto c = training_->exam().coverage();
  st_coverage_->setText(tr("Coverage: %1 none %2 light %3 %4 medium %5 %6 deep %7")
                            .arg(square(0), square(1), ScoreDialog::percent(c[0]), square(2), ScoreDialog::percent(c[1]), square(3),
                                 ScoreDialog::percent(c[2])));
}

bool MainWindow::end_exam() { return training_->end_exam(); }

QMenu* MainWindow::createPopupMenu() { return trainee() ? nullptr : QMainWindow::createPopupMenu(); }

void MainWindow::apply_mode() {
  using app::live::TrainingMode;
  const TrainingMode m = training_->mode();
  const bool on = app::live::is_trainee(m);
  // Hidden, not greyed: the instructor docks and their entries in View > Panels; back in
  // Instructor mode the docks that were open come back.
  const auto docks = instructor_docks();
  if (on && docks_shown_.isEmpty())
    for (auto* d : docks) docks_shown_ << !d->isHidden();
  for (int i = 0; i < docks.size(); ++i) {
    QDockWidget* d = docks[i];
    d->toggleViewAction()->setVisible(!on);
    d->setFeatures(on ? QDockWidget::NoDockWidgetFeatures
                      : QDockWidget::DockWidgetClosable | QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    if (on) d->hide();
    else if (docks_shown_.isEmpty() || docks_shown_[i]) d->show();
  }
  if (!on) docks_shown_.clear();
  // A new exam or practice: the last one's score (the answer) goes, as does the progress
  // window (instructor only).
  if (on && training_->exam_running() && score_) score_->close();
  if (on && progress_) progress_->close();
  a_progress_->setVisible(!on);
  a_thresholds_->setVisible(!on);
  curriculum_menu_->menuAction()->setVisible(!on);
  a_next_case_->setVisible(training_->curriculum().has_value());
  // In a trainee mode, the next case once the exam on this one has ended.
  a_next_case_->setEnabled(!on || !training_->exam_running());
  if (on && pressure_) pressure_->close();
  a_clear_coverage_->setVisible(!on);
  a_coverage_->setVisible(training_->overlay_allowed());
  update_coverage();
  // The 3-D view: no tumour outlines, no colour map (the stress map shows the tumour).
  if (on) {
    a_tumours_->setChecked(false);
    a_colour_->setChecked(false);
    a_stress_->setChecked(false);
    view_->set_tumours_visible(false);
    view_->set_colour_mode(VtkView::ColourMap::None);
    ws_->set_stress_enabled(false);
  } else if (!a_tumours_->isVisible()) {
    a_tumours_->setChecked(true);
    view_->set_tumours_visible(true);
  }
  for (QAction* a : {a_tumours_, a_colour_, a_stress_}) a->setVisible(!on);
  // Undo/redo name the edits they undo ("Add tumour: Sphere ... 107 kPa"); recordings open
  // in a review window that shows the tumours.
  // The force plots' scale line names the force over the patient's stiffest part (the
  // tumour's): an instructor's figure.
  if (auto* scale = plots_->findChild<QLabel*>(QStringLiteral("forceScale"))) scale->setVisible(!on);
  edit_menu_->menuAction()->setVisible(!on);
  for (QAction* a : {a_undo_, a_redo_}) a->setVisible(!on);
  a_open_rec_->setVisible(!on);
  a_open_rec_->setEnabled(!on);
  if (on) {
    if (review_) review_->close();
    if (import_) import_->close();
    tumour_panel_->paint->setChecked(false);
    tumour_panel_->erase->setChecked(false);
    device_panel_->mode->setCurrentIndex(1);  // mouse palpation
    view_->set_tool(VtkView::Tool::Palpate);
    a_palpate_tool_->setChecked(true);
    statusBar()->clearMessage();  // an instructor's message (a tumour added, a patient's name) must not linger
  }
  a_instructor_->setChecked(m == TrainingMode::Instructor);
  a_practice_->setChecked(m == TrainingMode::GuidedPractice);
  a_exam_->setChecked(m == TrainingMode::Exam);
  a_end_exam_->setVisible(on);
  a_end_exam_->setEnabled(on && training_->exam_running());
  a_mark_->setEnabled(training_->accepts_marks());
  confidence_->setEnabled(training_->accepts_marks());
  update_status();
}

QString MainWindow::mode_text() const {
  using app::live::TrainingMode;
  // A trainee reads an anonymous case code, never the patient's name (it may name the tumour).
  const QString code = QString::fromStdString(app::live::anonymous_case_code(patient_name().toStdString()));
  const bool running = training_->exam_running();
  const QString who = trainee_name_.isEmpty() ? QString() : tr(", trainee %1").arg(trainee_name_);
  switch (training_->mode()) {
    case TrainingMode::Instructor: return tr("Instructor: %1").arg(patient_panel_->phantom->currentText());
    case TrainingMode::GuidedPractice:
      return (running ? tr("Guided practice: case %1").arg(code) : tr("Guided practice ended: case %1").arg(code)) + who;
    case TrainingMode::Exam: return (running ? tr("Exam: case %1").arg(code) : tr("Exam ended: case %1").arg(code)) + who;
  }
  return {};
}

void MainWindow::tick() {
  const bool fresh = ws_->poll();
  // The patient as the tumour document has it (poll() moved it to a new one).
  const auto& g = ws_->tumours().patient();
  if (g && g->generation != generation_) {
    generation_ = g->generation;
    view_->set_patient(g);
    view_->show_tumours(ws_->tumours());
    editor_->patient_changed();
    patient_panel_->info->setText(tr("%1 nodes, %2 tetrahedra").arg(g->rest.size()).arg(g->tets.size()));
  }
  if (fresh) view_->show_snapshot(ws_->snapshot());
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (now - last_plot_ >= 100) {
    last_plot_ = now;
    if (forces_dock_->isVisible()) plots_->refresh();
  }
  if (recorder_ && now - last_flush_ >= 1000) {
    last_flush_ = now;
    recorder_->flush();
  }
  if (now - last_status_ >= 250) {
    last_status_ = now;
    update_status();
    update_coverage();
    const auto& s = ws_->stats();
    if (ws_->device().mode() == app::live::HandMode::Mouse)
      // Numbers and units only: VTK's built-in font has no Japanese glyphs.
      view_->set_overlay_text(QStringLiteral("F = %1 N    press %2 mm")
                                  .arg(s.force_n[1], 0, 'f', 2)
                                  .arg(view_->press_depth() * 1000, 0, 'f', 1));
    else
      view_->set_overlay_text(QString());
  }
  if (now - fps_t0_ >= 1000) {
    const quint64 frames = view_->frames();
    fps_ = double(frames - quint64(frame_count_)) * 1000.0 / double(now - fps_t0_);
    frame_count_ = int(frames);
    fps_t0_ = now;
  }
}

void MainWindow::update_status() {
  if (!st_backend_) return;
  if (st_mode_ && a_exam_) st_mode_->setText(mode_text());
  if (st_curriculum_) {
    st_curriculum_->setText(curriculum_text());
    st_curriculum_->setVisible(!st_curriculum_->text().isEmpty());
  }
  const auto& s = ws_->stats();
  const auto g = ws_->geometry();
  // The backend stepping now (after a CUDA error: the CPU it fell back to).
  const QString be = !s.backend.empty() ? QString::fromStdString(s.backend)
                     : g                ? QString::fromStdString(g->backend)
                                        : QStringLiteral("-");
  st_backend_->setText(s.fallbacks > 0 ? tr("Backend: %1 (fallback)").arg(be) : tr("Backend: %1").arg(be));
  st_backend_->setToolTip(QString::fromStdString(s.safety_note));
  st_step_->setText(tr("Simulation: %1 Hz").arg(s.step_rate_hz, 0, 'f', 0));
  st_haptic_->setText(tr("Haptic: %1 Hz").arg(s.haptic_rate_hz, 0, 'f', 0));
  const QString dev = !ws_->simulated_device() ? QString::fromStdString(ws_->device_description())
                      : ws_->device().mode() == app::live::HandMode::Mouse ? tr("mouse")
                                                                                    : tr("simulated HandHIRO");
  st_device_->setText(tr("Device: %1, %2").arg(dev, s.connected ? tr("connected") : tr("not connected")));
  st_fps_->setText(tr("View: %1 fps").arg(fps_, 0, 'f', 0));
  if (st_rec_) {
    st_rec_->setText(!recorder_ ? tr("Not recording")
                     : recorder_->failed() ? tr("Recording stopped: %1").arg(QString::fromStdString(recorder_->error()))
                                           : tr("Recording (%1 marks)").arg(recorder_->marks()));
    st_rec_->setToolTip(recorder_ ? QString::fromStdString(recorder_->path()) : QString());
  }
  sim_panel_->show_stats(s, be);
  device_panel_->show_stats(s);
}

void MainWindow::closeEvent(QCloseEvent* e) {
  QSettings settings;
  settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
  settings.setValue(QStringLiteral("window/state"), saveState());
  ws_->stop();
  QMainWindow::closeEvent(e);
}

}  // namespace palpation::ui
