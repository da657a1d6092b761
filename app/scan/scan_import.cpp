#include "scan/scan_import.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include <Eigen/Geometry>

#include "mesh_gmsh.h"

namespace palpation::app::scan {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string plural(int n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

double diag(const SurfaceMesh& s) {
  if (s.vertices.empty()) return 0;
  Eigen::Vector3d lo = s.vertices[0], hi = s.vertices[0];
  for (const auto& v : s.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

Eigen::Vector3d tri_normal(const SurfaceMesh& s, const std::array<int, 3>& t) {  // area-weighted (2x area)
  const auto& a = s.vertices[std::size_t(t[0])];
  return (s.vertices[std::size_t(t[1])] - a).cross(s.vertices[std::size_t(t[2])] - a);
}

double signed_volume(const SurfaceMesh& s) {
  double v = 0;
  for (const auto& t : s.triangles)
    v += s.vertices[std::size_t(t[0])].dot(s.vertices[std::size_t(t[1])].cross(s.vertices[std::size_t(t[2])]));
  return v / 6.0;
}

}  // namespace

std::string SurfaceReport::problems() const {
  std::vector<std::string> p;
  if (triangles == 0) p.push_back("no triangles");
  if (open_edges) p.push_back(plural(open_edges, "open edge") + " (holes: the surface is not closed)");
  if (nonmanifold_edges) p.push_back(plural(nonmanifold_edges, "non-manifold edge") + " (shared by more than two triangles)");
  if (triangles && components != 1) p.push_back(std::to_string(components) + " separate pieces (must be one closed surface)");
  if (triangles && open_edges == 0 && nonmanifold_edges == 0 && !(volume > 0)) p.push_back("encloses no volume");
  std::string s;
  for (const auto& x : p) s += (s.empty() ? "" : "; ") + x;
  return s;
}

std::string SurfaceReport::repairs() const {
  std::ostringstream o;
  o << "merged " << merged_vertices << " duplicate vertices, dropped " << degenerate_dropped << " degenerate and "
    << duplicate_dropped << " duplicate triangles, flipped " << flipped << " triangles" << (inverted ? ", turned the surface outward" : "");
  return o.str();
}

SurfaceReport repair_surface(SurfaceMesh& s) {
  SurfaceReport r;
  const double d = diag(s);
  // 1) Merge duplicate vertices (quantised to 1e-9 of the size).
  {
    const double q = std::max(d * 1e-9, 1e-300);
    std::map<std::array<long long, 3>, int> seen;
    std::vector<int> remap(s.vertices.size());
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
      const auto& v = s.vertices[i];
      const std::array<long long, 3> k{std::llround(v.x() / q), std::llround(v.y() / q), std::llround(v.z() / q)};
      auto [it, fresh] = seen.try_emplace(k, int(kept.size()));
      if (fresh) kept.push_back(v);
      else ++r.merged_vertices;
      remap[i] = it->second;
    }
    for (auto& t : s.triangles)
      for (int& k : t) k = remap[std::size_t(k)];
    s.vertices = std::move(kept);
  }
  // 2) Drop degenerate and duplicate triangles.
  {
    std::vector<std::array<int, 3>> kept;
    std::map<std::array<int, 3>, int> seen;
    const double min_area2 = std::pow(d * 1e-7, 4);
    for (const auto& t : s.triangles) {
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || tri_normal(s, t).squaredNorm() <= min_area2) {
        ++r.degenerate_dropped;
        continue;
      }
      std::array<int, 3> key = t;
      std::sort(key.begin(), key.end());
      if (!seen.emplace(key, 1).second) {
        ++r.duplicate_dropped;
        continue;
      }
      kept.push_back(t);
    }
    s.triangles = std::move(kept);
  }
  r.triangles = int(s.triangles.size());
  // Unused vertices out.
  {
    std::vector<int> remap(s.vertices.size(), -1);
    std::vector<Eigen::Vector3d> kept;
    for (auto& t : s.triangles)
      for (int& k : t) {
        if (remap[std::size_t(k)] < 0) {
          remap[std::size_t(k)] = int(kept.size());
          kept.push_back(s.vertices[std::size_t(k)]);
        }
        k = remap[std::size_t(k)];
      }
    s.vertices = std::move(kept);
  }
  r.vertices = int(s.vertices.size());
  if (s.triangles.empty()) return r;
  // 3) Edges: open, non-manifold.
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  edges.reserve(s.triangles.size() * 2);
  for (int i = 0; i < int(s.triangles.size()); ++i)
    for (int e = 0; e < 3; ++e) edges[edge_key(s.triangles[std::size_t(i)][std::size_t(e)], s.triangles[std::size_t(i)][std::size_t((e + 1) % 3)])].push_back(i);
  for (const auto& [k, ts] : edges) {
    if (ts.size() == 1) ++r.open_edges;
    if (ts.size() > 2) ++r.nonmanifold_edges;
  }
  // 4) Components and consistent orientation (breadth first over manifold edges).
  std::vector<int> comp(s.triangles.size(), -1);
  auto has_directed = [&](int ti, int a, int b) {
    const auto& t = s.triangles[std::size_t(ti)];
    for (int e = 0; e < 3; ++e)
      if (t[std::size_t(e)] == a && t[std::size_t((e + 1) % 3)] == b) return true;
    return false;
  };
  bool orientable = true;
  for (int seed = 0; seed < int(s.triangles.size()); ++seed) {
    if (comp[std::size_t(seed)] >= 0) continue;
    const int c = r.components++;
    std::deque<int> queue{seed};
    comp[std::size_t(seed)] = c;
    while (!queue.empty()) {
      const int ti = queue.front();
      queue.pop_front();
      for (int e = 0; e < 3; ++e) {
        const int a = s.triangles[std::size_t(ti)][std::size_t(e)], b = s.triangles[std::size_t(ti)][std::size_t((e + 1) % 3)];
        const auto& ts = edges[edge_key(a, b)];
        if (ts.size() != 2) continue;
        const int nb = ts[0] == ti ? ts[1] : ts[0];
        // A consistent neighbour runs the shared edge the other way (b -> a).
        const bool consistent = has_directed(nb, b, a);
        if (comp[std::size_t(nb)] < 0) {
          if (!consistent) {
            auto& t = s.triangles[std::size_t(nb)];
            std::swap(t[1], t[2]);
            ++r.flipped;
          }
          comp[std::size_t(nb)] = c;
          queue.push_back(nb);
        } else if (!consistent) {
          orientable = false;
        }
      }
    }
  }
  r.volume = signed_volume(s);
  if (r.open_edges == 0 && r.nonmanifold_edges == 0 && r.volume < 0) {
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
    r.inverted = true;
    r.volume = -r.volume;
  }
  if (!orientable) r.volume = 0;  // "encloses no volume" (a Klein-bottle-like surface)
  return r;
}

BasePlane find_base_plane(const SurfaceMesh& s) {
  const std::size_t n = s.triangles.size();
  const double tol = 0.005 * diag(s);
  const double cos_tol = std::cos(5.0 * kPi / 180.0);
  std::vector<Eigen::Vector3d> nrm(n);
  std::vector<double> area(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d v = tri_normal(s, s.triangles[i]);
    area[i] = 0.5 * v.norm();
    nrm[i] = area[i] > 0 ? Eigen::Vector3d(v.normalized()) : Eigen::Vector3d::Zero();
  }
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  for (int i = 0; i < int(n); ++i)
    for (int e = 0; e < 3; ++e) edges[edge_key(s.triangles[std::size_t(i)][std::size_t(e)], s.triangles[std::size_t(i)][std::size_t((e + 1) % 3)])].push_back(i);
  std::vector<char> used(n, 0);
  BasePlane best;
  best.area = -1;
  // Seeds in order of decreasing area: big flat triangles first.
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return area[std::size_t(a)] > area[std::size_t(b)]; });
  for (int seed : order) {
    if (used[std::size_t(seed)] || area[std::size_t(seed)] <= 0) continue;
    const Eigen::Vector3d n0 = nrm[std::size_t(seed)];
    const double d0 = n0.dot(s.vertices[std::size_t(s.triangles[std::size_t(seed)][0])]);
    double a_sum = 0;
    Eigen::Vector3d n_sum = Eigen::Vector3d::Zero(), c_sum = Eigen::Vector3d::Zero();
    std::deque<int> queue{seed};
    used[std::size_t(seed)] = 1;
    while (!queue.empty()) {
      const int ti = queue.front();
      queue.pop_front();
      const auto& t = s.triangles[std::size_t(ti)];
      const Eigen::Vector3d c = (s.vertices[std::size_t(t[0])] + s.vertices[std::size_t(t[1])] + s.vertices[std::size_t(t[2])]) / 3.0;
      a_sum += area[std::size_t(ti)];
      n_sum += area[std::size_t(ti)] * nrm[std::size_t(ti)];
      c_sum += area[std::size_t(ti)] * c;
      for (int e = 0; e < 3; ++e)
        for (int nb : edges[edge_key(t[std::size_t(e)], t[std::size_t((e + 1) % 3)])]) {
          if (used[std::size_t(nb)] || nrm[std::size_t(nb)].dot(n0) < cos_tol) continue;
          bool on = true;
          for (int k : s.triangles[std::size_t(nb)]) on = on && std::abs(n0.dot(s.vertices[std::size_t(k)]) - d0) <= tol;
          if (!on) continue;
          used[std::size_t(nb)] = 1;
          queue.push_back(nb);
        }
    }
    if (a_sum > best.area) {
      best.area = a_sum;
      best.normal = n_sum.normalized();
      best.offset = best.normal.dot(c_sum / a_sum);
    }
  }
  best.automatic = true;
  return best;
}

