#include "train/exam.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "model.h"

namespace palpation::app::train {

using nlohmann::json;

const char* level_name(Level l) {
  switch (l) {
    case Level::Light: return "light";
    case Level::Medium: return "medium";
    case Level::Deep: return "deep";
    default: return "none";
  }
}

void PressureThresholds::validate() const {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("pressure thresholds: ") + what);
  };
  need(std::isfinite(light_depth) && light_depth > 0, "light_depth: must be a positive fraction of the thickness");
  need(std::isfinite(medium_depth) && medium_depth > light_depth, "medium_depth: must be above light_depth");
  need(std::isfinite(deep_depth) && deep_depth > medium_depth && deep_depth < 1, "deep_depth: must be above medium_depth and below 1");
  need(std::isfinite(light_force) && light_force > 0, "light_force: must be positive (N)");
  need(std::isfinite(medium_force) && medium_force > light_force, "medium_force: must be above light_force");
  need(std::isfinite(deep_force) && deep_force > medium_force, "deep_force: must be above medium_force");
}

Level classify(double depth, double thickness, double force, const PressureThresholds& t) {
  const double frac = thickness > 0 ? depth / thickness : 0.0;
  if (frac >= t.deep_depth || force >= t.deep_force) return Level::Deep;
  if (frac >= t.medium_depth || force >= t.medium_force) return Level::Medium;
  if (frac >= t.light_depth || force >= t.light_force) return Level::Light;
  return Level::None;
}

json to_json(const PressureThresholds& t) {
  return {{"light_depth", t.light_depth}, {"medium_depth", t.medium_depth}, {"deep_depth", t.deep_depth},
          {"light_force", t.light_force}, {"medium_force", t.medium_force}, {"deep_force", t.deep_force}};
}

PressureThresholds thresholds_from_json(const json& j, const PressureThresholds& base) {
  if (!j.is_object()) throw std::invalid_argument("pressure thresholds: must be an object");
  PressureThresholds t = base;
  auto take = [&](const char* key, double& v) {
    if (!j.contains(key)) return;
    if (!j[key].is_number()) throw std::invalid_argument(std::string("pressure thresholds: ") + key + ": must be a number");
    v = j[key].get<double>();
  };
  take("light_depth", t.light_depth);
  take("medium_depth", t.medium_depth);
  take("deep_depth", t.deep_depth);
  take("light_force", t.light_force);
  take("medium_force", t.medium_force);
  take("deep_force", t.deep_force);
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!to_json(PressureThresholds{}).contains(it.key()))
      throw std::invalid_argument("pressure thresholds: " + it.key() + ": unknown field");
  t.validate();
  return t;
}

