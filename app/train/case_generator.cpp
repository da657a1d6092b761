#include "train/case_generator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "json_reader.h"
#include "phantom.h"
#include "tissue_layers.h"

namespace palpation::app::train {

using nlohmann::json;

namespace {

// Lengths are drawn in units of 0.1 mm, radii and centres kept in micrometres (integers).
constexpr double kUnit = 1e-4;      // m per drawing unit
constexpr double kMicron = 1e-6;    // m
constexpr double kBreastAxisX = 0.125;  // m, sim::BreastShape::center_x

// An integer in [lo, hi], uniform, from the generator's raw 64-bit output: the bucket
// method (rejecting the top partial bucket), the same on every standard library.
std::int64_t draw(std::mt19937_64& g, std::int64_t lo, std::int64_t hi) {
  const std::uint64_t n = static_cast<std::uint64_t>(hi - lo) + 1;
  if (n == 0) return lo + static_cast<std::int64_t>(g());  // the whole 64-bit range
  const std::uint64_t bucket = std::numeric_limits<std::uint64_t>::max() / n;
  std::uint64_t x;
  do x = g() / bucket;
  while (x >= n);
  return lo + static_cast<std::int64_t>(x);
}

// [min, max] in m as whole drawing units inside it.
std::int64_t units_up(double v, double unit) { return static_cast<std::int64_t>(std::ceil(v / unit - 1e-9)); }
std::int64_t units_down(double v, double unit) { return static_cast<std::int64_t>(std::floor(v / unit + 1e-9)); }

// Distance from (y0, y1), both >= 0, to the ellipse (x0/e0)^2 + (x1/e1)^2 = 1 with
// e0 >= e1 > 0 (Eberly, "Distance from a point to an ellipse, an ellipsoid, or a
// hyperellipsoid", 2013): bisection for the root of the normal's parameter, a fixed
// iteration count, only + - * / sqrt.
double distance_to_ellipse(double e0, double e1, double y0, double y1) {
  if (y1 > 0) {
    if (y0 > 0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0) return 0.0;
      const double r0 = (e0 / e1) * (e0 / e1);
      const double n0 = r0 * z0;
      double s0 = z1 - 1.0;
      double s1 = g < 0 ? 0.0 : std::sqrt(n0 * n0 + z1 * z1) - 1.0;
      double s = 0;
      for (int i = 0; i < 200; ++i) {
        s = 0.5 * (s0 + s1);
        if (s == s0 || s == s1) break;
        const double ratio0 = n0 / (s + r0), ratio1 = z1 / (s + 1.0);
        const double gs = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
        if (gs > 0)
          s0 = s;
        else if (gs < 0)
          s1 = s;
        else
          break;
      }
      const double x0 = r0 * y0 / (s + r0), x1 = y1 / (s + 1.0);
      return std::sqrt((x0 - y0) * (x0 - y0) + (x1 - y1) * (x1 - y1));
    }
    return std::abs(y1 - e1);
  }
  const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    const double x0 = e0 * xde0, x1 = e1 * std::sqrt(1.0 - xde0 * xde0);
    return std::sqrt((x0 - y0) * (x0 - y0) + x1 * x1);
  }
  return std::abs(y0 - e0);
}

// The dome (half ellipsoid, semi-axes a across and h up, axis through the origin here):
// is p (relative to the axis foot, any units) inside with at least `clear` to the skin?
bool inside_with_clearance(double a, double h, double px, double py, double pz, double clear) {
  const double rho = std::sqrt(px * px + py * py);
  if (pz < 0) return false;
  if ((rho / a) * (rho / a) + (pz / h) * (pz / h) >= 1.0) return false;
  const double d = a >= h ? distance_to_ellipse(a, h, rho, pz) : distance_to_ellipse(h, a, pz, rho);
  return d >= clear;
}

// Directions sampling a tumour's surface: the integer vectors of {-3..3}^3 but 0,
// normalised (342, at most about 8 degrees from any direction).
const std::vector<std::array<double, 3>>& surface_directions() {
  static const std::vector<std::array<double, 3>> dirs = [] {
    std::vector<std::array<double, 3>> v;
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j)
        for (int k = -3; k <= 3; ++k) {
          if (i == 0 && j == 0 && k == 0) continue;
          const double n = std::sqrt(double(i * i + j * j + k * k));
          v.push_back({i / n, j / n, k / n});
        }
    return v;
  }();
  return dirs;
}

