#include "live/tumour_document.h"

#include <algorithm>
#include <cmath>

#include "live/workstation.h"
#include "mesh.h"
#include "scenario.h"

namespace palpation::app::live {

std::vector<int> MaterialChange::elements() const {
  std::vector<int> v;
  v.reserve(after.size());
  for (const auto& [e, E] : after) v.push_back(e);
  return v;
}

void TumourDocument::set_patient(std::shared_ptr<const PatientGeometry> g) {
  g_ = std::move(g);
  young_ = g_ ? g_->young : std::vector<double>{};
  tumours_.clear();
  stroking_ = false;
  stroke_ = {};
  painted_count_ = 0;
  if (!g_) return;
  // The tumours the patient came with (scenario inclusions): one entry.
  Tumour own;
  for (std::size_t e = 0; e < young_.size(); ++e)
    if (is_tumour(int(e))) own.elements.push_back(int(e));
  if (!own.elements.empty()) tumours_.push_back(std::move(own));
}

std::uint64_t TumourDocument::generation() const { return g_ ? g_->generation : 0; }

double TumourDocument::tissue_young() const { return g_ ? g_->tissue_young : 0.0; }

bool TumourDocument::is_tumour(int e) const {
  return g_ && e >= 0 && e < int(young_.size()) && is_tumour_modulus(young_[std::size_t(e)], g_->base_of(e));
}

int TumourDocument::tumour_element_count() const {
  int n = 0;
  for (int e = 0; e < int(young_.size()); ++e) n += is_tumour(e);
  return n;
}

std::vector<std::array<int, 3>> TumourDocument::tumour_faces() const {
  if (!g_) return {};
  // The tumour elements as a mesh of their own over the patient's nodes: its boundary is
  // the tumour's surface (the same extraction that gives the patient's skin, Model::surface).
  sim::TetMesh m;
  m.nodes = g_->rest;
  for (int e = 0; e < int(young_.size()) && e < int(g_->tets.size()); ++e)
    if (is_tumour(e)) m.tets.push_back(g_->tets[std::size_t(e)]);
  if (m.tets.empty()) return {};
  return m.boundary_faces();
}

std::vector<int> TumourDocument::elements_in(TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii) const {
  std::vector<int> v;
  if (!g_) return v;
  sim::Inclusion inc;
  inc.shape = shape == TumourShape::Sphere ? "sphere" : "ellipsoid";
  inc.center = centre;
  inc.radii = shape == TumourShape::Sphere ? Eigen::Vector3d::Constant(radii.x()) : radii;
  for (std::size_t e = 0; e < g_->centroid.size(); ++e)
    if (inc.contains(g_->centroid[e])) v.push_back(int(e));
  return v;
}

MaterialChange TumourDocument::shape_change(TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii,
                                            double young) const {
  MaterialChange c;
  for (int e : elements_in(shape, centre, radii)) {
    c.before[e] = young_[std::size_t(e)];
    c.after[e] = young;
  }
  return c;
}

MaterialChange TumourDocument::removal(int i) const {
  MaterialChange c;
  if (!g_ || i < 0 || i >= int(tumours_.size())) return c;
  for (int e : tumours_[std::size_t(i)].elements) {
    if (e < 0 || e >= int(young_.size())) continue;
    c.before[e] = young_[std::size_t(e)];
    c.after[e] = g_->base_of(e);
  }
  return c;
}

std::vector<int> TumourDocument::elements_under_brush(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                                      const Brush& b) const {
  std::vector<int> v;
  if (!g_) return v;
  const Eigen::Vector3d n = normal.norm() > 0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d c = point - n * b.depth;
  for (std::size_t e = 0; e < g_->centroid.size(); ++e)
    if ((g_->centroid[e] - c).norm() <= b.radius) v.push_back(int(e));
  return v;
}

Moduli TumourDocument::dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Brush& b, bool erase) const {
  Moduli m;
  if (!g_) return m;
  for (int e : elements_under_brush(point, normal, b)) {
    const double target = erase ? g_->base_of(e) : b.young;
    if (young_[std::size_t(e)] != target) m[e] = target;
  }
  return m;
}