double BasePlane::tilt_deg() const {
  const double c = normal.norm() > 0 ? -normal.normalized().z() : 1.0;
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi;
}

double projected_footprint(const SurfaceMesh& s, const Eigen::Vector3d& normal) {
  if (s.vertices.empty() || !(normal.norm() > 0)) return 0;
  // Two axes in the plane; every vertex projected onto them.
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  std::vector<Eigen::Vector2d> p(s.vertices.size());
  Eigen::Vector2d lo(HUGE_VAL, HUGE_VAL), hi(-HUGE_VAL, -HUGE_VAL);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = Eigen::Vector2d(u.dot(s.vertices[i]), v.dot(s.vertices[i]));
    lo = lo.cwiseMin(p[i]);
    hi = hi.cwiseMax(p[i]);
  }
  // The union of the projected triangles on a grid of square cells (a cell counts when its
  // centre lies in a triangle): overlapping layers of the surface count once.
  constexpr int kCells = 512;
  const double cell = std::max(hi.x() - lo.x(), hi.y() - lo.y()) / kCells;
  if (!(cell > 0)) return 0;
  const int nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / cell))), ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / cell)));
  std::vector<char> covered(std::size_t(nx) * std::size_t(ny), 0);
  for (const auto& t : s.triangles) {
    const Eigen::Vector2d &a = p[std::size_t(t[0])], &b = p[std::size_t(t[1])], &c = p[std::size_t(t[2])];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) <= 0) continue;  // edge-on: its neighbours cover its outline
    const Eigen::Vector2d tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
    const int i0 = std::max(0, int(std::floor((tlo.x() - lo.x()) / cell - 0.5))), i1 = std::min(nx - 1, int(std::ceil((thi.x() - lo.x()) / cell - 0.5)));
    const int j0 = std::max(0, int(std::floor((tlo.y() - lo.y()) / cell - 0.5))), j1 = std::min(ny - 1, int(std::ceil((thi.y() - lo.y()) / cell - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Eigen::Vector2d q(lo.x() + (i + 0.5) * cell, lo.y() + (j + 0.5) * cell);
        const double l1 = ((q.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (q.y() - a.y())) / det;
        const double l2 = ((b.x() - a.x()) * (q.y() - a.y()) - (q.x() - a.x()) * (b.y() - a.y())) / det;
        if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) covered[std::size_t(j) * std::size_t(nx) + std::size_t(i)] = 1;
      }
  }
  std::size_t n_cov = 0;
  for (char x : covered) n_cov += std::size_t(x);
  return double(n_cov) * cell * cell;
}

