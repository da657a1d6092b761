// The tumours as the GUI knows them: the patient's per-element Young's moduli (the one
// GUI-side copy: the tumour editor, the 3-D view and the recorder's material changes all
// come from it), the bulk tissue's modulus, the tumour rule, the tumour list, the shapes
// and the brush that make tumours, and the tumours' boundary faces for drawing.
//
// The document changes nothing by itself in the simulation: live::Workstation owns it,
// and Workstation::set_element_young sets the moduli here and queues the same change for
// the simulation thread. The queries (shape_change, dab, removal) say what a change would
// be; undo steps (ui/) apply them through the workstation. GUI thread only. Qt-free.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "live/event.h"
#include "model.h"

namespace palpation::app::live {

struct PatientGeometry;

using sim::is_tumour_modulus;  // the tumour rule (sim/model.h)

/// Element -> Young's modulus (Pa).
using Moduli = std::map<int, double>;

/// A change of element moduli as one undo step: the values before and after.
struct MaterialChange {
  Moduli before, after;
  bool empty() const { return after.empty(); }
  std::vector<int> elements() const;
};

/// One entry of the tumour list: how it was made and its elements.
struct Tumour {
  TumourLabel label;
  std::vector<int> elements;
};

/// The brush: a ball of `radius` centred `depth` below the touched skin point (m), painting
/// `young` (Pa).
struct Brush {
  double radius = 0.008;
  double depth = 0.012;
  double young = 107000;
};

class TumourDocument {
 public:
  TumourDocument() = default;
  explicit TumourDocument(std::shared_ptr<const PatientGeometry> g) { set_patient(std::move(g)); }

  /// A new patient: its load-time moduli, the tumour list with one entry for the stiff
  /// elements it came with (scenario inclusions), no stroke.
  void set_patient(std::shared_ptr<const PatientGeometry> g);
  const std::shared_ptr<const PatientGeometry>& patient() const { return g_; }
  /// The patient's generation (0 without one).
  std::uint64_t generation() const;

  /// (ntet) Pa.
  const std::vector<double>& young() const { return young_; }
  /// The bulk tissue's modulus, Pa (what erasing and removing restore).
  double tissue_young() const;
  bool is_tumour(int element) const;
  /// Elements that are tumour tissue now (the rule).
  int tumour_element_count() const;
  const std::vector<Tumour>& tumours() const { return tumours_; }
  /// The boundary of the tumour elements (faces no other tumour element shares, outward:
  /// sim::TetMesh::boundary_faces over them), node indices of the patient's mesh.
  std::vector<std::array<int, 3>> tumour_faces() const;

  // What a change would be (nothing changes) -------------------------------------------
  /// Elements whose rest centroid lies inside the shape (a sphere takes radii.x()).
  std::vector<int> elements_in(TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii) const;
  /// Those elements to `young` (Pa).
  MaterialChange shape_change(TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, double young) const;
  /// Tumour i's elements back to the tissue's modulus (empty for a bad index).
  MaterialChange removal(int i) const;
  /// Elements whose rest centroid lies in the brush's ball at a skin point with outward
  /// normal `normal`.
  std::vector<int> elements_under_brush(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Brush& b) const;
  /// The moduli a dab gives: the touched elements not already at the target (the brush's
  /// modulus, or the tissue's when erasing).
  Moduli dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Brush& b, bool erase) const;

  // Changes ---------------------------------------------------------------------------
  /// Sets moduli (elements out of range and non-positive moduli are skipped); returns the
  /// changes made, in element order.
  std::vector<std::pair<int, double>> set_young(const std::vector<std::pair<int, double>>& changes);
  void insert_tumour(int at, Tumour t);
  void erase_tumour(int at);

  // Brush strokes: press, drags, release as one undo step ----------------------------
  void set_brush(const Brush& b) { brush_ = b; }
  const Brush& brush() const { return brush_; }
  void begin_stroke(bool erase);
  bool stroking() const { return stroking_; }
  bool stroke_erases() const { return erase_; }
  /// A dab of the stroke: its moduli (dab() with the stroke's brush), remembered for the
  /// stroke's undo step. Not applied: the caller applies them (Workstation::set_element_young).
  Moduli stroke_dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  struct Stroke {
    MaterialChange change;
    bool erase = false;
    std::optional<Tumour> painted;  // a paint stroke's new tumour list entry (numbered)
  };
  /// Ends the stroke; nothing when no stroke was going on or it changed nothing.
  std::optional<Stroke> end_stroke();

 private:
  std::shared_ptr<const PatientGeometry> g_;
  std::vector<double> young_;
  std::vector<Tumour> tumours_;
  Brush brush_;
  bool stroking_ = false, erase_ = false;
  MaterialChange stroke_;
  int painted_count_ = 0;
};

/// The boundary of the patient's deeper tissue layer inside the breast, for drawing: the
/// elements whose own tissue (PatientGeometry::base_of) lies nearer the deepest layer's
/// modulus than the one under the skin (the glandular tissue under the fat of the
/// built-in breasts; an element that a band boundary cuts goes by its averaged
/// modulus). Faces on the breast's own boundary (the chest wall) are left out. Empty
/// for uniform tissue. With more than two layers it draws the boundary between the
/// skin-side half of the moduli and the rest.
std::vector<std::array<int, 3>> deep_layer_faces(const PatientGeometry& g);

}  // namespace palpation::app::live
