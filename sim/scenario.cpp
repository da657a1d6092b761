#include "scenario.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "json_reader.h"
#include "phantom.h"

namespace palpation::sim {

using nlohmann::json;

namespace {

// The scenario's fields beside the common ones (sim/json_reader.h).
class Reader : public JsonReader {
 public:
  using JsonReader::JsonReader;
  double poisson(const json& v, const std::string& field) const {
    const double d = number(v, field);
    if (!(d > -1.0 && d < 0.5)) fail(field, "must be in (-1, 0.5), got " + fmt(d));
    return d;
  }
  Eigen::Vector3d vec3(const json& v, const std::string& field) const { return triple<Eigen::Vector3d>(v, field); }
};

}  // namespace

const char* path_interpolation_name(PathInterpolation p) {
  return p == PathInterpolation::MonotoneCubic ? "monotone-cubic" : "linear";
}

std::vector<std::string> path_interpolation_names() {
  return {path_interpolation_name(PathInterpolation::Linear), path_interpolation_name(PathInterpolation::MonotoneCubic)};
}

PathInterpolation parse_path_interpolation(const std::string& name) {
  return name == path_interpolation_name(PathInterpolation::MonotoneCubic) ? PathInterpolation::MonotoneCubic
                                                                           : PathInterpolation::Linear;
}

namespace {
/// The monotone cubic's slope at an interior key for one coordinate, from the secants
/// d0 over the interval before it (length h0) and d1 over the one after (length h1): the
/// three-point derivative (second order in the spacing), zero where the secants differ in
/// sign or one is flat (the coordinate turns or rests there), and at most 3 min(|d0|, |d1|)
/// (Hyman 1983): both end slopes of every interval are then between 0 and 3 times its
/// secant, where a cubic Hermite interval is monotone (Fritsch & Carlson 1980), so it never
/// leaves the range of its two keys. Written out here: Eigen has no monotone spline, and
/// these dozen lines are the whole method.
double monotone_slope(double h0, double d0, double h1, double d1) {
  if (!(d0 * d1 > 0)) return 0.0;
  const double m = (h1 * d0 + h0 * d1) / (h0 + h1);
  const double limit = 3.0 * std::min(std::abs(d0), std::abs(d1));
  return std::copysign(std::min(std::abs(m), limit), m);
}
}  // namespace

void FingerPath::sample(double t, Eigen::Vector3d& pos, Eigen::Vector3d& vel) const {
  vel.setZero();
  if (keys.empty()) {
    pos.setZero();
    return;
  }
  auto at = [this](std::size_t i) { return Eigen::Vector3d(keys[i][1], keys[i][2], keys[i][3]); };
  if (t <= keys.front()[0]) {
    pos = at(0);
    return;
  }
  if (t >= keys.back()[0]) {
    pos = at(keys.size() - 1);
    return;
  }
  // Binary search for the segment.
  std::size_t lo = 0, hi = keys.size() - 1;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (keys[mid][0] <= t ? lo : hi) = mid;
  }
  const double t0 = keys[lo][0], t1 = keys[hi][0];
  const double h = t1 - t0;
  const double u = (t - t0) / h;
  if (interpolation == PathInterpolation::Linear) {
    pos = (1 - u) * at(lo) + u * at(hi);
    vel = (at(hi) - at(lo)) / h;
    return;
  }
  // The segment's end slopes from its neighbours' secants (zero at the path's ends).
  const Eigen::Vector3d d = (at(hi) - at(lo)) / h;
  Eigen::Vector3d m0 = Eigen::Vector3d::Zero(), m1 = Eigen::Vector3d::Zero();
  if (lo > 0) {
    const double hp = t0 - keys[lo - 1][0];
    const Eigen::Vector3d dp = (at(lo) - at(lo - 1)) / hp;
    for (int c = 0; c < 3; ++c) m0[c] = monotone_slope(hp, dp[c], h, d[c]);
  }
  if (hi + 1 < keys.size()) {
    const double hn = keys[hi + 1][0] - t1;
    const Eigen::Vector3d dn = (at(hi + 1) - at(hi)) / hn;
    for (int c = 0; c < 3; ++c) m1[c] = monotone_slope(h, d[c], hn, dn[c]);
  }
  // Cubic Hermite basis on u in [0, 1] and its derivative.
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = 3 * u2 - 2 * u3, h11 = u3 - u2;
  const double g00 = 6 * u2 - 6 * u, g10 = 3 * u2 - 4 * u + 1, g11 = 3 * u2 - 2 * u;
  pos = h00 * at(lo) + h10 * h * m0 + h01 * at(hi) + h11 * h * m1;
  vel = (g00 * at(lo) - g00 * at(hi)) / h + g10 * m0 + g11 * m1;
}

