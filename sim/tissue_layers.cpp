#include "tissue_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include <Eigen/Geometry>

namespace palpation::sim {

namespace {

using V3 = Eigen::Vector3d;

/// Squared distance from p to the triangle abc (the closest-point regions of Ericson,
/// Real-Time Collision Detection 5.1.5). Written here: Eigen has no geometric queries and
/// the project takes no geometry library into sim/.
double distance2_to_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - ab * (d1 / (d1 - d3))).squaredNorm();
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - ac * (d2 / (d2 - d6))).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).squaredNorm();
  const double denom = 1.0 / (va + vb + vc);
  return (ap - ab * (vb * denom) - ac * (vc * denom)).squaredNorm();
}

/// Barycentric points that split a tetrahedron's volume evenly: a midpoint grid of n^3
/// points in the unit cube, each sorted (u1 <= u2 <= u3) and taken as the spacings
/// (u1, u2 - u1, u3 - u2, 1 - u3), which maps the cube onto the simplex with uniform density.
const std::vector<std::array<double, 4>>& volume_samples() {
  static const std::vector<std::array<double, 4>> pts = [] {
    constexpr int n = 6;
    std::vector<std::array<double, 4>> v;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          std::array<double, 3> u{(i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n};
          std::sort(u.begin(), u.end());
          v.push_back({u[0], u[1] - u[0], u[2] - u[1], 1.0 - u[2]});
        }
    return v;
  }();
  return pts;
}

int layer_index(const std::vector<TissueLayer>& layers, double d) {
  double top = 0;
  for (std::size_t i = 0; i + 1 < layers.size(); ++i) {
    top += layers[i].thickness;
    if (d < top) return int(i);
  }
  return int(layers.size()) - 1;
}

}  // namespace

std::vector<TissueLayer> breast_layers() {
  // Subcutaneous fat 1 cm at 19 kPa (the paper's tissue, Krouskop's fat at 5 %
  // precompression), glandular tissue below at 31.5 kPa (Krouskop's fibroglandular,
  // 28-35 kPa); resources/tissue_presets.json cites each figure. No skin band: at 1.5 mm it
  // is thinner than any element of the built-in meshes, and laid onto them it stiffened a
  // deep press by a third to a half and took the tumours' contrast away (docs/simulation.md,
  // "Tissue layers"); the skin is a membrane instead (apply_skin, tissue.skin).
  return {{"fat", 0.010, 19000.0}, {"glandular", 0.0, 31500.0}};
}

double layer_modulus(const std::vector<TissueLayer>& layers, double d) {
  return layers.empty() ? 0.0 : layers[std::size_t(layer_index(layers, d))].young_modulus;
}

namespace {
// A boundary face that is not all on the chest wall (fixed).
bool is_skin_face(const Model& m, int f) {
  const auto& t = m.surface[std::size_t(f)];
  return !(m.fixed[std::size_t(t[0])] && m.fixed[std::size_t(t[1])] && m.fixed[std::size_t(t[2])]);
}
}  // namespace

std::vector<double> skin_depths(const Model& m, double max_depth) {
  const int nn = m.num_nodes();
  std::vector<double> depth(std::size_t(nn), max_depth);
  // Skin triangles in a uniform grid of cells max_depth wide (each in every cell its
  // bounding box touches): a triangle within max_depth of a node touches the node's cell or
  // one of its 26 neighbours.
  const double cell = std::max(max_depth, 1e-6);
  auto key = [](long long x, long long y, long long z) { return (x * 73856093LL) ^ (y * 19349663LL) ^ (z * 83492791LL); };
  auto cell_of = [&](double v) { return static_cast<long long>(std::floor(v / cell)); };
  std::unordered_map<long long, std::vector<int>> grid;
  std::vector<int> skin;
  for (int f = 0; f < int(m.surface.size()); ++f) {
    if (!is_skin_face(m, f)) continue;
    const auto& t = m.surface[std::size_t(f)];
    skin.push_back(f);
    V3 lo = m.rest[std::size_t(t[0])], hi = lo;
    for (int a = 1; a < 3; ++a) {
      lo = lo.cwiseMin(m.rest[std::size_t(t[a])]);
      hi = hi.cwiseMax(m.rest[std::size_t(t[a])]);
    }
    for (long long x = cell_of(lo.x()); x <= cell_of(hi.x()); ++x)
      for (long long y = cell_of(lo.y()); y <= cell_of(hi.y()); ++y)
        for (long long z = cell_of(lo.z()); z <= cell_of(hi.z()); ++z) grid[key(x, y, z)].push_back(f);
  }
  if (skin.empty()) return depth;
  for (int v = 0; v < nn; ++v) {
    const V3& p = m.rest[std::size_t(v)];
    const long long cx = cell_of(p.x()), cy = cell_of(p.y()), cz = cell_of(p.z());
    double best = max_depth * max_depth;
    for (long long x = cx - 1; x <= cx + 1; ++x)
      for (long long y = cy - 1; y <= cy + 1; ++y)
        for (long long z = cz - 1; z <= cz + 1; ++z) {
          const auto it = grid.find(key(x, y, z));
          if (it == grid.end()) continue;
          for (int f : it->second) {  // a hash collision only adds candidates
            const auto& t = m.surface[std::size_t(f)];
            best = std::min(best, distance2_to_triangle(p, m.rest[std::size_t(t[0])], m.rest[std::size_t(t[1])],
                                                        m.rest[std::size_t(t[2])]));
          }
        }
    depth[std::size_t(v)] = std::min(std::sqrt(best), max_depth);
  }
  return depth;
}

