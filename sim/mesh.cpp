#include "mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>

namespace palpation::sim {

double ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-18) return -1;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) * inv;
  if (u < -1e-9 || u > 1 + 1e-9) return -1;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < -1e-9 || u + v > 1 + 1e-9) return -1;
  return e2.dot(q) * inv;
}

double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

int TetMesh::orient() {
  int flipped = 0;
  for (auto& t : tets) {
    if (tet_volume(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]) < 0) {
      std::swap(t[2], t[3]);
      ++flipped;
    }
  }
  return flipped;
}

std::string TetMesh::validate() const {
  std::ostringstream why;
  if (nodes.empty()) return "mesh has no nodes";
  if (tets.empty()) return "mesh has no tetrahedra";
  if (!region.empty() && region.size() != tets.size()) return "region tags do not match tetrahedra";
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].allFinite()) {
      why << "node " << i << " has a non-finite coordinate";
      return why.str();
    }
  }
  const int n = num_nodes();
  for (std::size_t e = 0; e < tets.size(); ++e) {
    const auto& t = tets[e];
    for (int k = 0; k < 4; ++k) {
      if (t[k] < 0 || t[k] >= n) {
        why << "tetrahedron " << e << " refers to node " << t[k] << " of " << n;
        return why.str();
      }
    }
    const double v = std::abs(tet_volume(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]));
    if (!(v > 0)) {
      why << "tetrahedron " << e << " is degenerate (zero volume)";
      return why.str();
    }
  }
  return {};
}

std::vector<std::array<int, 3>> TetMesh::boundary_faces() const {
  // Faces of a positively oriented tet (a,b,c,d), outward normals.
  static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> seen;
  for (const auto& t : tets) {
    const bool pos = tet_volume(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]) > 0;
    for (const auto& f : kFace) {
      std::array<int, 3> tri{t[f[0]], t[f[1]], t[f[2]]};
      if (!pos) std::swap(tri[1], tri[2]);
      std::array<int, 3> key = tri;
      std::sort(key.begin(), key.end());
      auto it = seen.find(key);
      if (it == seen.end())
        seen.emplace(key, std::make_pair(1, tri));
      else
        ++it->second.first;
    }
  }
  std::vector<std::array<int, 3>> out;
  for (const auto& [key, v] : seen)
    if (v.first == 1) out.push_back(v.second);
  return out;
}