std::vector<std::array<double, 4>> FingerPath::linear_keys(double step) const {
  if (interpolation == PathInterpolation::Linear || keys.size() < 2 || !(step > 0)) return keys;
  const double t0 = keys.front()[0], t1 = keys.back()[0];
  const auto n = static_cast<std::size_t>(std::ceil((t1 - t0) / step - 1e-9));
  std::vector<std::array<double, 4>> out;
  out.reserve(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = i == n ? t1 : t0 + double(i) * step;
    Eigen::Vector3d p, v;
    sample(t, p, v);
    out.push_back({t, p.x(), p.y(), p.z()});
  }
  return out;
}

std::vector<std::string> resolution_names() { return {"coarse", "paper", "fine", "xfine"}; }

std::optional<double> resolution_edge(const std::string& phantom, const std::string& name) {
  // Breast edge lengths were chosen so that "paper" gives about the paper's 9,100 nodes /
  // 44,000 tetrahedra and "xfine" about ten times that (see docs/benchmarks.md). Gmsh's
  // classic Delaunay mesher (sim/mesh_gmsh.cpp) puts about 5.6 tetrahedra on a node where
  // HXT put 5.1, so the edges are 3.85 % longer than HXT needed: paper 8.4k nodes / 47k
  // tetrahedra, both within 10 % of the paper's.
  if (phantom == "breast") {
    if (name == "coarse") return 0.0119;
    if (name == "paper") return 0.00535;
    if (name == "fine") return 0.00363;
    if (name == "xfine") return 0.0024;
  } else {
    if (name == "coarse") return 0.01;
    if (name == "paper") return 0.005;
    if (name == "fine") return 0.0025;
    if (name == "xfine") return 0.00125;
  }
  return std::nullopt;
}