std::vector<int> apply_layers(Model& m, const std::vector<TissueLayer>& layers) {
  std::vector<int> count(layers.size(), 0);
  if (layers.empty()) return count;
  double banded = 0;  // depth of the last layer's top
  for (std::size_t i = 0; i + 1 < layers.size(); ++i) banded += layers[i].thickness;
  // The search reaches the banded depth plus the longest edge: the depth changes by at most
  // an edge's length along it, so every node of an element that reaches into the bands gets
  // its exact depth, and an element with a node beyond the reach lies wholly in the core.
  double edge2 = 0;
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        edge2 = std::max(edge2, (m.rest[std::size_t(t[std::size_t(a)])] - m.rest[std::size_t(t[std::size_t(b)])]).squaredNorm());
  const std::vector<double> depth = skin_depths(m, banded + std::sqrt(edge2));
  const double nu = m.tissue.poisson_ratio;
  const auto& samples = volume_samples();
  m.tissue_young.resize(std::size_t(m.num_tets()));
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[std::size_t(e)];
    std::array<double, 4> d{};
    for (int a = 0; a < 4; ++a) d[std::size_t(a)] = depth[std::size_t(t[std::size_t(a)])];
    const double centroid = 0.25 * (d[0] + d[1] + d[2] + d[3]);
    ++count[std::size_t(layer_index(layers, centroid))];
    const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
    double E = 0;
    if (layer_index(layers, *lo) == layer_index(layers, *hi)) {
      E = layer_modulus(layers, *lo);
    } else {
      double compliance = 0;  // bands in series: their compliances add (tissue_layers.h)
      for (const auto& w : samples)
        compliance += 1.0 / layer_modulus(layers, w[0] * d[0] + w[1] * d[1] + w[2] * d[2] + w[3] * d[3]);
      E = double(samples.size()) / compliance;
    }
    m.tissue_young[std::size_t(e)] = E;
    m.set_element_material(e, E, nu);
  }
  return count;
}

void apply_skin(Model& m, const SkinSpec& spec) {
  SkinMembrane& k = m.skin;
  k = SkinMembrane{};
  if (!spec.present()) return;
  k.spec = spec;
  k.poisson_ratio = m.tissue.poisson_ratio;
  for (int f = 0; f < int(m.surface.size()); ++f) {
    if (!is_skin_face(m, f)) continue;
    const auto& t = m.surface[std::size_t(f)];
    const V3 X[3] = {m.rest[std::size_t(t[0])], m.rest[std::size_t(t[1])], m.rest[std::size_t(t[2])]};
    const V3 N = (X[1] - X[0]).cross(X[2] - X[0]);
    const double twice_area = N.norm();
    if (!(twice_area > 0)) continue;  // a degenerate face carries no membrane
    const V3 n0 = N / twice_area;
    membrane::Rest<double> r{};
    // g_a = n0 x (edge opposite a, walked counter-clockwise) / 2A: grad of the barycentric
    // coordinate of node a in the plane.
    for (int a = 0; a < 3; ++a) {
      const V3 g = n0.cross(X[(a + 2) % 3] - X[(a + 1) % 3]) / twice_area;
      for (int c = 0; c < 3; ++c) r.g[3 * a + c] = g[c];
    }
    const V3 e1 = (X[1] - X[0]).normalized();
    for (int c = 0; c < 3; ++c) {
      r.n0[c] = n0[c];
      r.e1[c] = e1[c];
    }
    r.at = 0.5 * twice_area * spec.thickness;
    std::array<int, 9> blocks{};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) blocks[std::size_t(3 * a + b)] = m.block_of(m.dof[std::size_t(t[a])], m.dof[std::size_t(t[b])]);
    k.triangles.push_back(t);
    k.rest.push_back(r);
    k.block.push_back(blocks);
  }
}

}  // namespace palpation::sim