SkinMap build_skin_map(const sim::Model& m) {
  SkinMap s;
  s.nodes = m.rest;
  // The outer surface is the boundary's connected piece that holds the chest wall (or the
  // largest, without one): a mesh's internal voids have boundary faces too, which no finger
  // can reach.
  const int nsurf = int(m.surface.size());
  std::map<std::pair<int, int>, std::vector<int>> surf_edges;
  for (int f = 0; f < nsurf; ++f)
    for (int k = 0; k < 3; ++k) {
      int a = m.surface[std::size_t(f)][std::size_t(k)], b = m.surface[std::size_t(f)][std::size_t((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      surf_edges[{a, b}].push_back(f);
    }
  std::vector<int> piece(std::size_t(nsurf), -1);
  std::vector<double> piece_area;
  std::vector<char> piece_chest;
  for (int f0 = 0; f0 < nsurf; ++f0) {
    if (piece[std::size_t(f0)] >= 0) continue;
    const int id = int(piece_area.size());
    piece_area.push_back(0);
    piece_chest.push_back(0);
    std::vector<int> stack{f0};
    piece[std::size_t(f0)] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      const auto& t = m.surface[std::size_t(f)];
      const Eigen::Vector3d &a = m.rest[std::size_t(t[0])], &b = m.rest[std::size_t(t[1])], &c = m.rest[std::size_t(t[2])];
      piece_area[std::size_t(id)] += 0.5 * (b - a).cross(c - a).norm();
      if (m.fixed[std::size_t(t[0])] && m.fixed[std::size_t(t[1])] && m.fixed[std::size_t(t[2])]) piece_chest[std::size_t(id)] = 1;
      for (int k = 0; k < 3; ++k) {
        int u = t[std::size_t(k)], v = t[std::size_t((k + 1) % 3)];
        if (u > v) std::swap(u, v);
        for (int g : surf_edges[{u, v}])
          if (piece[std::size_t(g)] < 0) {
            piece[std::size_t(g)] = id;
            stack.push_back(g);
          }
      }
    }
  }
  int outer = -1;
  for (int id = 0; id < int(piece_area.size()); ++id)
    if (outer < 0 || piece_chest[std::size_t(id)] > piece_chest[std::size_t(outer)] ||
        (piece_chest[std::size_t(id)] == piece_chest[std::size_t(outer)] && piece_area[std::size_t(id)] > piece_area[std::size_t(outer)]))
      outer = id;
  std::vector<int> chest;
  for (int f = 0; f < nsurf; ++f) {
    const auto& t = m.surface[std::size_t(f)];
    const bool on_chest = m.fixed[std::size_t(t[0])] && m.fixed[std::size_t(t[1])] && m.fixed[std::size_t(t[2])];
    if (on_chest) {
      chest.push_back(f);
      continue;
    }
    if (piece[std::size_t(f)] != outer) continue;
    s.faces.push_back(t);
    s.model_face.push_back(f);
  }
  const std::size_t n = s.faces.size();
  s.centroid.resize(n);
  s.normal.resize(n);
  s.area.resize(n);
  s.thickness.resize(n);
  s.lo = Eigen::Vector3d::Constant(1e300);
  s.hi = Eigen::Vector3d::Constant(-1e300);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = s.faces[i];
    const Eigen::Vector3d &a = m.rest[std::size_t(t[0])], &b = m.rest[std::size_t(t[1])], &c = m.rest[std::size_t(t[2])];
    const Eigen::Vector3d cr = (b - a).cross(c - a);
    s.area[i] = 0.5 * cr.norm();
    s.normal[i] = cr.norm() > 0 ? Eigen::Vector3d(cr.normalized()) : Eigen::Vector3d::UnitZ();
    s.centroid[i] = (a + b + c) / 3.0;
    s.total_area += s.area[i];
    s.lo = s.lo.cwiseMin(a.cwiseMin(b).cwiseMin(c));
    s.hi = s.hi.cwiseMax(a.cwiseMax(b).cwiseMax(c));
  }
  // Thickness: from the skin inward along the normal to the chest wall (the fixed faces);
  // where that ray misses the chest wall (a side of a box, a fold), the distance to the
  // nearest chest-wall node.
  std::vector<int> fixed_nodes;
  for (int v = 0; v < int(m.fixed.size()); ++v)
    if (m.fixed[std::size_t(v)]) fixed_nodes.push_back(v);
  for (std::size_t i = 0; i < n; ++i) {
    double best = -1;
    for (int f : chest) {
      const auto& t = m.surface[std::size_t(f)];
      const double d = sim::ray_triangle(s.centroid[i], -s.normal[i], m.rest[std::size_t(t[0])], m.rest[std::size_t(t[1])],
                                    m.rest[std::size_t(t[2])]);
      if (d > 0 && (best < 0 || d < best)) best = d;
    }
    if (best < 0) {
      for (int v : fixed_nodes) {
        const double d = (m.rest[std::size_t(v)] - s.centroid[i]).norm();
        if (best < 0 || d < best) best = d;
      }
    }
    s.thickness[i] = best > 0 ? best : 0.0;
  }
  // Neighbours across edges.
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      int a = s.faces[i][std::size_t(k)], b = s.faces[i][std::size_t((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      edges[{a, b}].push_back(int(i));
    }
  s.neighbours.assign(n, {});
  for (const auto& [e, fs] : edges)
    for (int a : fs)
      for (int b : fs)
        if (a != b) s.neighbours[std::size_t(a)].push_back(b);
  // The grid: cells of about two mean edge lengths.
  double mean_area = n ? s.total_area / double(n) : 1e-4;
  s.cell_ = std::max(1e-3, 2.0 * std::sqrt(2.0 * mean_area));
  for (int k = 0; k < 3; ++k) s.dims_[std::size_t(k)] = n ? std::max(1, int(std::ceil((s.hi[k] - s.lo[k]) / s.cell_)) + 1) : 1;
  s.grid_.assign(std::size_t(s.dims_[0]) * std::size_t(s.dims_[1]) * std::size_t(s.dims_[2]), {});
  for (std::size_t i = 0; i < n; ++i) {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[std::size_t(k)] = std::clamp(int((s.centroid[i][k] - s.lo[k]) / s.cell_), 0, s.dims_[std::size_t(k)] - 1);
    s.grid_[(std::size_t(c[2]) * std::size_t(s.dims_[1]) + std::size_t(c[1])) * std::size_t(s.dims_[0]) + std::size_t(c[0])]
        .push_back(int(i));
  }
  return s;
}

std::vector<int> SkinMap::faces_within(const Eigen::Vector3d& p, double r) const {
  std::vector<int> out;
  if (faces.empty() || !p.allFinite() || !(r >= 0)) return out;
  std::array<int, 3> a{}, b{};
  for (int k = 0; k < 3; ++k) {
    const double lo_c = (p[k] - r - lo[k]) / cell_, hi_c = (p[k] + r - lo[k]) / cell_;
    if (hi_c < 0 || lo_c > dims_[std::size_t(k)] - 1 + 1.0) return out;
    a[std::size_t(k)] = std::clamp(int(std::floor(lo_c)), 0, dims_[std::size_t(k)] - 1);
    b[std::size_t(k)] = std::clamp(int(std::floor(hi_c)), 0, dims_[std::size_t(k)] - 1);
  }
  const double r2 = r * r;
  for (int z = a[2]; z <= b[2]; ++z)
    for (int y = a[1]; y <= b[1]; ++y)
      for (int x = a[0]; x <= b[0]; ++x)
        for (int f : grid_[(std::size_t(z) * std::size_t(dims_[1]) + std::size_t(y)) * std::size_t(dims_[0]) + std::size_t(x)])
          if ((centroid[std::size_t(f)] - p).squaredNorm() <= r2) out.push_back(f);
  return out;
}

int SkinMap::nearest_face(const Eigen::Vector3d& p) const {
  if (faces.empty() || !p.allFinite()) return -1;
  // Grow the ball until it holds a centroid: the nearest inside it is the nearest of all.
  const double far = (hi - lo).norm() + (p - 0.5 * (lo + hi)).norm() + cell_;
  for (double r = cell_; ; r *= 2) {
    const std::vector<int> near = faces_within(p, std::min(r, far));
    if (!near.empty()) {
      int best = near[0];
      for (int f : near)
        if ((centroid[std::size_t(f)] - p).squaredNorm() < (centroid[std::size_t(best)] - p).squaredNorm()) best = f;
      return best;
    }
    if (r >= far) return -1;
  }
}

Eigen::Vector3d SkinMap::project(const Eigen::Vector3d& p) const {
  const int f = nearest_face(p);
  if (f < 0) return p;
  return p - (p - centroid[std::size_t(f)]).dot(normal[std::size_t(f)]) * normal[std::size_t(f)];
}

double SkinMap::distance(const Eigen::Vector3d& p) const { return (p - project(p)).norm(); }

Eigen::Vector3d SkinMap::skin_above(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  double best = -1;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (normal[i].dot(up) <= 0) continue;
    const double d = sim::ray_triangle(p, up, nodes[std::size_t(faces[i][0])], nodes[std::size_t(faces[i][1])],
                                  nodes[std::size_t(faces[i][2])]);
    if (d >= 0 && (best < 0 || d < best)) best = d;
  }
  if (best >= 0) return p + best * up;
  const int f = nearest_face(p);
  return f >= 0 ? centroid[std::size_t(f)] : p;
}

std::vector<TumourTruth> find_tumours(const std::vector<Eigen::Vector3d>& rest, const std::vector<std::array<int, 4>>& tets,
                                      const std::vector<double>& young, const std::vector<double>& tissue_young,
                                      const SkinMap& skin,
                                      double pad_radius) {
  const int ne = int(std::min({young.size(), tissue_young.size(), tets.size()}));
  std::vector<int> parent(rest.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[std::size_t(v)] != v) v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    return v;
  };
  std::vector<int> stiff;
  for (int e = 0; e < ne; ++e) {
    if (!sim::is_tumour_modulus(young[std::size_t(e)], tissue_young[std::size_t(e)])) continue;
    stiff.push_back(e);
    const auto& t = tets[std::size_t(e)];
    for (int k = 1; k < 4; ++k) parent[std::size_t(root(t[std::size_t(k)]))] = root(t[0]);
  }
  std::map<int, std::vector<int>> groups;
  for (int e : stiff) groups[root(tets[std::size_t(e)][0])].push_back(e);
  std::vector<TumourTruth> out;
  for (const auto& [r, els] : groups) {
    TumourTruth t;
    double vol = 0, ey = 0, et = 0;
    for (int e : els) {
      const auto& q = tets[std::size_t(e)];
      const Eigen::Vector3d c = 0.25 * (rest[std::size_t(q[0])] + rest[std::size_t(q[1])] + rest[std::size_t(q[2])] +
                                        rest[std::size_t(q[3])]);
      const double v = std::abs((rest[std::size_t(q[1])] - rest[std::size_t(q[0])])
                                    .dot((rest[std::size_t(q[2])] - rest[std::size_t(q[0])])
                                             .cross(rest[std::size_t(q[3])] - rest[std::size_t(q[0])]))) / 6.0;
      t.centre += v * c;
      vol += v;
      ey += v * young[std::size_t(e)];
      et += v * tissue_young[std::size_t(e)];
    }
    t.centre /= vol;
    t.young = ey / vol;
    t.contrast = et > 0 ? ey / et : 0;  // against the tissue it replaced
    t.elements = int(els.size());
    double top = -1e300;
    for (int e : els)
      for (int v : tets[std::size_t(e)]) {
        const Eigen::Vector3d& x = rest[std::size_t(v)];
        t.lateral_radius = std::max(t.lateral_radius, (x - t.centre).head<2>().norm());
        top = std::max(top, x.z());
      }
    t.skin_point = skin.skin_above(t.centre);
    t.depth = std::max(0.0, t.skin_point.z() - top);
    t.tolerance = t.lateral_radius + pad_radius;
    out.push_back(t);
  }
  std::sort(out.begin(), out.end(), [](const TumourTruth& a, const TumourTruth& b) {
    return a.centre.x() != b.centre.x() ? a.centre.x() < b.centre.x() : a.centre.y() < b.centre.y();
  });
  return out;
}

ExamTracker::ExamTracker(std::shared_ptr<const SkinMap> skin, PressureThresholds t) : skin_(std::move(skin)), t_(t) {
  t_.validate();
  reset();
}

void ExamTracker::reset() {
  level_.assign(skin_->faces.size(), 0);
  touched_.assign(skin_->faces.size(), 0);
  reached_.assign(skin_->faces.size(), LevelTimes{kNever, kNever, kNever});
  path_.clear();
  pressing_.fill(false);
  first_ = last_ = -1;
}

void ExamTracker::add(const FingerSample& s) {
  if (s.finger < 0 || s.finger >= int(pressing_.size()) || !s.centre.allFinite() || !(s.radius > 0)) return;
  const std::size_t k = std::size_t(s.finger);
  const SkinMap& skin = *skin_;
  const int f = skin.nearest_face(s.centre);
  if (f < 0) return;
  // The pad's reach below the rest skin, along the nearest face's normal.
  const double dist = (s.centre - skin.centroid[std::size_t(f)]).dot(skin.normal[std::size_t(f)]);
  const double depth = s.radius - dist;
  const Level lv = depth > 0 ? classify(depth, skin.thickness[std::size_t(f)], std::isfinite(s.force) ? s.force : 0.0, t_)
                             : Level::None;
  if (depth > 0) touched_[std::size_t(f)] = 1;
  if (lv == Level::None) {
    pressing_[k] = false;
    return;
  }
  // The pad's footprint on the rest skin: the circle where the fingertip sphere crosses the
  // skin's plane (radius sqrt(R^2 - (R - d)^2), the whole pad once it is sunk by R), and at
  // least R / 2: a real finger pad flattens on the skin, about 0.5 cm^2 of contact at light
  // forces (docs/training.md, "Coverage"), which a rigid sphere's cap underestimates.
  const double d = std::min(depth, s.radius);
  const double a = std::max(0.5 * s.radius, std::sqrt(std::max(0.0, s.radius * s.radius - (s.radius - d) * (s.radius - d))));
  const Eigen::Vector3d p = s.centre - dist * skin.normal[std::size_t(f)];
  const unsigned char l = static_cast<unsigned char>(lv);
  // The time each level (and those below it) was first reached on the face: a sample
  // without a finite time counts from the last one's, so that every level reached has a
  // time and levels_at() at the end is face_level().
  const double when = std::isfinite(s.t) ? s.t : std::max(0.0, last_);
  auto raise = [&](std::size_t g) {
    level_[g] = std::max(level_[g], l);
    LevelTimes& r = reached_[g];
    for (int q = 0; q < int(l); ++q) r[std::size_t(q)] = std::min(r[std::size_t(q)], when);
  };
  raise(std::size_t(f));
  for (int g : skin.faces_within(p, a)) raise(std::size_t(g));
  if (first_ < 0) first_ = s.t;
  last_ = std::max(last_, s.t);
  if (!pressing_[k] || (p - last_p_[k]).norm() >= 1e-3) {
    path_.push_back({s.t, p, s.finger, !pressing_[k]});
    last_p_[k] = p;
  }
  pressing_[k] = true;
}

std::vector<unsigned char> levels_at(const std::vector<LevelTimes>& reached, double t) {
  std::vector<unsigned char> out(reached.size(), 0);
  for (std::size_t i = 0; i < reached.size(); ++i) {
    unsigned char l = 0;
    while (l < kLevels && reached[i][l] < kNever && reached[i][l] <= t) ++l;
    out[i] = l;
  }
  return out;
}

std::array<double, kLevels> coverage_at(const SkinMap& skin, const std::vector<LevelTimes>& reached, double t) {
  std::array<double, kLevels> c{};
  if (skin.total_area <= 0) return c;
  for (std::size_t i = 0; i < reached.size() && i < skin.area.size(); ++i)
    for (std::size_t l = 0; l < std::size_t(kLevels); ++l)
      if (reached[i][l] < kNever && reached[i][l] <= t) c[l] += skin.area[i];
  for (double& v : c) v /= skin.total_area;
  return c;
}

std::array<double, kLevels> ExamTracker::coverage() const {
  std::array<double, kLevels> c{};
  const SkinMap& skin = *skin_;
  if (skin.total_area <= 0) return c;
  for (std::size_t i = 0; i < level_.size(); ++i)
    for (int l = 1; l <= kLevels; ++l)
      if (level_[i] >= l) c[std::size_t(l - 1)] += skin.area[i];
  for (double& v : c) v /= skin.total_area;
  return c;
}

double ExamTracker::touched() const {
  const SkinMap& skin = *skin_;
  double a = 0;
  for (std::size_t i = 0; i < touched_.size(); ++i)
    if (touched_[i] || level_[i]) a += skin.area[i];
  return skin.total_area > 0 ? a / skin.total_area : 0.0;
}

Level ExamTracker::level_near(const Eigen::Vector3d& p, double r) const {
  unsigned char best = 0;
  std::vector<int> fs = skin_->faces_within(p, r);
  if (fs.empty()) {
    const int f = skin_->nearest_face(p);
    if (f >= 0) fs.push_back(f);
  }
  for (int f : fs) best = std::max(best, level_[std::size_t(f)]);
  return static_cast<Level>(best);
}

PatternFigures ExamTracker::pattern() const {
  PatternFigures pf;
  const SkinMap& skin = *skin_;
  // Vertical strips: the patient's head-foot axis is y (the phantoms' and scans' frame,
  // docs/training.md). A strip is a run of one finger's pressed path that stays within
  // 5 mm of its starting x and keeps its direction along y (turning back by more than 5 mm
  // ends it; small circles along the way do not) while it travels at least a third of the
  // skin's length in y.
  const double half_band = 0.005, turn = 0.005, min_len = (skin.hi.y() - skin.lo.y()) / 3.0;
  std::vector<double> strip_x;
  double strip_len = 0;
  for (int finger = 0; finger < 5; ++finger) {
    std::vector<const PathPoint*> pts;
    for (const auto& p : path_)
      if (p.finger == finger) pts.push_back(&p);
    std::size_t i = 0;
    while (i < pts.size()) {
      std::size_t j = i + 1;
      double len = 0, ylo = pts[i]->p.y(), yhi = ylo, xs = pts[i]->p.x();
      int dir = 0;  // +1 towards the head, -1 towards the feet, 0 not yet
      while (j < pts.size() && !pts[j]->start && std::abs(pts[j]->p.x() - pts[i]->p.x()) <= half_band) {
        const double y = pts[j]->p.y();
        if (dir == 0 && std::abs(y - pts[i]->p.y()) > turn) dir = y > pts[i]->p.y() ? 1 : -1;
        if ((dir > 0 && yhi - y > turn) || (dir < 0 && y - ylo > turn)) break;
        len += (pts[j]->p - pts[j - 1]->p).norm();
        ylo = std::min(ylo, y);
        yhi = std::max(yhi, y);
        xs += pts[j]->p.x();
        ++j;
      }
      if (yhi - ylo >= min_len && min_len > 0) {
        strip_x.push_back(xs / double(j - i));
        strip_len += len;
      }
      i = j;
    }
    for (std::size_t q = 1; q < pts.size(); ++q)
      if (!pts[q]->start) pf.path_length += (pts[q]->p - pts[q - 1]->p).norm();
  }
  pf.vertical_fraction = pf.path_length > 0 ? std::min(1.0, strip_len / pf.path_length) : 0.0;
  // Lanes: strips closer than a third of a pad width are the same lane gone over again.
  std::sort(strip_x.begin(), strip_x.end());
  const double pad = 0.016;  // the finger pad's width: twice the fingertip radius of 8 mm
  std::vector<double> lanes;
  for (double x : strip_x)
    if (lanes.empty() || x - lanes.back() > pad / 3) lanes.push_back(x);
  pf.strips = int(lanes.size());
  if (lanes.size() >= 2) {
    double s = 0;
    for (std::size_t i = 1; i < lanes.size(); ++i) s += 1.0 - (lanes[i] - lanes[i - 1]) / pad;
    pf.mean_overlap = s / double(lanes.size() - 1);
  }
  // Skipped regions: connected unpalpated faces.
  std::vector<char> seen(level_.size(), 0);
  for (std::size_t i = 0; i < level_.size(); ++i) {
    if (seen[i] || level_[i] > 0) continue;
    PatternFigures::Region r;
    std::vector<int> stack{int(i)};
    seen[i] = 1;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      r.area += skin.area[std::size_t(f)];
      r.centre += skin.area[std::size_t(f)] * skin.centroid[std::size_t(f)];
      for (int g : skin.neighbours[std::size_t(f)])
        if (!seen[std::size_t(g)] && level_[std::size_t(g)] == 0) {
          seen[std::size_t(g)] = 1;
          stack.push_back(g);
        }
    }
    if (r.area >= 1e-4) {
      r.centre /= r.area;
      pf.skipped.push_back(r);
    }
  }
  std::sort(pf.skipped.begin(), pf.skipped.end(), [](const auto& a, const auto& b) { return a.area > b.area; });
  return pf;
}