Scenario parse_scenario(const std::string& text, const std::string& source) {
  Reader rd(source);
  json j = rd.parse(text);
  rd.only_keys(j, "", {"patient", "tissue", "inclusions", "solver", "contact", "fingers", "duration", "gravity", "marks"});
  Scenario s;
  s.source = source;

  if (!j.contains("patient")) rd.fail("patient", "is required");
  {
    const json& p = j["patient"];
    rd.only_keys(p, "patient", {"phantom", "mesh", "resolution", "size", "grading", "base_radius", "height", "skin_edge"});
    if (p.contains("mesh") == p.contains("phantom")) rd.fail("patient", "give exactly one of \"phantom\" or \"mesh\"");
    if (p.contains("phantom")) s.patient.phantom = rd.choice(p["phantom"], "patient.phantom", {"breast", "box"});
    if (p.contains("mesh")) {
      s.patient.phantom.clear();
      std::filesystem::path mp = rd.string(p["mesh"], "patient.mesh");
      if (mp.empty()) rd.fail("patient.mesh", "is empty");
      if (mp.is_relative()) mp = std::filesystem::path(source).parent_path() / mp;
      s.patient.mesh = mp.string();
    }
    if (p.contains("size")) {
      if (s.patient.phantom != "box") rd.fail("patient.size", "only the box phantom takes a size");
      s.patient.size = rd.vec3(p["size"], "patient.size");
      for (int k = 0; k < 3; ++k)
        if (!(s.patient.size[k] > 0)) rd.fail("patient.size", "every side must be > 0");
    }
    for (const char* key : {"base_radius", "height"})
      if (p.contains(key)) {
        const std::string field = std::string("patient.") + key;
        if (s.patient.phantom != "breast") rd.fail(field, "only the breast phantom takes a " + std::string(key));
        const double v = rd.positive(p[key], field);
        if (v < 0.02 || v > 0.2) rd.fail(field, "must be in [0.02, 0.2] m");
        (std::string(key) == "height" ? s.patient.height : s.patient.base_radius) = v;
      }
    if (p.contains("skin_edge")) {
      if (s.patient.phantom != "breast") rd.fail("patient.skin_edge", "only the breast phantom takes a skin_edge");
      s.patient.skin_edge = rd.positive(p["skin_edge"], "patient.skin_edge");
      if (!edge_in_range(s.patient.skin_edge)) rd.fail("patient.skin_edge", std::string("must be in ") + kEdgeRange);
    }
    if (p.contains("grading")) {
      if (s.patient.phantom != "box") rd.fail("patient.grading", "only the box phantom takes a grading");
      s.patient.grading = rd.number(p["grading"], "patient.grading");
      if (s.patient.grading < 1.0 || s.patient.grading > 3.0) rd.fail("patient.grading", "must be in [1, 3]");
    }
    if (p.contains("resolution")) {
      const json& r = p["resolution"];
      if (r.is_string()) {
        s.patient.resolution = r.get<std::string>();
        auto e = resolution_edge(s.patient.phantom, s.patient.resolution);
        if (!e) rd.fail("patient.resolution", "unknown level \"" + s.patient.resolution + "\" (coarse, paper, fine, xfine, or an edge length in m)");
        s.patient.edge = *e;
      } else {
        s.patient.edge = rd.positive(r, "patient.resolution");
        s.patient.resolution.clear();
        if (!edge_in_range(s.patient.edge))
          rd.fail("patient.resolution", std::string("edge length must be in ") + kEdgeRange);
      }
    } else {
      s.patient.edge = *resolution_edge(s.patient.phantom, s.patient.resolution);
    }
  }

  if (j.contains("tissue")) {
    const json& t = j["tissue"];
    rd.only_keys(t, "tissue",
                 {"young_modulus", "poisson_ratio", "density", "damping_mass", "damping_stiffness", "element", "layers", "skin"});
    if (t.contains("element"))
      s.params.element = parse_element(rd.choice(t["element"], "tissue.element", element_names()));
    if (t.contains("young_modulus")) s.young_modulus = rd.positive(t["young_modulus"], "tissue.young_modulus");
    if (t.contains("poisson_ratio")) s.poisson_ratio = rd.poisson(t["poisson_ratio"], "tissue.poisson_ratio");
    if (t.contains("density")) s.density = rd.positive(t["density"], "tissue.density");
    if (t.contains("damping_mass")) s.params.damping.mass = rd.non_negative(t["damping_mass"], "tissue.damping_mass");
    if (t.contains("damping_stiffness"))
      s.params.damping.stiffness = rd.non_negative(t["damping_stiffness"], "tissue.damping_stiffness");
    if (t.contains("layers")) {
      // Bands below the skin, from the skin inward; the last (the core) has no thickness.
      const json& arr = t["layers"];
      if (!arr.is_array() || arr.empty() || arr.size() > kMaxLayers)
        rd.fail("tissue.layers", "must be an array of 1 to " + std::to_string(kMaxLayers) + " layers");
      for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string f = "tissue.layers[" + std::to_string(i) + "]";
        const json& l = arr[i];
        rd.only_keys(l, f, {"name", "thickness", "young_modulus"});
        TissueLayer layer;
        if (!l.contains("name")) rd.fail(f + ".name", "is required");
        layer.name = rd.string(l["name"], f + ".name");
        if (layer.name.empty() || layer.name.size() > 64) rd.fail(f + ".name", "must be 1 to 64 characters");
        for (const auto& other : s.layers)
          if (other.name == layer.name) rd.fail(f + ".name", "\"" + layer.name + "\" names two layers");
        const bool core = i + 1 == arr.size();
        if (core && l.contains("thickness"))
          rd.fail(f + ".thickness", "the last layer takes all that lies deeper: it has no thickness");
        if (!core) {
          if (!l.contains("thickness")) rd.fail(f + ".thickness", "is required (m) for every layer but the last");
          layer.thickness = rd.positive(l["thickness"], f + ".thickness");
          if (!(layer.thickness <= kMaxEdge)) rd.fail(f + ".thickness", "must be at most " + Reader::fmt(kMaxEdge) + " m");
        }
        if (!l.contains("young_modulus")) rd.fail(f + ".young_modulus", "is required (Pa)");
        layer.young_modulus = rd.positive(l["young_modulus"], f + ".young_modulus");
        s.layers.push_back(layer);
      }
    }
  }
  if (j.contains("tissue") && j["tissue"].contains("skin")) {
    // The skin as a membrane: in-plane stiffness E t over the surface triangles.
    const json& k = j["tissue"]["skin"];
    rd.only_keys(k, "tissue.skin", {"thickness", "young_modulus"});
    if (!k.contains("thickness")) rd.fail("tissue.skin.thickness", "is required (m)");
    s.skin.thickness = rd.positive(k["thickness"], "tissue.skin.thickness");
    if (!(s.skin.thickness <= kMaxSkinThickness))
      rd.fail("tissue.skin.thickness", "must be at most " + Reader::fmt(kMaxSkinThickness) + " m (a membrane, not a layer)");
    if (k.contains("young_modulus")) s.skin.young_modulus = rd.positive(k["young_modulus"], "tissue.skin.young_modulus");
  }
  // Stiffness contrast bound (docs/stability.md, `palpation stress`): beyond it the CG solve
  // of a step no longer converges within the iteration budget. Between the tissue, its
  // layers and the tumours.
  const auto check_contrast = [&](double E, const std::string& field) {
    const auto within = [&](double other, const std::string& of) {
      const double contrast = std::max(E / other, other / E);
      if (!(contrast <= kMaxStiffnessContrast))
        rd.fail(field, "must be within " + Reader::fmt(kMaxStiffnessContrast) + "x of " + of + " (" + Reader::fmt(other) +
                           " Pa), got " + Reader::fmt(contrast) + "x (docs/stability.md)");
    };
    within(s.young_modulus, "tissue.young_modulus");
    for (std::size_t i = 0; i < s.layers.size(); ++i)
      within(s.layers[i].young_modulus, "tissue.layers[" + std::to_string(i) + "].young_modulus");
  };
  for (std::size_t i = 0; i < s.layers.size(); ++i)
    check_contrast(s.layers[i].young_modulus, "tissue.layers[" + std::to_string(i) + "].young_modulus");
  if (s.skin.present()) check_contrast(s.skin.young_modulus, "tissue.skin.young_modulus");

  if (j.contains("inclusions")) {
    const json& arr = j["inclusions"];
    if (!arr.is_array()) rd.fail("inclusions", "must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string f = "inclusions[" + std::to_string(i) + "]";
      const json& in = arr[i];
      rd.only_keys(in, f, {"shape", "center", "radius", "radii", "young_modulus", "poisson_ratio"});
      Inclusion inc;
      inc.shape = in.contains("shape") ? rd.choice(in["shape"], f + ".shape", {"sphere", "ellipsoid"}) : "sphere";
      if (!in.contains("center")) rd.fail(f + ".center", "is required");
      inc.center = rd.vec3(in["center"], f + ".center");
      if (inc.shape == "sphere") {
        if (!in.contains("radius")) rd.fail(f + ".radius", "is required for a sphere");
        if (in.contains("radii")) rd.fail(f + ".radii", "a sphere takes \"radius\"");
        inc.radii = Eigen::Vector3d::Constant(rd.positive(in["radius"], f + ".radius"));
      } else {
        if (!in.contains("radii")) rd.fail(f + ".radii", "is required for an ellipsoid");
        if (in.contains("radius")) rd.fail(f + ".radius", "an ellipsoid takes \"radii\"");
        inc.radii = rd.vec3(in["radii"], f + ".radii");
        for (int k = 0; k < 3; ++k)
          if (!(inc.radii[k] > 0)) rd.fail(f + ".radii", "every radius must be > 0");
      }
      inc.young_modulus = in.contains("young_modulus") ? rd.positive(in["young_modulus"], f + ".young_modulus") : 107000.0;
      inc.poisson_ratio = in.contains("poisson_ratio") ? rd.poisson(in["poisson_ratio"], f + ".poisson_ratio") : s.poisson_ratio;
      check_contrast(inc.young_modulus, f + ".young_modulus");
      s.inclusions.push_back(inc);
    }
  }

  if (j.contains("solver")) {
    const json& sv = j["solver"];
    rd.only_keys(sv, "solver", {"backend", "dt", "precision", "cg_tolerance", "cg_max_iterations",
                             "cg_rescue_tolerance", "cg_rescue_iterations", "threads", "corotation_tolerance",
                             "preconditioner", "force_error", "check", "warm_start"});
    if (sv.contains("backend")) s.backend = rd.choice(sv["backend"], "solver.backend", {"auto", "cpu", "cuda"});
    if (sv.contains("dt")) {
      s.params.solver.dt = rd.positive(sv["dt"], "solver.dt");
      if (s.params.solver.dt > 0.1) rd.fail("solver.dt", "must be <= 0.1 s");
    }
    if (sv.contains("precision"))
      s.params.solver.precision =
          rd.choice(sv["precision"], "solver.precision", {"double", "float"}) == "float" ? Precision::Float : Precision::Double;
    if (sv.contains("cg_tolerance")) {
      s.params.solver.cg_tolerance = rd.positive(sv["cg_tolerance"], "solver.cg_tolerance");
      if (s.params.solver.cg_tolerance >= 1) rd.fail("solver.cg_tolerance", "must be < 1");
    }
    if (sv.contains("cg_max_iterations"))
      s.params.solver.cg_max_iterations = rd.integer(sv["cg_max_iterations"], "solver.cg_max_iterations", 1, 100000);
    if (sv.contains("cg_rescue_tolerance")) {
      s.params.solver.cg_rescue_tolerance = rd.positive(sv["cg_rescue_tolerance"], "solver.cg_rescue_tolerance");
      if (s.params.solver.cg_rescue_tolerance >= 1) rd.fail("solver.cg_rescue_tolerance", "must be < 1");
    }
    if (sv.contains("cg_rescue_iterations"))
      s.params.solver.cg_rescue_iterations =
          rd.integer(sv["cg_rescue_iterations"], "solver.cg_rescue_iterations", 0, 100000);
    if (sv.contains("threads")) s.params.solver.threads = rd.integer(sv["threads"], "solver.threads", 0, 256);
    if (sv.contains("corotation_tolerance")) {
      s.params.solver.corotation_tolerance = rd.non_negative(sv["corotation_tolerance"], "solver.corotation_tolerance");
      if (s.params.solver.corotation_tolerance > 0.01) rd.fail("solver.corotation_tolerance", "must be <= 0.01");
    }
    if (sv.contains("preconditioner"))
      s.params.solver.preconditioner =
          parse_preconditioner(rd.choice(sv["preconditioner"], "solver.preconditioner", preconditioner_names()));
    if (sv.contains("check"))
      s.params.solver.check = parse_check_place(rd.choice(sv["check"], "solver.check", check_place_names()));
    if (sv.contains("warm_start"))
      s.params.solver.warm_start = parse_warm_start(rd.choice(sv["warm_start"], "solver.warm_start", warm_start_names()));
    // A scenario that names a CG tolerance and no force error keeps that tolerance fixed
    // (every scenario written before the key: its results stay what they were).
    s.params.solver.force_error = sv.contains("cg_tolerance") ? 0.0 : kDefaultForceError;
    if (sv.contains("force_error")) {
      s.params.solver.force_error = rd.non_negative(sv["force_error"], "solver.force_error");
      if (s.params.solver.force_error > 0.5)
        rd.fail("solver.force_error", "must be <= 0.5 (a fraction of the converged force; 0 keeps cg_tolerance fixed)");
    }
  } else {
    s.params.solver.force_error = kDefaultForceError;
  }

  if (j.contains("contact")) {
    const json& c = j["contact"];
    rd.only_keys(c, "contact", {"stiffness", "damping", "force_filter_hz"});
    if (c.contains("stiffness")) s.params.contact.stiffness = rd.positive(c["stiffness"], "contact.stiffness");
    if (c.contains("damping")) s.params.contact.damping = rd.non_negative(c["damping"], "contact.damping");
    if (c.contains("force_filter_hz")) s.params.contact.force_filter_hz = rd.positive(c["force_filter_hz"], "contact.force_filter_hz");
  }

  if (j.contains("gravity")) s.params.gravity = rd.vec3(j["gravity"], "gravity");

  if (!j.contains("fingers")) rd.fail("fingers", "is required (1 to 5 fingers)");
  {
    const json& arr = j["fingers"];
    if (!arr.is_array() || arr.empty() || arr.size() > 5) rd.fail("fingers", "must be an array of 1 to 5 fingers");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string f = "fingers[" + std::to_string(i) + "]";
      rd.only_keys(arr[i], f, {"radius", "path", "interpolation"});
      FingerPath fp;
      if (arr[i].contains("radius")) fp.radius = rd.positive(arr[i]["radius"], f + ".radius");
      if (arr[i].contains("interpolation"))
        fp.interpolation =
            parse_path_interpolation(rd.choice(arr[i]["interpolation"], f + ".interpolation", path_interpolation_names()));
      if (!arr[i].contains("path")) rd.fail(f + ".path", "is required");
      const json& path = arr[i]["path"];
      if (!path.is_array() || path.empty()) rd.fail(f + ".path", "must be a non-empty array of [t, x, y, z]");
      for (std::size_t k = 0; k < path.size(); ++k) {
        const std::string pf = f + ".path[" + std::to_string(k) + "]";
        if (!path[k].is_array() || path[k].size() != 4) rd.fail(pf, "must be [t, x, y, z]");
        std::array<double, 4> key{};
        for (int c = 0; c < 4; ++c) key[c] = rd.number(path[k][c], pf + "[" + std::to_string(c) + "]");
        if (!fp.keys.empty() && !(key[0] > fp.keys.back()[0]))
          rd.fail(pf, "keyframe times must increase (" + Reader::fmt(key[0]) + " after " + Reader::fmt(fp.keys.back()[0]) + ")");
        if (key[0] < 0) rd.fail(pf + "[0]", "time must be >= 0");
        fp.keys.push_back(key);
      }
      s.fingers.push_back(std::move(fp));
    }
  }
  if (j.contains("duration")) {
    s.duration = rd.positive(j["duration"], "duration");
    if (s.duration > 3600) rd.fail("duration", "must be <= 3600 s");
  }
  if (s.duration / s.params.solver.dt > 1e7) rd.fail("duration", "more than 10 million steps at this dt");
  if (j.contains("marks")) {
    const json& arr = j["marks"];
    if (!arr.is_array()) rd.fail("marks", "must be an array of [t, x, y, z, confidence]");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string f = "marks[" + std::to_string(i) + "]";
      if (!arr[i].is_array() || (arr[i].size() != 5 && arr[i].size() != 4)) rd.fail(f, "must be [t, x, y, z, confidence]");
      ScenarioMark m;
      m.t = rd.number(arr[i][0], f + "[0]");
      if (m.t < 0 || m.t > s.duration) rd.fail(f + "[0]", "time must be within the session (0 to " + Reader::fmt(s.duration) + " s)");
      for (int c = 0; c < 3; ++c) m.position[c] = rd.number(arr[i][std::size_t(c + 1)], f + "[" + std::to_string(c + 1) + "]");
      if (arr[i].size() == 5) {
        m.confidence = rd.number(arr[i][4], f + "[4]");
        if (m.confidence < 0 || m.confidence > 1) rd.fail(f + "[4]", "confidence must be within 0..1, got " + Reader::fmt(m.confidence));
      }
      if (!s.marks.empty() && m.t < s.marks.back().t) rd.fail(f + "[0]", "mark times must not decrease");
      s.marks.push_back(m);
    }
  }
  return s;
}