double interpolate(double x, std::initializer_list<std::array<double, 2>> pts) {
  const auto* p = pts.begin();
  if (x <= p[0][0]) return p[0][1];
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (x <= p[i][0]) return p[i - 1][1] + (x - p[i - 1][0]) / (p[i][0] - p[i - 1][0]) * (p[i][1] - p[i - 1][1]);
  return p[pts.size() - 1][1];
}

struct Placed {
  std::int64_t cx, cy, cz;   // um, relative to the axis foot
  std::int64_t bound;        // um, bounding-sphere radius
};

}  // namespace

// ---------------------------------------------------------------- ranges

void validate(const CaseRanges& r, const std::string& source, const std::string& field) {
  const sim::JsonReader rd(source);
  auto range = [&](const char* key, double lo, double hi, double min_allowed, double max_allowed, const char* unit) {
    const std::string f = sim::JsonReader::join(field, key);
    if (!std::isfinite(lo) || !std::isfinite(hi)) rd.fail(f, "must be finite");
    if (lo > hi) rd.fail(f, "min " + sim::JsonReader::fmt(lo) + " is above max " + sim::JsonReader::fmt(hi));
    if (lo < min_allowed || hi > max_allowed)
      rd.fail(f, "must be within " + sim::JsonReader::fmt(min_allowed) + ".." + sim::JsonReader::fmt(max_allowed) + unit +
                     ", got [" + sim::JsonReader::fmt(lo) + ", " + sim::JsonReader::fmt(hi) + "]");
  };
  if (r.tumours_min < 0 || r.tumours_max > CaseRanges::kMaxTumours || r.tumours_min > r.tumours_max)
    rd.fail(sim::JsonReader::join(field, "tumours"),
            "must be [min, max] within 0.." + std::to_string(CaseRanges::kMaxTumours) + ", got [" +
                std::to_string(r.tumours_min) + ", " + std::to_string(r.tumours_max) + "]");
  range("diameter", r.diameter_min, r.diameter_max, CaseRanges::kMinDiameter, CaseRanges::kMaxDiameter, " m");
  range("depth", r.depth_min, r.depth_max, CaseRanges::kMinDepth, CaseRanges::kMaxDepth, " m");
  range("hardness", r.hardness_min, r.hardness_max, CaseRanges::kMinHardness, CaseRanges::kMaxHardness,
        " (x tissue; above 30x no published lesion, docs/training.md)");
  range("base_radius", r.base_radius_min, r.base_radius_max, CaseRanges::kMinBaseRadius, CaseRanges::kMaxBaseRadius, " m");
  range("height", r.height_min, r.height_max, CaseRanges::kMinHeight, CaseRanges::kMaxHeight, " m");
  // A grid point must lie in each range (0.1 mm lengths, 0.1x hardness).
  auto grid = [&](const char* key, double lo, double hi, double unit) {
    if (units_up(lo, unit) > units_down(hi, unit))
      rd.fail(sim::JsonReader::join(field, key), "holds no value on the " + sim::JsonReader::fmt(unit) + " grid cases are drawn on");
  };
  grid("diameter", r.diameter_min, r.diameter_max, kUnit);
  grid("depth", r.depth_min, r.depth_max, kUnit);
  grid("hardness", r.hardness_min, r.hardness_max, 0.1);
  grid("base_radius", r.base_radius_min, r.base_radius_max, kUnit);
  grid("height", r.height_min, r.height_max, kUnit);
  if (!(r.ellipsoid_fraction >= 0 && r.ellipsoid_fraction <= 1))
    rd.fail(sim::JsonReader::join(field, "ellipsoid_fraction"), "must be within 0..1, got " + sim::JsonReader::fmt(r.ellipsoid_fraction));
  if (!(r.tissue_young >= 1000 && r.tissue_young <= 1e6))
    rd.fail(sim::JsonReader::join(field, "tissue_young_modulus"), "must be within 1000..1000000 Pa, got " + sim::JsonReader::fmt(r.tissue_young));
  if (!sim::resolution_edge("breast", r.resolution))
    rd.fail(sim::JsonReader::join(field, "resolution"), "unknown level \"" + r.resolution + "\" (coarse, paper, fine, xfine)");
}