ExamScore score_exam(const ExamTracker& tracker, const std::vector<TumourTruth>& tumours, std::vector<Mark> marks,
                     double duration) {
  ExamScore s;
  s.coverage = tracker.coverage();
  s.touched = tracker.touched();
  s.pattern = tracker.pattern();
  s.thresholds = tracker.thresholds();
  s.duration = duration;
  s.exam_time = tracker.first_contact() >= 0 ? std::max(0.0, duration - tracker.first_contact()) : 0.0;
  std::stable_sort(marks.begin(), marks.end(), [](const Mark& a, const Mark& b) { return a.t < b.t; });
  s.marks = marks;
  for (const Mark& m : marks) s.marks_on_skin.push_back(tracker.skin().project(m.position));
  for (const TumourTruth& t : tumours) {
    TumourResult r;
    r.truth = t;
    r.max_level_over = tracker.level_near(t.skin_point, std::max(t.lateral_radius, 0.005));
    r.deep_reached = r.max_level_over == Level::Deep;
    s.tumours.push_back(r);
  }
  // Each tumour is found by the nearest mark within its tolerance; a mark finds one tumour
  // at most (closest pairs first).
  struct Pair {
    double d;
    int mark, tumour;
  };
  std::vector<Pair> pairs;
  std::vector<char> on_tumour(marks.size(), 0);
  for (int i = 0; i < int(marks.size()); ++i)
    for (int k = 0; k < int(tumours.size()); ++k) {
      const double d = (s.marks_on_skin[std::size_t(i)] - tumours[std::size_t(k)].skin_point).norm();
      if (d <= tumours[std::size_t(k)].tolerance) {
        pairs.push_back({d, i, k});
        on_tumour[std::size_t(i)] = 1;
      }
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d < b.d; });
  std::vector<char> used(marks.size(), 0);
  double err = 0;
  for (const Pair& p : pairs) {
    TumourResult& r = s.tumours[std::size_t(p.tumour)];
    if (r.found || used[std::size_t(p.mark)]) continue;
    r.found = true;
    r.mark = p.mark;
    r.error = p.d;
    r.time_to_find = marks[std::size_t(p.mark)].t;
    used[std::size_t(p.mark)] = 1;
    ++s.hits;
    err += p.d;
  }
  // A second mark on a tumour already found is a repeat, not a false positive.
  for (int i = 0; i < int(marks.size()); ++i)
    if (!on_tumour[std::size_t(i)]) s.false_positive_marks.push_back(i);
  s.false_positives = int(s.false_positive_marks.size());
  if (!tumours.empty()) s.sensitivity = double(s.hits) / double(tumours.size());
  if (!marks.empty()) s.ppv = double(marks.size() - s.false_positive_marks.size()) / double(marks.size());
  if (tumours.empty()) s.specific = marks.empty();
  s.mean_error = s.hits ? err / s.hits : 0.0;
  // What to practise next.
  auto pct = [](double v) { return int(std::lround(100 * v)); };
  for (int l = 0; l < kLevels; ++l)
    if (s.coverage[std::size_t(l)] < 0.9) {
      Advice a{Advice::Kind::Coverage};
      a.level = static_cast<Level>(l + 1);
      a.percent = pct(s.coverage[std::size_t(l)]);
      s.advice.push_back(a);
    }
  if (s.pattern.path_length > 0 && (s.pattern.strips < 3 || s.pattern.vertical_fraction < 0.5)) {
    Advice a{Advice::Kind::Strips};
    a.count = s.pattern.strips;
    a.percent = pct(s.pattern.vertical_fraction);
    s.advice.push_back(a);
  } else if (s.pattern.strips >= 2 && s.pattern.mean_overlap < 0) {
    s.advice.push_back({Advice::Kind::Overlap});
  }
  for (const TumourResult& r : s.tumours)
    if (!r.found && !r.deep_reached) {
      Advice a{Advice::Kind::PressDeep};
      a.depth_mm = int(std::lround(r.truth.depth * 1000));
      s.advice.push_back(a);
    }
  if (s.false_positives > 0) {
    Advice a{Advice::Kind::FalsePositives};
    a.count = s.false_positives;
    s.advice.push_back(a);
  }
  if (s.advice.empty()) s.advice.push_back({Advice::Kind::Complete});
  return s;
}