std::vector<std::pair<int, double>> TumourDocument::set_young(const std::vector<std::pair<int, double>>& changes) {
  std::vector<std::pair<int, double>> done;
  done.reserve(changes.size());
  for (const auto& [e, E] : changes) {
    if (e < 0 || e >= int(young_.size()) || !(E > 0)) continue;
    young_[std::size_t(e)] = E;
    done.emplace_back(e, E);
  }
  return done;
}

void TumourDocument::insert_tumour(int at, Tumour t) {
  at = std::clamp(at, 0, int(tumours_.size()));
  tumours_.insert(tumours_.begin() + at, std::move(t));
}

void TumourDocument::erase_tumour(int at) {
  if (at >= 0 && at < int(tumours_.size())) tumours_.erase(tumours_.begin() + at);
}

void TumourDocument::begin_stroke(bool erase) {
  stroking_ = true;
  erase_ = erase;
  stroke_ = {};
}

Moduli TumourDocument::stroke_dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (!stroking_) return {};
  Moduli m = dab(point, normal, brush_, erase_);
  for (const auto& [e, E] : m) {
    stroke_.before.emplace(e, young_[std::size_t(e)]);  // the value before the stroke's first dab
    stroke_.after[e] = E;
  }
  return m;
}

std::optional<TumourDocument::Stroke> TumourDocument::end_stroke() {
  if (!stroking_) return std::nullopt;
  stroking_ = false;
  if (stroke_.empty()) return std::nullopt;
  Stroke s;
  s.change = std::move(stroke_);
  stroke_ = {};
  s.erase = erase_;
  if (!erase_) {
    Tumour t;
    t.label.origin = TumourLabel::Origin::Painted;
    t.label.number = ++painted_count_;
    t.label.young = brush_.young;
    t.elements = s.change.elements();
    s.painted = std::move(t);
  }
  return s;
}

std::vector<std::array<int, 3>> deep_layer_faces(const PatientGeometry& g) {
  if (g.base_young.size() != g.tets.size() || g.tets.empty()) return {};
  const auto [lo, hi] = std::minmax_element(g.base_young.begin(), g.base_young.end());
  if (!(*hi > *lo * 1.01)) return {};
  // The modulus under the skin: the mean over the elements with a node on the surface.
  std::vector<char> on_surface(g.rest.size(), 0);
  for (const auto& f : g.surface)
    for (int v : f) on_surface[std::size_t(v)] = 1;
  double skin_side = 0;
  int n = 0;
  for (std::size_t e = 0; e < g.tets.size(); ++e)
    if (std::any_of(g.tets[e].begin(), g.tets[e].end(), [&](int v) { return on_surface[std::size_t(v)] != 0; })) {
      skin_side += g.base_young[e];
      ++n;
    }
  if (n == 0) return {};
  skin_side /= n;
  const double half = 0.5 * (*hi - *lo);
  sim::TetMesh deep, all;
  deep.nodes = all.nodes = g.rest;
  all.tets = g.tets;
  for (std::size_t e = 0; e < g.tets.size(); ++e)
    if (std::abs(g.base_young[e] - skin_side) > half) deep.tets.push_back(g.tets[e]);
  if (deep.tets.empty()) return {};
  auto key = [](std::array<int, 3> f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  std::vector<std::array<int, 3>> outer;
  for (const auto& f : all.boundary_faces()) outer.push_back(key(f));
  std::sort(outer.begin(), outer.end());
  std::vector<std::array<int, 3>> faces;
  for (const auto& f : deep.boundary_faces())
    if (!std::binary_search(outer.begin(), outer.end(), key(f))) faces.push_back(f);
  return faces;
}

}  // namespace palpation::app::live