CaseRanges ranges_from_json(const json& j, const std::string& source, const std::string& field, const CaseRanges& base) {
  const sim::JsonReader rd(source, /*comments=*/true);
  rd.only_keys(j, field, {"tumours", "diameter", "depth", "hardness", "base_radius", "height", "ellipsoid_fraction",
                          "tissue_young_modulus", "resolution"});
  CaseRanges r = base;
  auto pair = [&](const char* key, double& lo, double& hi) {
    rd.opt(j, key, field, [&](const json& v, const std::string& f) {
      if (!v.is_array() || v.size() != 2) rd.fail(f, "must be [min, max]");
      lo = rd.number(v[0], f + "[0]");
      hi = rd.number(v[1], f + "[1]");
    });
  };
  rd.opt(j, "tumours", field, [&](const json& v, const std::string& f) {
    if (v.is_number_integer()) {
      r.tumours_min = r.tumours_max = rd.integer(v, f, 0, CaseRanges::kMaxTumours);
      return;
    }
    if (!v.is_array() || v.size() != 2) rd.fail(f, "must be a count or [min, max]");
    r.tumours_min = rd.integer(v[0], f + "[0]", 0, CaseRanges::kMaxTumours);
    r.tumours_max = rd.integer(v[1], f + "[1]", 0, CaseRanges::kMaxTumours);
  });
  pair("diameter", r.diameter_min, r.diameter_max);
  pair("depth", r.depth_min, r.depth_max);
  pair("hardness", r.hardness_min, r.hardness_max);
  pair("base_radius", r.base_radius_min, r.base_radius_max);
  pair("height", r.height_min, r.height_max);
  rd.opt(j, "ellipsoid_fraction", field, [&](const json& v, const std::string& f) { r.ellipsoid_fraction = rd.number(v, f); });
  rd.opt(j, "tissue_young_modulus", field, [&](const json& v, const std::string& f) { r.tissue_young = rd.number(v, f); });
  rd.opt(j, "resolution", field, [&](const json& v, const std::string& f) { r.resolution = rd.string(v, f); });
  validate(r, source, field);
  return r;
}

json to_json(const CaseRanges& r) {
  return {{"tumours", {r.tumours_min, r.tumours_max}},
          {"diameter", {r.diameter_min, r.diameter_max}},
          {"depth", {r.depth_min, r.depth_max}},
          {"hardness", {r.hardness_min, r.hardness_max}},
          {"base_radius", {r.base_radius_min, r.base_radius_max}},
          {"height", {r.height_min, r.height_max}},
          {"ellipsoid_fraction", r.ellipsoid_fraction},
          {"tissue_young_modulus", r.tissue_young},
          {"resolution", r.resolution}};
}

// ---------------------------------------------------------------- difficulty

double estimate_detection(double diameter, double depth, double hardness) {
  // Size, superficial and firm (silicone models: 0.3 cm 14%, 1 cm 87%; Pugh: 2 cm 99.6%).
  const double size = interpolate(diameter * 100.0, {{{0.2, 0.05}}, {{0.3, 0.14}}, {{1.0, 0.87}}, {{2.0, 0.996}}});
  // Depth (tissue over the top): superficial (<= 0.5 cm) 1, deep (>= 2.5 cm) 0.6 (Pugh: 2 cm
  // deep firm 60% against 2 cm superficial 99.6%).
  const double deep = interpolate(depth * 100.0, {{{0.5, 0.0}}, {{2.5, 1.0}}});
  const double depth_factor = 1.0 - 0.4 * deep;
  // Hardness matters at depth only (Pugh: 2 cm superficial soft 99.6%; deep hard 75% against
  // deep firm 60%): firm (5.6x, the paper's 107 kPa) 1, soft (2x) 0.8, hard (24x) 1.25.
  const double hard = interpolate(hardness, {{{1.5, 0.75}}, {{2.0, 0.8}}, {{5.6, 1.0}}, {{24.0, 1.25}}});
  const double hardness_factor = 1.0 + deep * (hard - 1.0);
  return std::clamp(size * depth_factor * hardness_factor, 0.0, 1.0);
}

int difficulty_grade(double p) {
  if (p >= 0.85) return 1;
  if (p >= 0.65) return 2;
  if (p >= 0.45) return 3;
  if (p >= 0.25) return 4;
  return 5;
}

const char* difficulty_name(int grade) {
  switch (grade) {
    case 1: return "very easy";
    case 2: return "easy";
    case 3: return "moderate";
    case 4: return "hard";
    default: return "very hard";
  }
}

double surrounding_modulus(const sim::Scenario& s, double depth) {
  return s.layers.empty() ? s.young_modulus : sim::layer_modulus(s.layers, depth);
}

