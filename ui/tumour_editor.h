// Tumours as the instructor edits them: per-element Young's modulus (the document), the
// list of tumours (added by shape or painted), and undo commands. Every change goes to the
// running simulation as one queued material command (app::live::Workstation::set_element_young:
// the model's per-element materials, then Backend::update_materials(), no remeshing).
// A brush stroke (press, drag, release) is one undo step.
#pragma once

#include <map>
#include <memory>
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
  void set_patient(std::shared_ptr<const app::live::PatientGeometry> g);
  std::shared_ptr<const app::live::PatientGeometry> patient() const { return g_; }
  QUndoStack* undo_stack() { return &undo_; }
  const std::vector<double>& young() const { return young_; }
  QStringList tumour_names() const;

  /// Adds a sphere/ellipsoid tumour (elements whose rest centroid lies inside). One undo
  /// step. Returns the number of elements it changed.
  int add_shape(const QString& shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, double young);
  /// Removes tumour i (its elements back to the tissue's modulus). One undo step.
  void remove_tumour(int i);

  // Brush: a ball of `radius` centred `depth` below the touched surface point.
  void set_brush(double radius, double depth, double young) {
    brush_radius_ = radius;
    brush_depth_ = depth;
    brush_young_ = young;
  }
  void begin_stroke(bool erase);
  /// Paints (or erases) at a surface point with outward normal n; applied at once.
  int dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  /// Ends the stroke: pushes it onto the undo stack as one step.
  void end_stroke();

  /// Sets elements' moduli in the document and the simulation (undo commands use it).
  void apply(const std::map<int, double>& young, const QString& text);
  void insert_tumour(int at, const QString& name, const std::vector<int>& elements);
  void erase_tumour(int at);

 signals:
  void changed();

 private:
  app::live::Workstation* ws_;
  std::shared_ptr<const app::live::PatientGeometry> g_;
  std::vector<double> young_;
  struct Tumour {
    QString name;  // English (shown through RecordedText: tumour_names())
    std::vector<int> elements;
  };
  std::vector<Tumour> tumours_;
  QUndoStack undo_;
  double brush_radius_ = 0.008, brush_depth_ = 0.012, brush_young_ = 107000;
  bool stroking_ = false, erase_ = false;
  std::map<int, double> stroke_old_, stroke_new_;
  int painted_count_ = 0;
};

}  // namespace palpation::ui
