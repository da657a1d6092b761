#include "panels.h"

#include <algorithm>

#include <QCheckBox>
#include <QCoreApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProgressBar>
#include <QSignalBlocker>
#include <QPushButton>
#include <QSpinBox>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>

#include "event_text.h"
#include "live/patient_choice.h"
#include "live/step_pacer.h"
#include "tumour_editor.h"

namespace palpation::ui {

namespace {
QDoubleSpinBox* spin(double lo, double hi, double v, int decimals, double step, const QString& suffix = {}) {
  auto* s = new QDoubleSpinBox;
  s->setRange(lo, hi);
  s->setDecimals(decimals);
  s->setSingleStep(step);
  s->setValue(v);
  if (!suffix.isEmpty()) s->setSuffix(suffix);
  return s;
}
void set_label(QFormLayout* form, QWidget* field, const QString& text) {
  if (auto* l = qobject_cast<QLabel*>(form->labelForField(field))) l->setText(text);
}
// A library patient's description in the current language: a built-in patient's from its
// data, any other as stored.
QString shown_description(const QString& name, bool builtin, const QString& stored) {
  if (builtin)
    if (const auto d = app::store::builtin_description(name.toStdString())) return EventText::patient_description(*d);
  return stored;
}
const char* const kFingers[5] = {QT_TRANSLATE_NOOP("DevicePanel", "Thumb"), QT_TRANSLATE_NOOP("DevicePanel", "Index"),
                                 QT_TRANSLATE_NOOP("DevicePanel", "Middle"), QT_TRANSLATE_NOOP("DevicePanel", "Ring"),
                                 QT_TRANSLATE_NOOP("DevicePanel", "Little")};
}  // namespace

// ---------------------------------------------------------------------------------------
PatientPanel::PatientPanel(QWidget* parent) : QWidget(parent) {
  phantom = new QComboBox;
  phantom->setObjectName(QStringLiteral("PatientChooser"));
  phantom->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  phantom->setMinimumContentsLength(18);
  set_patients({});
  description = new QLabel;
  description->setWordWrap(true);
  resolution = new QComboBox;
  for (const char* r : {"coarse", "paper", "fine"}) resolution->addItem(QString(), QString::fromLatin1(r));
  young = spin(0.5, 500, 19, 1, 1, QStringLiteral(" kPa"));
  poisson = spin(0.0, 0.49, 0.45, 3, 0.01);
  apply = new QPushButton;
  import_scan = new QPushButton;
  info = new QLabel;
  info->setWordWrap(true);
  form_ = new QFormLayout(this);
  form_->addRow(QStringLiteral("-"), phantom);
  form_->addRow(description);
  form_->addRow(QStringLiteral("-"), resolution);
  form_->addRow(QStringLiteral("-"), young);
  form_->addRow(QStringLiteral("-"), poisson);
  form_->addRow(apply);
  form_->addRow(import_scan);
  form_->addRow(info);
  connect(apply, &QPushButton::clicked, this, &PatientPanel::loadRequested);
  connect(import_scan, &QPushButton::clicked, this, &PatientPanel::importRequested);
  connect(phantom, qOverload<int>(&QComboBox::activated), this, [this](int i) {
    description->setText(phantom->itemData(i, Qt::ToolTipRole).toString());
    emit patientChosen(phantom->itemData(i).toString());
  });
  retranslate();
}

void PatientPanel::set_patients(const QList<Entry>& entries) {
  const QString keep = chosen();
  QSignalBlocker block(phantom);
  phantom->clear();
  for (const auto& e : entries) {
    phantom->addItem(e.name, e.name);
    phantom->setItemData(phantom->count() - 1, e.description, Qt::UserRole + 2);  // as stored (English for built-ins)
    phantom->setItemData(phantom->count() - 1, e.builtin, Qt::UserRole + 3);
    phantom->setItemData(phantom->count() - 1, shown_description(e.name, e.builtin, e.description), Qt::ToolTipRole);
    phantom->setItemData(phantom->count() - 1, e.category, Qt::UserRole + 1);
  }
  // The built-in phantoms, always there (also without a library).
  phantom->addItem(QString(), QStringLiteral("phantom:breast"));
  phantom->addItem(QString(), QStringLiteral("phantom:box"));
  for (int i = phantom->count() - 2; i < phantom->count(); ++i) phantom->setItemData(i, QStringLiteral("phantom"), Qt::UserRole + 1);
  if (form_) retranslate();
  if (!keep.isEmpty()) select_patient(keep);
}

bool PatientPanel::select_patient(const QString& name) {
  const int i = phantom->findData(name);
  if (i < 0) return false;
  QSignalBlocker block(phantom);
  phantom->setCurrentIndex(i);
  if (description) description->setText(phantom->itemData(i, Qt::ToolTipRole).toString());
  return true;
}

QString PatientPanel::chosen() const { return phantom->currentData().toString(); }

void PatientPanel::retranslate() {
  const int n = phantom->count();
  phantom->setItemText(n - 2, tr("Breast phantom (paper's tumour)"));
  phantom->setItemText(n - 1, tr("Box phantom"));
  phantom->setItemData(n - 2, tr("The paper's breast with its tumour (107 kPa at x = 12.5 cm)."), Qt::ToolTipRole);
  phantom->setItemData(n - 1, tr("A 10 x 10 x 5 cm block of tissue, no tumour."), Qt::ToolTipRole);
  for (int i = 0; i < n - 2; ++i)  // the library's patients: their stored descriptions in the new language
    phantom->setItemData(i,
                         shown_description(phantom->itemData(i).toString(), phantom->itemData(i, Qt::UserRole + 3).toBool(),
                                           phantom->itemData(i, Qt::UserRole + 2).toString()),
                         Qt::ToolTipRole);
  if (description) description->setText(phantom->currentData(Qt::ToolTipRole).toString());  // the chosen one's, in the new language
  resolution->setItemText(0, tr("Coarse (about 1,000 nodes, real time on a CPU)"));
  resolution->setItemText(1, tr("Paper (about 9,100 nodes, GPU)"));
  resolution->setItemText(2, tr("Fine (GPU)"));
  set_label(form_, phantom, tr("Patient"));
  set_label(form_, resolution, tr("Resolution"));
  set_label(form_, young, tr("Tissue Young's modulus"));
  set_label(form_, poisson, tr("Poisson ratio"));
  apply->setText(tr("Load patient"));
  import_scan->setText(tr("Import scan..."));
  phantom->setToolTip(tr("Patients from the library (built-in shapes, graded tumour cases, imported scans) and the built-in phantoms."));
  resolution->setToolTip(tr("Phantom patients only; an imported scan keeps the resolution it was meshed at."));
}

void PatientPanel::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

void PatientPanel::show_scenario(const sim::Scenario& s) {
  resolution->setCurrentIndex(std::max(0, resolution->findData(QString::fromStdString(s.patient.resolution))));
  resolution->setEnabled(!s.patient.phantom.empty());
  young->setValue(s.young_modulus / 1000.0);
  poisson->setValue(s.poisson_ratio);
}

sim::Scenario PatientPanel::scenario(const sim::Scenario& base) const {
  sim::Scenario s = base;
  if (!s.patient.phantom.empty()) {
    if (!app::live::set_phantom_resolution(s, resolution->currentData().toString().toStdString()))
      s.patient.resolution = resolution->currentData().toString().toStdString();
  }
  s.young_modulus = young->value() * 1000.0;
  s.poisson_ratio = poisson->value();
  return s;
}

// ---------------------------------------------------------------------------------------
TumourPanel::TumourPanel(TumourEditor* editor, QWidget* parent) : QWidget(parent), editor_(editor) {
  list = new QListWidget;
  list->setMaximumHeight(110);
  preset = new QComboBox;
  for (const auto& p : tissue_presets()) preset->addItem(p.name, p.young);
  source = new QLabel;
  source->setWordWrap(true);
  young = spin(1, 1000, 107, 1, 5, QStringLiteral(" kPa"));
  shape = new QComboBox;
  shape->addItem(QString(), int(app::live::TumourShape::Sphere));
  shape->addItem(QString(), int(app::live::TumourShape::Ellipsoid));
  const double c0[3] = {12.5, 0, 3.5};
  for (int i = 0; i < 3; ++i) {
    centre[i] = spin(-30, 30, c0[i], 1, 0.5, QStringLiteral(" cm"));
    radii[i] = spin(0.2, 5, 1.0, 1, 0.1, QStringLiteral(" cm"));
  }
  add = new QPushButton;
  remove = new QPushButton;
  brush_radius = spin(0.2, 3, 0.8, 1, 0.1, QStringLiteral(" cm"));
  brush_depth = spin(0, 5, 1.2, 1, 0.1, QStringLiteral(" cm"));
  paint = new QToolButton;
  erase = new QToolButton;
  paint->setCheckable(true);
  erase->setCheckable(true);
  undo = new QToolButton;
  redo = new QToolButton;
  undo->setDefaultAction(editor->undo_stack()->createUndoAction(this));
  redo->setDefaultAction(editor->undo_stack()->createRedoAction(this));

  auto* lay = new QVBoxLayout(this);
  lay->addWidget(list);
  auto* lr = new QHBoxLayout;
  lr->addWidget(remove);
  lr->addStretch();
  lr->addWidget(undo);
  lr->addWidget(redo);
  lay->addLayout(lr);
  top_form_ = new QFormLayout;
  top_form_->addRow(QStringLiteral("-"), preset);
  top_form_->addRow(QStringLiteral("-"), young);
  top_form_->addRow(source);
  lay->addLayout(top_form_);
  shape_box_ = new QGroupBox;
  shape_form_ = new QFormLayout(shape_box_);
  shape_form_->addRow(QStringLiteral("-"), shape);
  auto row = [](std::array<QDoubleSpinBox*, 3>& a) {
    auto* w = new QWidget;
    auto* h = new QHBoxLayout(w);
    h->setContentsMargins(0, 0, 0, 0);
    for (auto* s : a) h->addWidget(s);
    return w;
  };
  auto* cw = row(centre);
  auto* rw = row(radii);
  shape_form_->addRow(QStringLiteral("-"), cw);
  shape_form_->addRow(QStringLiteral("-"), rw);
  shape_form_->addRow(add);
  lay->addWidget(shape_box_);
  brush_box_ = new QGroupBox;
  brush_form_ = new QFormLayout(brush_box_);
  brush_form_->addRow(QStringLiteral("-"), brush_radius);
  brush_form_->addRow(QStringLiteral("-"), brush_depth);
  auto* bw = new QWidget;
  auto* bh = new QHBoxLayout(bw);
  bh->setContentsMargins(0, 0, 0, 0);
  bh->addWidget(paint);
  bh->addWidget(erase);
  brush_form_->addRow(bw);
  lay->addWidget(brush_box_);
  lay->addStretch();
  centre_label_widget_ = cw;
  radii_label_widget_ = rw;

  connect(preset, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) {
    const auto p = tissue_presets();
    if (i >= 0 && i < int(p.size())) {
      young->setValue(p[i].young / 1000.0);
      source->setText(tr("Source: %1").arg(p[i].source));
    }
  });
  connect(paint, &QToolButton::toggled, this, [this](bool on) {
    if (on) erase->setChecked(false);
    emit toolRequested(on ? 1 : (erase->isChecked() ? 2 : 0));
  });
  connect(erase, &QToolButton::toggled, this, [this](bool on) {
    if (on) paint->setChecked(false);
    emit toolRequested(on ? 2 : (paint->isChecked() ? 1 : 0));
  });
  connect(editor, &TumourEditor::changed, this, &TumourPanel::refresh_list);
  retranslate();
}

