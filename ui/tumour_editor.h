// Tumours as the instructor edits them: undo commands over the workstation's tumour
// document (app/live/tumour_document.h: the moduli, the tumour rule, the tumour list, the
// shapes and the brush). Every change goes to the document and the running simulation as
// one queued material command (app::live::Workstation::set_element_young: the running
// body's materials, then Backend::set_materials(), no remeshing). A brush stroke
// (press, drag, release) is one undo step.
#pragma once

#include <vector>

#include <QObject>
#include <QString>
#include <QStringList>
#include <QUndoStack>

#include <Eigen/Core>

#include "live/workstation.h"

namespace palpation::ui {

/// A tissue stiffness preset with where the figure comes from (shared/reference/facts.md).
struct TissuePreset {
  QString name;    // translated
  double young;    // Pa
  QString source;  // translated
};
std::vector<TissuePreset> tissue_presets();

class TumourEditor : public QObject {
  Q_OBJECT

 public:
  explicit TumourEditor(app::live::Workstation* ws, QObject* parent = nullptr);
  /// A new patient (the workstation's document follows it): the undo history ends.
  void patient_changed();
  /// The workstation's tumour document.
  const app::live::TumourDocument& document() const { return ws_->tumours(); }
  QUndoStack* undo_stack() { return &undo_; }
  const std::vector<double>& young() const { return document().young(); }
  /// The tumour list, in the chosen language.
  QStringList tumour_names() const;

  /// Adds a sphere/ellipsoid tumour (elements whose rest centroid lies inside). One undo
  /// step. Returns the number of elements it changed.
  int add_shape(app::live::TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, double young);
  /// Removes tumour i (its elements back to the tissue's modulus). One undo step.
  void remove_tumour(int i);

  // Brush: a ball of `radius` centred `depth` below the touched surface point.
  void set_brush(double radius, double depth, double young);
  void begin_stroke(bool erase);
  /// Paints (or erases) at a surface point with outward normal n; applied at once.
  int dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  /// Ends the stroke: pushes it onto the undo stack as one step.
  void end_stroke();

  /// Sets elements' moduli in the document and the simulation (undo commands use it).
  void apply(const app::live::Moduli& young, const app::live::MaterialEdit& edit);
  void insert_tumour(int at, const app::live::Tumour& t);
  void erase_tumour(int at);

 signals:
  void changed();

 private:
  app::live::Workstation* ws_;
  QUndoStack undo_;
};

}  // namespace palpation::ui