std::optional<Difficulty> scenario_difficulty(const sim::Scenario& s) {
  if (!s.patient.mesh.empty() || s.patient.phantom != "breast") return std::nullopt;
  sim::BreastShape dome;
  dome.base_radius = s.patient.base_radius;
  dome.height = s.patient.height;
  Difficulty d;
  bool any = false;
  for (const auto& inc : s.inclusions) {
    const double skin_z = dome.surface_z(inc.center.x(), inc.center.y());
    const double hardness = inc.young_modulus / surrounding_modulus(s, skin_z - inc.center.z());
    if (!(hardness > 1.2)) continue;
    any = true;
    const double depth = std::max(0.0, skin_z - (inc.center.z() + inc.radii.z()));
    d.detection *= estimate_detection(2.0 * inc.radii.maxCoeff(), depth, hardness);
  }
  if (!any) d.detection = 0.94;  // as generate_case: the pooled clinical specificity
  d.grade = difficulty_grade(d.detection);
  return d;
}

std::string generated_case_name(std::uint64_t seed) { return "Generated case " + std::to_string(seed); }

// ---------------------------------------------------------------- the generator

GeneratedCase generate_case(std::uint64_t seed, const CaseRanges& ranges, const std::string& source) {
  validate(ranges, source, "ranges");
  GeneratedCase c;
  c.seed = seed;
  c.ranges = ranges;
  c.name = generated_case_name(seed);
  std::mt19937_64 g(seed);

  const std::int64_t a = draw(g, units_up(ranges.base_radius_min, kUnit), units_down(ranges.base_radius_max, kUnit));
  const std::int64_t h = draw(g, units_up(ranges.height_min, kUnit), units_down(ranges.height_max, kUnit));
  const int count = static_cast<int>(draw(g, ranges.tumours_min, ranges.tumours_max));
  const std::int64_t tissue = std::llround(ranges.tissue_young);  // Pa
  const std::int64_t ellipsoid_permille = std::llround(ranges.ellipsoid_fraction * 1000.0);
  const double a_um = double(a) * 100.0, h_um = double(h) * 100.0;

  sim::Scenario& s = c.scenario;
  s.source = c.name;
  s.patient.phantom = "breast";
  s.patient.resolution = ranges.resolution;
  s.patient.edge = *sim::resolution_edge("breast", ranges.resolution);
  s.patient.base_radius = double(a) / 1e4;
  s.patient.height = double(h) / 1e4;
  s.young_modulus = double(tissue);
  // The built-in breasts' layers, the fat at the ranges' tissue modulus and the gland at
  // its published ratio to it, in whole pascals.
  s.layers = sim::breast_layers();
  const double fat = s.layers.front().young_modulus;
  for (auto& layer : s.layers) layer.young_modulus = double(std::llround(layer.young_modulus * double(tissue) / fat));
  s.poisson_ratio = 0.45;
  s.density = 1000.0;

  // Clearances in whole micrometres.
  const std::int64_t wall_um = std::llround(kChestWallClearance / kMicron), gap_um = std::llround(kTumourGap / kMicron);
  const double skin_um = double(std::llround(kSkinClearance / kMicron));
  std::vector<Placed> placed;
  constexpr int kDraws = 40, kPositions = 250;  // per tumour: sizes/depths, positions for each
  for (int t = 0; t < count; ++t) {
    bool done = false;
    for (int attempt = 0; attempt < kDraws && !done; ++attempt) {
      const std::int64_t diameter = draw(g, units_up(ranges.diameter_min, kUnit), units_down(ranges.diameter_max, kUnit));
      const std::int64_t depth = draw(g, units_up(ranges.depth_min, kUnit), units_down(ranges.depth_max, kUnit));
      const std::int64_t tenths = draw(g, units_up(ranges.hardness_min, 0.1), units_down(ranges.hardness_max, 0.1));
      const bool ellipsoid = draw(g, 0, 999) < ellipsoid_permille;
      const std::int64_t r = diameter * 50;  // um: the longest radius
      std::array<std::int64_t, 3> radii{r, r, r};
      if (ellipsoid) {
        const int longest = static_cast<int>(draw(g, 0, 2));
        for (int k = 0; k < 3; ++k)
          if (k != longest) radii[std::size_t(k)] = r * draw(g, 60, 100) / 100;
      }
      for (int p = 0; p < kPositions && !done; ++p) {
        const std::int64_t dx = draw(g, -a, a), dy = draw(g, -a, a);  // 0.1 mm from the axis
        const std::int64_t rho2 = dx * dx + dy * dy;
        if (rho2 >= a * a) continue;
        // Centre so that `depth` of tissue lies over the top, vertically.
        const double skin = double(h) * std::sqrt(1.0 - double(rho2) / double(a * a));  // 0.1 mm
        const std::int64_t top = static_cast<std::int64_t>(std::floor((skin - double(depth)) * 100.0));  // um
        const std::int64_t cz = top - radii[2];
        const std::int64_t cx = dx * 100, cy = dy * 100;
        if (cz - radii[2] < wall_um) continue;
        bool apart = true;
        for (const Placed& o : placed) {
          const std::int64_t ddx = cx - o.cx, ddy = cy - o.cy, ddz = cz - o.cz;
          const std::int64_t need = r + o.bound + gap_um;
          if (ddx * ddx + ddy * ddy + ddz * ddz < need * need) apart = false;
        }
        if (!apart) continue;
        bool inside = true;
        for (const auto& d : surface_directions()) {
          if (!inside_with_clearance(a_um, h_um, double(cx) + double(radii[0]) * d[0], double(cy) + double(radii[1]) * d[1],
                                     double(cz) + double(radii[2]) * d[2], skin_um)) {
            inside = false;
            break;
          }
        }
        if (!inside) continue;
        placed.push_back({cx, cy, cz, r});
        sim::Inclusion inc;
        inc.shape = ellipsoid ? "ellipsoid" : "sphere";
        inc.center = Eigen::Vector3d(double(std::llround(kBreastAxisX / kMicron) + cx) / 1e6, double(cy) / 1e6, double(cz) / 1e6);
        inc.radii = Eigen::Vector3d(double(radii[0]) / 1e6, double(radii[1]) / 1e6, double(radii[2]) / 1e6);
        // Hardness against the layer around the centre (vertically below the skin, as the
        // depth is measured).
        const double centre_depth = (skin * 100.0 - double(cz)) / 1e6;
        const std::int64_t around = std::llround(surrounding_modulus(s, centre_depth));
        inc.young_modulus = double(around * tenths) / 10.0;
        inc.poisson_ratio = s.poisson_ratio;
        s.inclusions.push_back(inc);
        GeneratedTumour gt;
        gt.diameter = double(diameter) / 1e4;
        gt.depth = double(depth) / 1e4;
        gt.hardness = double(tenths) / 10.0;
        gt.detection = estimate_detection(gt.diameter, gt.depth, gt.hardness);
        c.tumours.push_back(gt);
        done = true;
      }
    }
    if (!done)
      throw sim::ScenarioError(source + ": ranges: no room for tumour " + std::to_string(t + 1) + " of " + std::to_string(count) +
                               " in the breast of seed " + std::to_string(seed) + " (base radius " + sim::JsonReader::fmt(double(a) / 100.0) +
                               " cm, height " + sim::JsonReader::fmt(double(h) / 100.0) + " cm) after " +
                               std::to_string(kDraws * kPositions) +
                               " tries: allow smaller depths or diameters, a larger breast, or fewer tumours");
  }

  // Without tumours the case tests specificity: the pooled clinical figure (Barton 1999).
  c.detection = c.tumours.empty() ? 0.94 : 1.0;
  for (const auto& t : c.tumours) c.detection *= t.detection;
  c.difficulty = difficulty_grade(c.detection);

  // A press over the apex, so that `palpation run` has something to do; the trainee's own
  // hand replaces it in an exam. Not over a tumour: the file says nothing by where it presses.
  sim::FingerPath fp;
  fp.radius = 0.008;
  const double top = s.patient.height + fp.radius;
  fp.keys = {{0.0, kBreastAxisX, 0.0, top + 0.005}, {1.0, kBreastAxisX, 0.0, top - 0.01}, {2.0, kBreastAxisX, 0.0, top + 0.005}};
  s.fingers.push_back(fp);
  s.duration = 2.0;
  return c;
}

json case_summary(const GeneratedCase& c, bool answer) {
  json j = {{"name", c.name},
            {"seed", c.seed},
            {"difficulty", c.difficulty},
            {"difficulty_name", difficulty_name(c.difficulty)},
            {"detection", c.detection},
            {"ranges", to_json(c.ranges)}};
  if (answer) {
    json t = json::array();
    for (std::size_t i = 0; i < c.tumours.size(); ++i) {
      const auto& inc = c.scenario.inclusions[i];
      t.push_back({{"shape", inc.shape},
                   {"center", {inc.center.x(), inc.center.y(), inc.center.z()}},
                   {"diameter", c.tumours[i].diameter},
                   {"depth", c.tumours[i].depth},
                   {"hardness", c.tumours[i].hardness},
                   {"young_modulus", inc.young_modulus},
                   {"detection", c.tumours[i].detection}});
    }
    j["tumours"] = t;
  }
  return j;
}

}  // namespace palpation::app::train
