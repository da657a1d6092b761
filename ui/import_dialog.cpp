#include "import_dialog.h"

#include <cmath>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTimer>
#include <QVBoxLayout>

#include "store/patient_library.h"
#include "live/patient_choice.h"
#include "vtk_view.h"

namespace palpation::ui {

ImportDialog::ImportDialog(app::store::PatientLibrary* library, QWidget* parent) : QDialog(parent), library_(library) {
  setObjectName(QStringLiteral("ImportDialog"));
  file = new QLineEdit;
  browse = new QPushButton;
  name = new QLineEdit;
  resolution = new QComboBox;
  for (const char* r : {"coarse", "paper", "fine"}) resolution->addItem(QString(), QString::fromLatin1(r));
  scale = new QComboBox;
  scale->addItem(QString(), 1.0);
  scale->addItem(QString(), 0.01);
  scale->addItem(QString(), 0.001);
  base_auto = new QCheckBox;
  base_auto->setChecked(true);
  const double def[4] = {0, 0, -1, 0};
  auto* base_row = new QHBoxLayout;
  for (int i = 0; i < 4; ++i) {
    base[i] = new QDoubleSpinBox;
    base[i]->setRange(i < 3 ? -1.0 : -2.0, i < 3 ? 1.0 : 2.0);
    base[i]->setDecimals(i < 3 ? 3 : 4);
    base[i]->setSingleStep(i < 3 ? 0.1 : 0.001);
    base[i]->setValue(def[i]);
    base[i]->setEnabled(false);
    base_row->addWidget(base[i]);
  }
  progress = new QProgressBar;
  progress->setRange(0, 1000);
  stage = new QLabel;
  report = new QLabel;
  report->setWordWrap(true);
  error = new QLabel;
  error->setWordWrap(true);
  error->setStyleSheet(QStringLiteral("color: #b00000; font-weight: bold"));
  error->setTextInteractionFlags(Qt::TextSelectableByMouse);
  import = new QPushButton;
  cancel = new QPushButton;
  cancel->setEnabled(false);
  save = new QPushButton;
  save->setEnabled(false);
  close_button = new QPushButton;
  preview = new VtkView;
  preview->setMinimumSize(420, 320);

  auto* file_row = new QHBoxLayout;
  file_row->addWidget(file, 1);
  file_row->addWidget(browse);
  auto* form = new QFormLayout;
  form->addRow(QStringLiteral("file"), file_row);
  form->addRow(QStringLiteral("name"), name);
  form->addRow(QStringLiteral("resolution"), resolution);
  form->addRow(QStringLiteral("scale"), scale);
  form->addRow(QStringLiteral("base"), base_auto);
  form->addRow(QStringLiteral("plane"), base_row);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(import);
  buttons->addWidget(cancel);
  buttons->addStretch();
  buttons->addWidget(save);
  buttons->addWidget(close_button);
  auto* left = new QVBoxLayout;
  left->addLayout(form);
  left->addWidget(progress);
  left->addWidget(stage);
  left->addWidget(error);
  left->addWidget(report, 1);
  auto* top = new QHBoxLayout;
  top->addLayout(left, 1);
  top->addWidget(preview, 1);
  auto* lay = new QVBoxLayout(this);
  lay->addLayout(top, 1);
  lay->addLayout(buttons);

  connect(browse, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Scanned breast surface"), QString(),
                                                   tr("Surface meshes (*.stl *.obj *.ply);;All files (*)"));
    if (f.isEmpty()) return;
    file->setText(f);
    if (name->text().isEmpty()) name->setText(QFileInfo(f).completeBaseName());
  });
  connect(base_auto, &QCheckBox::toggled, this, [this](bool on) {
    for (auto* b : base) b->setEnabled(!on);
  });
  connect(import, &QPushButton::clicked, this, &ImportDialog::start_import);
  connect(cancel, &QPushButton::clicked, this, [this] {
    stage->setText(tr("Cancelling..."));
    job_.cancel();  // kills the Gmsh child; returns when the worker has stopped
    poll();
  });
  connect(save, &QPushButton::clicked, this, &ImportDialog::save_patient);
  connect(close_button, &QPushButton::clicked, this, &ImportDialog::reject);
  timer_ = new QTimer(this);
  connect(timer_, &QTimer::timeout, this, &ImportDialog::poll);
  retranslate();
  resize(1000, 560);
}

ImportDialog::~ImportDialog() { job_.cancel(); }

void ImportDialog::retranslate() {
  setWindowTitle(tr("Import a scanned breast"));
  auto* form = findChild<QFormLayout*>();
  auto label = [form](QWidget* w, const QString& t) {
    if (auto* l = qobject_cast<QLabel*>(form->labelForField(w))) l->setText(t);
  };
  if (form) {
    label(name, tr("Patient name"));
    label(resolution, tr("Resolution"));
    label(scale, tr("File units"));
    label(base_auto, tr("Chest-wall plane"));
    for (int i = 0; i < form->rowCount(); ++i) {
      if (auto* it = form->itemAt(i, QFormLayout::LabelRole)) {
        if (auto* l = qobject_cast<QLabel*>(it->widget())) {
          if (i == 0) l->setText(tr("Scan file"));
          if (i == 5) l->setText(tr("n (into the chest), d (m)"));
        }
      }
    }
  }
  browse->setText(tr("Browse..."));
  resolution->setItemText(0, tr("Coarse (real time on a CPU)"));
  resolution->setItemText(1, tr("Paper (GPU)"));
  resolution->setItemText(2, tr("Fine (GPU)"));
  scale->setItemText(0, tr("metres"));
  scale->setItemText(1, tr("centimetres"));
  scale->setItemText(2, tr("millimetres"));
  base_auto->setText(tr("Find automatically (the largest flat region)"));
  base_auto->setToolTip(tr("Untick to give the plane n . x = d by hand: n points out of the body into the chest."));
  import->setText(tr("Import"));
  cancel->setText(tr("Cancel import"));
  save->setText(tr("Save as patient"));
  close_button->setText(tr("Close"));
}