double TumourPanel::preset_young() const { return young->value() * 1000.0; }

app::live::TumourShape TumourPanel::chosen_shape() const { return app::live::TumourShape(shape->currentData().toInt()); }

void TumourPanel::refresh_list() {
  list->clear();
  list->addItems(editor_->tumour_names());
}

void TumourPanel::retranslate() {
  const auto p = tissue_presets();
  for (int i = 0; i < int(p.size()) && i < preset->count(); ++i) preset->setItemText(i, p[i].name);
  if (preset->currentIndex() >= 0 && preset->currentIndex() < int(p.size()))
    source->setText(tr("Source: %1").arg(p[preset->currentIndex()].source));
  set_label(top_form_, preset, tr("Preset"));
  set_label(top_form_, young, tr("Stiffness"));
  shape_box_->setTitle(tr("Add by shape"));
  shape->setItemText(0, tr("Sphere"));
  shape->setItemText(1, tr("Ellipsoid"));
  set_label(shape_form_, shape, tr("Shape"));
  set_label(shape_form_, centre_label_widget_, tr("Centre x, y, z"));
  set_label(shape_form_, radii_label_widget_, tr("Radius (x, y, z)"));
  add->setText(tr("Add tumour"));
  remove->setText(tr("Remove selected"));
  brush_box_->setTitle(tr("Brush"));
  set_label(brush_form_, brush_radius, tr("Radius"));
  set_label(brush_form_, brush_depth, tr("Depth below the skin"));
  paint->setText(tr("Paint"));
  erase->setText(tr("Erase"));
  paint->setToolTip(tr("Drag on the breast to paint tumour tissue (one undo step per stroke)"));
  erase->setToolTip(tr("Drag on the breast to restore healthy tissue"));
  undo->defaultAction()->setText(tr("Undo"));
  redo->defaultAction()->setText(tr("Redo"));
  refresh_list();
}