std::string Advice::text() const {
  const std::string p = std::to_string(percent) + "%";
  switch (kind) {
    case Kind::Coverage:
      return std::string("Cover the whole breast at ") + level_name(level) + " pressure: " + p + " of the skin was reached at that level.";
    case Kind::Strips:
      return "Search in vertical strips, head to foot, overlapping each by about a third of a finger pad: " + std::to_string(count) +
             " strips covered " + p + " of the path.";
    case Kind::Overlap: return "Overlap neighbouring strips: they left gaps between them.";
    case Kind::PressDeep:
      return "Press deep at every spot: a lump " + std::to_string(depth_mm) + " mm below the skin was missed where deep pressure was not reached.";
    case Kind::FalsePositives:
      return "Check a suspected lump at all three pressure levels before marking it: " + std::to_string(count) + " mark(s) found no lump.";
    case Kind::Complete: return "A complete examination: keep this pattern and pressure.";
  }
  return {};
}

namespace {
json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
}  // namespace

json to_json(const ExamScore& s) {
  json j;
  j["coverage"] = {{"total", s.touched}, {"light", s.coverage[0]}, {"medium", s.coverage[1]}, {"deep", s.coverage[2]}};
  json skipped = json::array();
  for (const auto& r : s.pattern.skipped) skipped.push_back({{"centre", vec(r.centre)}, {"area_cm2", r.area * 1e4}});
  j["pattern"] = {{"strips", s.pattern.strips},
                  {"vertical_fraction", s.pattern.vertical_fraction},
                  {"mean_overlap", s.pattern.mean_overlap},
                  {"path_length_m", s.pattern.path_length},
                  {"skipped_regions", skipped}};
  json ts = json::array();
  for (const auto& r : s.tumours) {
    json t = {{"centre", vec(r.truth.centre)},
              {"skin_point", vec(r.truth.skin_point)},
              {"lateral_radius_m", r.truth.lateral_radius},
              {"depth_m", r.truth.depth},
              {"young_pa", r.truth.young},
              {"contrast", r.truth.contrast},
              {"tolerance_m", r.truth.tolerance},
              {"hit", r.found},
              {"max_pressure_over", level_name(r.max_level_over)},
              {"deep_pressure_reached", r.deep_reached}};
    t["mark"] = r.found ? json(r.mark) : json();
    t["position_error_m"] = r.found ? json(r.error) : json();
    t["time_to_find_s"] = r.found ? json(r.time_to_find) : json();
    ts.push_back(t);
  }
  j["tumours"] = ts;
  json ms = json::array();
  for (std::size_t i = 0; i < s.marks.size(); ++i)
    ms.push_back({{"t", s.marks[i].t},
                  {"position", vec(s.marks[i].position)},
                  {"on_skin", vec(i < s.marks_on_skin.size() ? s.marks_on_skin[i] : s.marks[i].position)},
                  {"confidence", s.marks[i].confidence}});
  j["marks"] = ms;
  j["false_positive_marks"] = s.false_positive_marks;
  j["hits"] = s.hits;
  j["false_positives"] = s.false_positives;
  j["sensitivity"] = s.sensitivity ? json(*s.sensitivity) : json();
  j["ppv"] = s.ppv ? json(*s.ppv) : json();
  j["specific"] = s.specific ? json(*s.specific) : json();
  j["mean_error_m"] = s.mean_error;
  j["exam_time_s"] = s.exam_time;
  j["duration_s"] = s.duration;
  j["thresholds"] = to_json(s.thresholds);
  json advice = json::array();
  for (const Advice& a : s.advice) advice.push_back(a.text());
  j["advice"] = advice;
  return j;
}

