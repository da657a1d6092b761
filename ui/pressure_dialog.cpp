#include "pressure_dialog.h"

#include <stdexcept>

#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace palpation::ui {

PressureDialog::PressureDialog(const app::train::PressureThresholds& t, QWidget* parent) : QDialog(parent) {
  setObjectName(QStringLiteral("PressureDialog"));
  setWindowTitle(tr("Pressure levels"));
  auto* intro = new QLabel(tr("A touch counts at a level when the fingertip pad presses the skin in by this share of the "
                              "tissue's thickness under it, or presses with this force, whichever comes first. "
                              "They apply to the exams that start from now on."));
  intro->setWordWrap(true);
  auto* grid = new QGridLayout;
  grid->addWidget(new QLabel(tr("Indentation (% of thickness)")), 0, 1);
  grid->addWidget(new QLabel(tr("Force (N)")), 0, 2);
  const QString names[3] = {tr("Light"), tr("Medium"), tr("Deep")};
  const char* keys[3] = {"light", "medium", "deep"};
  for (int l = 0; l < 3; ++l) {
    grid->addWidget(new QLabel(names[l]), l + 1, 0);
    depth_[l] = new QDoubleSpinBox;
    depth_[l]->setObjectName(QStringLiteral("%1_depth").arg(QLatin1String(keys[l])));
    depth_[l]->setRange(0.1, 99.0);
    depth_[l]->setDecimals(1);
    depth_[l]->setSuffix(QStringLiteral(" %"));
    force_[l] = new QDoubleSpinBox;
    force_[l]->setObjectName(QStringLiteral("%1_force").arg(QLatin1String(keys[l])));
    force_[l]->setRange(0.01, 50.0);
    force_[l]->setDecimals(2);
    force_[l]->setSuffix(QStringLiteral(" N"));
    grid->addWidget(depth_[l], l + 1, 1);
    grid->addWidget(force_[l], l + 1, 2);
  }
  error_ = new QLabel;
  error_->setObjectName(QStringLiteral("pressure_error"));
  error_->setStyleSheet(QStringLiteral("color: #b00020"));
  error_->setWordWrap(true);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel | QDialogButtonBox::RestoreDefaults);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("OK"));
  buttons->button(QDialogButtonBox::Cancel)->setText(tr("Cancel"));
  buttons->button(QDialogButtonBox::RestoreDefaults)->setText(tr("Restore defaults"));
  connect(buttons, &QDialogButtonBox::accepted, this, &PressureDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(buttons->button(QDialogButtonBox::RestoreDefaults), &QPushButton::clicked, this,
          [this] { set_thresholds(app::train::PressureThresholds{}); });
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(intro);
  layout->addLayout(grid);
  layout->addWidget(error_);
  layout->addWidget(buttons);
  set_thresholds(t);
}

app::train::PressureThresholds PressureDialog::thresholds() const {
  app::train::PressureThresholds t;
  t.light_depth = depth_[0]->value() / 100.0;
  t.medium_depth = depth_[1]->value() / 100.0;
  t.deep_depth = depth_[2]->value() / 100.0;
  t.light_force = force_[0]->value();
  t.medium_force = force_[1]->value();
  t.deep_force = force_[2]->value();
  return t;
}

void PressureDialog::set_thresholds(const app::train::PressureThresholds& t) {
  const double d[3] = {t.light_depth, t.medium_depth, t.deep_depth}, f[3] = {t.light_force, t.medium_force, t.deep_force};
  for (int l = 0; l < 3; ++l) {
    depth_[l]->setValue(d[l] * 100.0);
    force_[l]->setValue(f[l]);
  }
  error_->clear();
}

void PressureDialog::accept() {
  try {
    thresholds().validate();
  } catch (const std::invalid_argument&) {
    // The scorer's reason names its JSON fields; the dialog says it in the fields' terms.
    error_->setText(tr("Each level must be above the one before it, in indentation and in force, and deep indentation "
                       "below 100 %."));
    return;
  }
  error_->clear();
  QDialog::accept();
}

QString PressureDialog::error_text() const { return error_->text(); }

}  // namespace palpation::ui