void TumourPanel::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

// ---------------------------------------------------------------------------------------
SimulationPanel::SimulationPanel(QWidget* parent) : QWidget(parent) {
  backend = new QComboBox;
  for (const auto& b : app::live::available_backends()) backend->addItem(QString::fromStdString(b));
  tolerance = new QDoubleSpinBox;
  tolerance->setDecimals(6);
  tolerance->setRange(1e-6, 1e-1);
  tolerance->setSingleStep(1e-4);
  // The simulation's own defaults (params.h) until the main window shows what runs.
  const sim::SolverParams defaults;
  tolerance->setValue(defaults.cg_tolerance);
  iterations = new QSpinBox;
  iterations->setRange(5, 2000);
  iterations->setValue(defaults.cg_max_iterations);
  // Percent of the converged finger force; at 0 the CG tolerance above stays fixed.
  force_error = new QDoubleSpinBox;
  force_error->setDecimals(2);
  force_error->setRange(0, 50);
  force_error->setSingleStep(0.5);
  force_error->setSuffix(QStringLiteral(" %"));
  force_error->setValue(100 * defaults.force_error);
  apply = new QPushButton;
  step_ms = new QLabel;
  cg = new QLabel;
  step_rate = new QLabel;
  pace = new QLabel;
  haptic_rate = new QLabel;
  state = new QLabel;
  safety = new QLabel;
  safety->setWordWrap(true);
  form_ = new QFormLayout(this);
  form_->addRow(QStringLiteral("-"), backend);
  form_->addRow(QStringLiteral("-"), tolerance);
  form_->addRow(QStringLiteral("-"), iterations);
  form_->addRow(QStringLiteral("-"), force_error);
  form_->addRow(apply);
  form_->addRow(QStringLiteral("-"), state);
  form_->addRow(QStringLiteral("-"), safety);
  form_->addRow(QStringLiteral("-"), step_ms);
  form_->addRow(QStringLiteral("-"), cg);
  form_->addRow(QStringLiteral("-"), step_rate);
  form_->addRow(QStringLiteral("-"), pace);
  form_->addRow(QStringLiteral("-"), haptic_rate);
  retranslate();
}