ImportResult import_scan(const std::string& path, const ImportOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  auto step = [&](double f, const std::string& stage) {
    if (opt.progress && !opt.progress(f, stage)) throw std::runtime_error("cancelled");
  };
  if (!(opt.edge >= 5e-4 && opt.edge <= 0.05)) throw ImportError("--resolution: edge length must be in [0.0005, 0.05] m");
  if (!(opt.scale > 0) || !std::isfinite(opt.scale)) throw ImportError("--scale: must be > 0");
  ImportResult res;
  step(0.0, "reading");
  // The reader's child is polled for a cancel (the GUI's Cancel stops it at once).
  std::function<bool()> reading_cancelled;
  if (opt.progress) reading_cancelled = [&]() { return !opt.progress(0.0, "reading"); };
  SurfaceMesh s = read_surface(path, reading_cancelled);
  for (auto& v : s.vertices) v *= opt.scale;
  step(0.1, "checking and repairing");
  res.report = repair_surface(s);
  if (!res.report.ok()) throw ImportError(path + ": " + res.report.problems() + " (after repair: " + res.report.repairs() + ")");
  const double size = diag(s);
  if (size < 0.02 || size > 1.0) {
    std::ostringstream o;
    o.precision(3);
    o << path << ": the surface is " << size << " m across (expected 0.02 to 1 m): give its units with --scale "
      << "(0.001 for millimetres)";
    throw ImportError(o.str());
  }
  step(0.2, "finding the chest-wall base plane");
  BasePlane base = opt.base ? *opt.base : find_base_plane(s);
  base.normal.normalize();
  {
    // The surface lying on the plane, and the body on its inner side.
    const double tol = 0.005 * size;
    double on = 0, below = 0;
    for (const auto& t : s.triangles) {
      bool all_on = true;
      for (int k : t) all_on = all_on && std::abs(base.normal.dot(s.vertices[std::size_t(k)]) - base.offset) <= tol;
      if (all_on) on += 0.5 * tri_normal(s, t).norm();
    }
    for (const auto& v : s.vertices) below = std::max(below, base.normal.dot(v) - base.offset);
    base.area = on;  // a given plane too: what it touches
    if (on <= 0) throw ImportError(path + ": base plane: no part of the surface lies on it (give a plane through a flat face)");
    if (below > tol) {
      std::ostringstream o;
      o.precision(3);
      o << path << ": base plane: the surface reaches " << below * 1000 << " mm beyond it into the chest (not a cut at the chest wall)";
      throw ImportError(o.str());
    }
    // A chest wall carries the body: a base that is a small part of the body's outline on
    // its plane is a flat patch of a closed body (a sphere's facet), not a cut at the chest.
    base.footprint = projected_footprint(s, base.normal);
    if (base.footprint_fraction() < kMinBaseFootprintFraction) {
      char buf[640];
      if (opt.base)
        std::snprintf(buf, sizeof buf,
                      "no chest wall: the plane given touches %.1f cm^2 of the surface, %.1f %% of the body's outline on "
                      "it (a chest wall needs at least %.0f %%); give the plane of the scan's flat cut at the chest wall "
                      "(--base-plane nx,ny,nz,d: n out of the body into the chest, d in m)",
                      base.area * 1e4, 100.0 * base.footprint_fraction(), 100.0 * kMinBaseFootprintFraction);
      else
        std::snprintf(buf, sizeof buf,
                      "no chest wall: the largest flat region is %.1f cm^2 (tilted %.0f degrees from the scan's z axis), "
                      "%.1f %% of the body's outline on its plane (a chest wall needs at least %.0f %%): the scan must be cut "
                      "flat at the chest wall. Cut it there in a mesh editor, or, if it has a flat base that was not found "
                      "whole (a rough cut), give that plane with --base-plane nx,ny,nz,d (n out of the body into the chest, "
                      "d in m)",
                      base.area * 1e4, base.tilt_deg(), 100.0 * base.footprint_fraction(),
                      100.0 * kMinBaseFootprintFraction);
      throw ImportError(path + ": " + buf);
    }
  }
  res.base = base;
  // Rotate the base normal onto -z, the plane onto z = 0.
  const Eigen::Quaterniond rot = Eigen::Quaterniond::FromTwoVectors(base.normal, -Eigen::Vector3d::UnitZ());
  for (auto& v : s.vertices) {
    v = rot * v;
    v.z() += base.offset;  // n.x = offset  ->  -z = offset  ->  z + offset = 0
  }
  step(0.3, "tetrahedralising (Gmsh)");
  const auto tm = std::chrono::steady_clock::now();
  std::function<bool()> cancelled;
  if (opt.progress)
    cancelled = [&]() {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - tm).count();
      return !opt.progress(0.3 + 0.6 * (1.0 - std::exp(-el / 5.0)), "tetrahedralising (Gmsh)");
    };
  try {
    res.mesh = sim::gmsh_tetrahedralize(s.vertices, s.triangles, opt.edge, opt.timeout_s, cancelled);
  } catch (const std::runtime_error& e) {
    const std::string w = e.what();
    if (w.find("cancelled") != std::string::npos) throw std::runtime_error("cancelled");
    throw std::runtime_error(path + ": tetrahedralising failed: " + w);
  }
  res.mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tm).count();
  const double snap = 1e-6 * size;
  for (auto& p : res.mesh.nodes)
    if (std::abs(p.z()) < snap) p.z() = 0.0;
  if (std::string v = res.mesh.validate(); !v.empty()) throw std::runtime_error(path + ": the tetrahedral mesh is invalid: " + v);
  step(1.0, "done");
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