void TetMesh::bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
  lo = Eigen::Vector3d::Constant(1e300);
  hi = Eigen::Vector3d::Constant(-1e300);
  for (const auto& p : nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

// Written here rather than taken from a library: Gmsh 4.8 has no renumbering (and boxes
// and imported meshes never pass through it), Eigen's orderings reduce fill, not
// bandwidth, and the search itself is a breadth-first walk.
std::vector<int> TetMesh::order_for_locality() {
  const int n = num_nodes();
  std::vector<int> by(tets.size());
  std::iota(by.begin(), by.end(), 0);
  if (n == 0) return by;
  const auto N = static_cast<std::size_t>(n);
  // Node adjacency over the tetrahedra's edges, CSR, each list sorted and unique.
  std::vector<int> ptr(N + 1, 0), adj;
  {
    std::vector<std::vector<int>> nb(N);
    for (const auto& t : tets)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (a != b) nb[std::size_t(t[a])].push_back(t[b]);
    for (int i = 0; i < n; ++i) {
      auto& l = nb[std::size_t(i)];
      std::sort(l.begin(), l.end());
      l.erase(std::unique(l.begin(), l.end()), l.end());
      ptr[std::size_t(i) + 1] = ptr[std::size_t(i)] + int(l.size());
    }
    adj.reserve(std::size_t(ptr[N]));
    for (const auto& l : nb) adj.insert(adj.end(), l.begin(), l.end());
  }
  auto degree = [&](int i) { return ptr[std::size_t(i) + 1] - ptr[std::size_t(i)]; };
  std::vector<int> order;  // Cuthill-McKee order, reversed at the end
  order.reserve(N);
  std::vector<int> level(N, -1), stamp(N, -1);
  // Breadth-first levels from s over its piece of the mesh (stamp marks this walk; the
  // pieces already ordered are not reachable from it); returns the last level's node of
  // least degree.
  int walk = 0;
  auto far_end = [&](int s) {
    ++walk;
    std::vector<int> queue{s};
    stamp[std::size_t(s)] = walk;
    level[std::size_t(s)] = 0;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int u = queue[q];
      for (int k = ptr[std::size_t(u)]; k < ptr[std::size_t(u) + 1]; ++k) {
        const int w = adj[std::size_t(k)];
        if (stamp[std::size_t(w)] == walk) continue;
        stamp[std::size_t(w)] = walk;
        level[std::size_t(w)] = level[std::size_t(u)] + 1;
        queue.push_back(w);
      }
    }
    const int last = level[std::size_t(queue.back())];
    int best = queue.back();
    for (auto it = queue.rbegin(); it != queue.rend() && level[std::size_t(*it)] == last; ++it)
      if (degree(*it) < degree(best)) best = *it;
    return std::pair{best, last};
  };
  for (int seed = 0; seed < n; ++seed) {
    if (stamp[std::size_t(seed)] == -2) continue;
    // A pseudo-peripheral start (George and Liu): walk to the far end until the depth
    // stops growing; a start at the mesh's edge keeps the levels, and so the bandwidth,
    // narrow.
    int start = seed;
    auto [end, depth] = far_end(start);
    for (int tries = 0; tries < 4; ++tries) {
      auto [end2, depth2] = far_end(end);
      if (depth2 <= depth) break;
      start = end;
      end = end2;
      depth = depth2;
    }
    // Cuthill-McKee from it: each node's unnumbered neighbours by ascending degree.
    const std::size_t first = order.size();
    order.push_back(start);
    stamp[std::size_t(start)] = -2;
    std::vector<int> next;
    for (std::size_t q = first; q < order.size(); ++q) {
      const int u = order[q];
      next.clear();
      for (int k = ptr[std::size_t(u)]; k < ptr[std::size_t(u) + 1]; ++k) {
        const int w = adj[std::size_t(k)];
        if (stamp[std::size_t(w)] == -2) continue;
        stamp[std::size_t(w)] = -2;
        next.push_back(w);
      }
      std::stable_sort(next.begin(), next.end(), [&](int a, int b) { return degree(a) < degree(b); });
      order.insert(order.end(), next.begin(), next.end());
    }
  }
  std::reverse(order.begin(), order.end());
  std::vector<int> renum(N);
  std::vector<Eigen::Vector3d> moved(N);
  for (int k = 0; k < n; ++k) {
    renum[std::size_t(order[std::size_t(k)])] = k;
    moved[std::size_t(k)] = nodes[std::size_t(order[std::size_t(k)])];
  }
  nodes = std::move(moved);
  for (auto& t : tets)
    for (int& v : t) v = renum[std::size_t(v)];
  std::vector<int> low(tets.size());
  for (std::size_t e = 0; e < tets.size(); ++e) low[e] = *std::min_element(tets[e].begin(), tets[e].end());
  std::stable_sort(by.begin(), by.end(), [&](int a, int b) { return low[std::size_t(a)] < low[std::size_t(b)]; });
  std::vector<std::array<int, 4>> sorted(tets.size());
  std::vector<int> sorted_region(region.size());
  for (std::size_t k = 0; k < by.size(); ++k) {
    sorted[k] = tets[std::size_t(by[k])];
    if (!region.empty()) sorted_region[k] = region[std::size_t(by[k])];
  }
  tets = std::move(sorted);
  region = std::move(sorted_region);
  return by;
}

std::uint64_t TetMesh::hash() const {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  };
  mix(nodes.data(), nodes.size() * sizeof(Eigen::Vector3d));
  mix(tets.data(), tets.size() * sizeof(tets[0]));
  mix(region.data(), region.size() * sizeof(int));
  return h;
}

TetMesh make_box_mesh(const Eigen::Vector3d& size, int nx, int ny, int nz) {
  TetMesh m;
  nx = std::max(nx, 1);
  ny = std::max(ny, 1);
  nz = std::max(nz, 1);
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  m.nodes.reserve(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.nodes.emplace_back(size.x() * (double(i) / nx - 0.5), size.y() * (double(j) / ny - 0.5),
                             size.z() * double(k) / nz);
  // Kuhn subdivision of each cube into 6 tets along the main diagonal (0 -> 7): all
  // cubes use the same pattern, so shared faces are split the same way (conforming).
  static const int kPaths[6][3] = {{1, 3, 7}, {1, 5, 7}, {2, 3, 7}, {2, 6, 7}, {4, 5, 7}, {4, 6, 7}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int c[8];
        for (int b = 0; b < 8; ++b) c[b] = id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
        for (const auto& p : kPaths) m.tets.push_back({c[0], c[p[0]], c[p[1]], c[7]});
      }
  m.region.assign(m.tets.size(), 0);
  m.orient();
  return m;
}

void grade_box_mesh(TetMesh& mesh, const Eigen::Vector3d& size, double grading) {
  if (grading == 1.0) return;
  for (auto& p : mesh.nodes) {
    for (int k = 0; k < 2; ++k) {
      const double u = p[k] / (0.5 * size[k]);
      p[k] = 0.5 * size[k] * std::copysign(std::pow(std::abs(u), grading), u);
    }
    const double w = p.z() / size.z();
    p.z() = size.z() * (1.0 - std::pow(1.0 - w, grading));
  }
}

TetMesh make_box_mesh(const Eigen::Vector3d& size, double edge, double grading) {
  auto cells = [edge](double s) { return std::max(1, static_cast<int>(std::lround(s / edge))); };
  TetMesh m = make_box_mesh(size, cells(size.x()), cells(size.y()), cells(size.z()));
  grade_box_mesh(m, size, grading);
  return m;
}

}  // namespace palpation::sim