void SimulationPanel::retranslate() {
  set_label(form_, backend, tr("Backend"));
  set_label(form_, tolerance, tr("CG tolerance"));
  set_label(form_, iterations, tr("CG max. iterations"));
  set_label(form_, force_error, tr("Force error held"));
  force_error->setSpecialValueText(tr("off: fixed CG tolerance"));
  force_error->setToolTip(tr("The finger-force error the solver holds, in percent of the converged force: it picks "
                             "the loosest CG tolerance that keeps it, starting from the one above, and checks it "
                             "against a converged step every so often. Off: the CG tolerance stays as set."));
  set_label(form_, state, tr("State"));
  set_label(form_, safety, tr("Safety"));
  set_label(form_, step_ms, tr("Step time"));
  set_label(form_, cg, tr("CG iterations"));
  set_label(form_, step_rate, tr("Simulation rate"));
  set_label(form_, pace, tr("Tissue pace"));
  pace->setToolTip(tr("Simulated time a wall-clock second. Below 100 % this patient's mesh is too fine for this "
                      "machine to keep real time: the tissue moves in slow motion, and the solver's time step "
                      "is the shortest that keeps %1 % of the pace the longest one would.")
                       .arg(100 * app::live::StepPacer::kRateShare, 0, 'f', 0));
  set_label(form_, haptic_rate, tr("Haptic rate"));
  apply->setText(tr("Apply solver settings"));
  backend->setToolTip(tr("A backend change takes effect when the patient is (re)loaded."));
}

void SimulationPanel::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