std::vector<FingerSample> vertical_strip_exam(const SkinMap& skin, const PressureThresholds& t, const StripExamSpec& spec) {
  std::vector<FingerSample> out;
  if (skin.faces.empty() || !(spec.spacing > 0) || !(spec.step > 0) || !(spec.speed > 0)) return out;
  // The depth fraction that lands inside each level's band.
  auto fraction = [&](Level l) {
    switch (l) {
      case Level::Light: return 0.5 * (t.light_depth + t.medium_depth);
      case Level::Medium: return 0.5 * (t.medium_depth + t.deep_depth);
      default: return t.deep_depth + 0.05;
    }
  };
  const double x0 = std::max(spec.x_min, skin.lo.x()), x1 = std::min(spec.x_max, skin.hi.x());
  const double below = skin.lo.z() - 1e-3;
  double time = 0;
  bool up = true;
  for (double x = x0 + 0.5 * spec.spacing; x <= x1; x += spec.spacing)
    for (Level l : spec.levels) {
      for (double k = 0; ; k += 1) {
        const double y = up ? skin.lo.y() + k * spec.step : skin.hi.y() - k * spec.step;
        if (y < skin.lo.y() - 1e-12 || y > skin.hi.y() + 1e-12) break;
        const Eigen::Vector3d foot(x, y, below);
        const Eigen::Vector3d p = skin.skin_above(foot);
        if ((p - foot).head<2>().norm() > 1e-3) continue;  // no skin above this point
        const int f = skin.nearest_face(p);
        if (f < 0) continue;
        const double d = fraction(l) * skin.thickness[std::size_t(f)];
        out.push_back({time, spec.finger, p + skin.normal[std::size_t(f)] * (spec.radius - d), spec.radius, 0.0});
        time += spec.step / spec.speed;
      }
      up = !up;
      time += 0.3;  // lift and move to the next pass
    }
  return out;
}

}  // namespace palpation::app::train