void write_test_dome(const std::string& path, double a, double h, bool drop_base, bool extra, bool rotate_x_90) {
  const int nr = 6, nu = 16;  // rings, segments
  std::vector<Eigen::Vector3d> v;
  std::vector<std::array<int, 3>> t;
  v.emplace_back(0, 0, h);  // apex 0
  for (int i = 1; i <= nr; ++i) {
    const double th = 0.5 * kPi * i / nr;
    for (int j = 0; j < nu; ++j) {
      const double ph = 2 * kPi * j / nu;
      v.emplace_back(a * std::sin(th) * std::cos(ph), a * std::sin(th) * std::sin(ph), h * std::cos(th));
    }
  }
  auto ring = [&](int i, int j) { return 1 + (i - 1) * nu + ((j % nu) + nu) % nu; };
  for (int j = 0; j < nu; ++j) t.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < nr; ++i)
    for (int j = 0; j < nu; ++j) {
      t.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      t.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  if (!drop_base) {
    const int c = int(v.size());
    v.emplace_back(0, 0, 0);
    for (int j = 0; j < nu; ++j) t.push_back({c, ring(nr, j + 1), ring(nr, j)});
  }
  if (extra) {
    v.emplace_back(0, 0, -0.01);
    t.push_back({ring(nr, 0), ring(nr, 1), int(v.size()) - 1});
  }
  if (rotate_x_90)
    for (auto& p : v) p = Eigen::Vector3d(p.x(), -p.z(), p.y());  // base normal -z -> +y
  const std::string ext = std::filesystem::path(path).extension().string();
  std::ofstream o(path);
  o.precision(9);
  if (ext == ".stl") {
    o << "solid dome\n";
    for (const auto& f : t) {
      o << " facet normal 0 0 0\n  outer loop\n";
      for (int k : f) o << "   vertex " << v[std::size_t(k)].x() << ' ' << v[std::size_t(k)].y() << ' ' << v[std::size_t(k)].z() << "\n";
      o << "  endloop\n endfacet\n";
    }
    o << "endsolid dome\n";
  } else if (ext == ".obj") {
    for (const auto& p : v) o << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
    for (const auto& f : t) o << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << "\n";
  } else if (ext == ".ply") {
    o << "ply\nformat ascii 1.0\nelement vertex " << v.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face " << t.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : v) o << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
    for (const auto& f : t) o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << "\n";
  } else {
    throw std::invalid_argument(path + ": extension must be .stl, .obj or .ply");
  }
}

}  // namespace palpation::app::scan