void ImportDialog::changeEvent(QEvent* e) {
  if (e->type() == QEvent::LanguageChange && import) retranslate();
  QDialog::changeEvent(e);
}

void ImportDialog::reject() {
  job_.cancel();
  QDialog::reject();
}

double ImportDialog::edge() const {
  const auto e = app::live::resolution_edge("breast", resolution->currentData().toString().toStdString());
  return e ? *e : 0.00515;
}

bool ImportDialog::importing() const { return job_.running() || (timer_ && timer_->isActive()); }

void ImportDialog::start_import() {
  error->clear();
  report->clear();
  save->setEnabled(false);
  const QString f = file->text().trimmed();
  if (f.isEmpty()) {
    error->setText(tr("Choose a scan file (STL, OBJ or PLY) first."));
    return;
  }
  app::scan::ImportOptions o;
  o.edge = edge();
  o.scale = scale->currentData().toDouble();
  if (!base_auto->isChecked()) {
    const Eigen::Vector3d n(base[0]->value(), base[1]->value(), base[2]->value());
    if (!(n.norm() > 1e-6)) {
      error->setText(tr("The base plane's normal must not be zero."));
      return;
    }
    app::scan::BasePlane b;
    b.normal = n.normalized();
    b.offset = base[3]->value() / n.norm();
    b.automatic = false;
    o.base = b;
  }
  imported_file_ = f;
  imported_edge_ = o.edge;
  job_.start(f.toStdString(), std::move(o));
  import->setEnabled(false);
  cancel->setEnabled(true);
  progress->setValue(0);
  stage->setText(tr("Reading %1...").arg(QFileInfo(f).fileName()));
  timer_->start(50);
}

void ImportDialog::poll() {
  progress->setValue(int(job_.progress() * 1000));
  if (job_.running()) {
    stage->setText(QString::fromStdString(job_.stage()));
    return;
  }
  if (!job_.finished()) return;
  timer_->stop();
  import->setEnabled(true);
  cancel->setEnabled(false);
  if (job_.cancelled()) {
    stage->setText(tr("Cancelled: nothing was saved."));
    progress->setValue(0);
    return;
  }
  const auto r = job_.result();
  if (!r) {
    stage->setText(tr("Import failed: nothing was saved."));
    error->setText(QString::fromStdString(job_.error()));
    return;
  }
  progress->setValue(1000);
  stage->setText(tr("Done in %1 s (meshing %2 s).").arg(r->seconds, 0, 'f', 1).arg(r->mesh_seconds, 0, 'f', 1));
  const std::string rep = r->report.repairs();
  // The chest wall that will be fixed, shown before saving: its area, its share of the
  // body's outline and its tilt in the scan's frame.
  report->setText(tr("%1 nodes, %2 tetrahedra. Repairs: %3. Chest wall (fixed) %4: n = (%5, %6, %7), %8 cm², "
                     "%9 % of the body's outline, tilted %10° from the scan's z axis.")
                      .arg(r->mesh.num_nodes())
                      .arg(r->mesh.num_tets())
                      .arg(rep.empty() ? tr("none") : QString::fromStdString(rep))
                      .arg(r->base.automatic ? tr("found") : tr("given"))
                      .arg(r->base.normal.x(), 0, 'f', 3)
                      .arg(r->base.normal.y(), 0, 'f', 3)
                      .arg(r->base.normal.z(), 0, 'f', 3)
                      .arg(r->base.area * 1e4, 0, 'f', 1)
                      .arg(100.0 * r->base.footprint_fraction(), 0, 'f', 0)
                      .arg(r->base.tilt_deg(), 0, 'f', 0));
  preview->set_patient(app::scan::preview_geometry(r->mesh, ++generation_));
  preview->set_camera(VtkView::CameraPreset::Oblique);
  preview->update();
  save->setEnabled(library_ != nullptr);
  if (!library_) save->setToolTip(tr("No patient library is open."));
}

void ImportDialog::save_patient() {
  const auto r = job_.result();
  if (!r || !library_) return;
  const QString n = name->text().trimmed();
  if (n.isEmpty()) {
    error->setText(tr("Give the patient a name."));
    return;
  }
  try {
    if (library_->find(n.toStdString())) {
      error->setText(tr("A patient named \"%1\" exists already in %2: choose another name.")
                         .arg(n, QString::fromStdString(library_->location())));
      return;
    }
    library_->add(app::scan::imported_patient_record(*r, n.toStdString(), imported_file_.toStdString(), imported_edge_));
  } catch (const std::exception& e) {
    error->setText(QString::fromStdString(e.what()));
    return;
  }
  error->clear();
  saved_ = n;
  stage->setText(tr("Saved as \"%1\" in the patient library.").arg(n));
  save->setEnabled(false);
  emit patientSaved(n);
}

}  // namespace palpation::ui