Scenario load_scenario(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(path + ": (file): cannot be read (" + std::string(std::strerror(errno)) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scenario(ss.str(), path);
}

std::string scenario_to_json(const Scenario& s) {
  json j;
  json p;
  if (!s.patient.mesh.empty()) {
    p["mesh"] = s.patient.mesh;
  } else {
    p["phantom"] = s.patient.phantom;
    if (s.patient.phantom == "box") {
      p["size"] = {s.patient.size.x(), s.patient.size.y(), s.patient.size.z()};
      if (s.patient.grading != 1.0) p["grading"] = s.patient.grading;
    }
    if (s.patient.phantom == "breast") {
      if (s.patient.base_radius != PatientSpec{}.base_radius) p["base_radius"] = s.patient.base_radius;
      if (s.patient.height != PatientSpec{}.height) p["height"] = s.patient.height;
      if (s.patient.skin_edge > 0) p["skin_edge"] = s.patient.skin_edge;
    }
  }
  if (!s.patient.resolution.empty())
    p["resolution"] = s.patient.resolution;
  else
    p["resolution"] = s.patient.edge;
  j["patient"] = p;
  j["tissue"] = {{"young_modulus", s.young_modulus},
                 {"poisson_ratio", s.poisson_ratio},
                 {"density", s.density},
                 {"damping_mass", s.params.damping.mass},
                 {"damping_stiffness", s.params.damping.stiffness}};
  j["tissue"]["element"] = element_name(resolve_element(s.params.element, s.poisson_ratio));
  if (!s.layers.empty()) {
    json layers = json::array();
    for (std::size_t i = 0; i < s.layers.size(); ++i) {
      json l = {{"name", s.layers[i].name}, {"young_modulus", s.layers[i].young_modulus}};
      if (i + 1 < s.layers.size()) l["thickness"] = s.layers[i].thickness;
      layers.push_back(l);
    }
    j["tissue"]["layers"] = layers;
  }
  if (s.skin.present())
    j["tissue"]["skin"] = {{"thickness", s.skin.thickness}, {"young_modulus", s.skin.young_modulus}};
  j["inclusions"] = json::array();
  for (const auto& inc : s.inclusions) {
    json ji = {{"shape", inc.shape},
               {"center", {inc.center.x(), inc.center.y(), inc.center.z()}},
               {"young_modulus", inc.young_modulus},
               {"poisson_ratio", inc.poisson_ratio}};
    if (inc.shape == "sphere")
      ji["radius"] = inc.radii.x();
    else
      ji["radii"] = {inc.radii.x(), inc.radii.y(), inc.radii.z()};
    j["inclusions"].push_back(ji);
  }
  const auto& sv = s.params.solver;
  j["solver"] = {{"backend", s.backend},
                 {"dt", sv.dt},
                 {"precision", sv.precision == Precision::Float ? "float" : "double"},
                 {"cg_tolerance", sv.cg_tolerance},
                 {"cg_max_iterations", sv.cg_max_iterations},
                 {"cg_rescue_tolerance", sv.cg_rescue_tolerance},
                 {"cg_rescue_iterations", sv.cg_rescue_iterations},
                 {"corotation_tolerance", sv.corotation_tolerance}};
  // Written only when not the default (auto), so that a scenario's text (generated cases,
  // which curricula pin by hash; recordings) stays byte for byte what it was before the key.
  if (sv.preconditioner != Preconditioner::Auto) j["solver"]["preconditioner"] = preconditioner_name(sv.preconditioner);
  if (sv.check != CheckPlace::Auto) j["solver"]["check"] = check_place_name(sv.check);
  if (sv.warm_start != WarmStart::Auto) j["solver"]["warm_start"] = warm_start_name(sv.warm_start);
  // Read back, a scenario with cg_tolerance and no force_error has a fixed tolerance.
  if (sv.force_error > 0) j["solver"]["force_error"] = sv.force_error;
  j["contact"] = {{"stiffness", s.params.contact.stiffness},
                  {"damping", s.params.contact.damping},
                  {"force_filter_hz", s.params.contact.force_filter_hz}};
  if (s.params.gravity.squaredNorm() > 0) j["gravity"] = {s.params.gravity.x(), s.params.gravity.y(), s.params.gravity.z()};
  j["fingers"] = json::array();
  for (const auto& f : s.fingers) {
    json path = json::array();
    for (const auto& k : f.keys) path.push_back({k[0], k[1], k[2], k[3]});
    json finger = {{"radius", f.radius}, {"path", path}};
    // Written only where it is not the default, so a linear scenario's text (and the
    // cached references keyed by its hash) stay as they were.
    if (f.interpolation != PathInterpolation::Linear) finger["interpolation"] = path_interpolation_name(f.interpolation);
    j["fingers"].push_back(std::move(finger));
  }
  j["duration"] = s.duration;
  if (!s.marks.empty()) {
    j["marks"] = json::array();
    for (const auto& m : s.marks) j["marks"].push_back({m.t, m.position.x(), m.position.y(), m.position.z(), m.confidence});
  }
  return j.dump(2);
}

}  // namespace palpation::sim