void SimulationPanel::show_stats(const app::live::LiveStats& s, const QString& be) {
  // The state in words; an error's reason stays as the simulation wrote it.
  using app::live::SimState;
  QString word;
  switch (s.state) {
    case SimState::Stopped: word = tr("stopped"); break;
    case SimState::Loading: word = tr("loading"); break;
    case SimState::Running: word = tr("running"); break;
    case SimState::Swapping: word = tr("swapping"); break;
    case SimState::Error: word = tr("error: %1").arg(QString::fromStdString(s.error)); break;
  }
  state->setText(word + (be.isEmpty() ? QString() : QStringLiteral(" (") + be + QStringLiteral(")")));
  // Backend fallbacks and divergence resets (design.md section 7), with the newest reason.
  QString text = s.fallbacks == 0 && s.divergences == 0
                     ? tr("no fault")
                     : tr("%n backend fallback(s)", nullptr, s.fallbacks) + QStringLiteral(", ") +
                           tr("%n divergence reset(s)", nullptr, s.divergences);
  if (s.recovering) text += QStringLiteral("; ") + tr("forces held and blended");
  if (!s.safety_note.empty()) text += QStringLiteral("\n") + QString::fromStdString(s.safety_note);
  safety->setText(text);
  safety->setStyleSheet(s.fallbacks + s.divergences > 0 ? QStringLiteral("color: #b35c00") : QString());
  step_ms->setText(tr("%1 ms").arg(s.step_ms, 0, 'f', 2));
  cg->setText(QString::number(s.cg_iterations));
  step_rate->setText(tr("%1 Hz").arg(s.step_rate_hz, 0, 'f', 0));
  // Steps start on a grid of dt and never run ahead of the wall clock: 95 % and up is real
  // time within the window's counting.
  const bool slow = s.step_rate_hz > 0 && s.pace < 0.95;
  pace->setText(tr("%1 % of real time, dt %2 ms").arg(100 * std::min(s.pace, 1.0), 0, 'f', 0).arg(s.dt_ms, 0, 'f', 1));
  pace->setStyleSheet(slow ? QStringLiteral("color: #b35c00") : QString());
  haptic_rate->setText(tr("%1 Hz").arg(s.haptic_rate_hz, 0, 'f', 0));
}

// ---------------------------------------------------------------------------------------
DevicePanel::DevicePanel(double max_force, QWidget* parent) : QWidget(parent), max_force_(max_force) {
  mode = new QComboBox;
  mode->addItem(QString(), QStringLiteral("scripted"));
  mode->addItem(QString(), QStringLiteral("mouse"));
  address = new QLineEdit(QStringLiteral("192.168.0.10:7001"));
  address->setEnabled(false);
  note = new QLabel;
  note->setWordWrap(true);
  jitter = new QLabel;
  form_ = new QFormLayout(this);
  form_->addRow(QStringLiteral("-"), mode);
  form_->addRow(QStringLiteral("-"), address);
  form_->addRow(note);
  for (int f = 0; f < 5; ++f) {
    bars[f] = new QProgressBar;
    bars[f]->setRange(0, int(max_force * 100));
    bars[f]->setFormat(QStringLiteral("%v cN"));
    attached[f] = new QLabel;
    auto* w = new QWidget;
    auto* h = new QHBoxLayout(w);
    h->setContentsMargins(0, 0, 0, 0);
    h->addWidget(bars[f], 1);
    h->addWidget(attached[f]);
    names_[f] = new QLabel;
    form_->addRow(names_[f], w);
  }
  form_->addRow(QStringLiteral("-"), jitter);
  retranslate();
}

void DevicePanel::retranslate() {
  mode->setItemText(0, tr("Simulated HandHIRO (scripted palpation)"));
  mode->setItemText(1, tr("Mouse palpation (no robot)"));
  set_label(form_, mode, tr("Device"));
  set_label(form_, address, tr("HandHIRO address"));
  set_label(form_, jitter, tr("Loop jitter"));
  note->setText(tr("The HandHIRO network link is chosen at start: palpation-trainer --device emulator, "
                   "or --device handhiro --robot ADDRESS:PORT."));
  for (int f = 0; f < 5; ++f) names_[f]->setText(QCoreApplication::translate("DevicePanel", kFingers[f]));
}

void DevicePanel::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange) retranslate();
  QWidget::changeEvent(e);
}

void DevicePanel::show_stats(const app::live::LiveStats& s) {
  for (int f = 0; f < 5; ++f) {
    bars[f]->setValue(int(std::min(s.force_n[f], max_force_) * 100));
    attached[f]->setText(s.attached[f] ? tr("attached") : tr("released"));
  }
  jitter->setText(tr("%1 us (max over 0.5 s)").arg(s.jitter_us, 0, 'f', 0));
}

}  // namespace palpation::ui
