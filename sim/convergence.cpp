#include "convergence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "simulation.h"

namespace palpation::sim {

TumourResolution tumour_resolution(const Model& m, const Inclusion& inc) {
  TumourResolution r;
  double volume = 0, edges = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[std::size_t(e)];
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) c += m.rest[std::size_t(t[a])];
    if (!inc.contains(c / 4.0)) continue;  // apply_inclusions' centroid rule
    ++r.elements;
    volume += m.volume[std::size_t(e)];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges += (m.rest[std::size_t(t[a])] - m.rest[std::size_t(t[b])]).norm();
  }
  if (r.elements == 0) return r;
  const double analytic = 4.0 / 3.0 * M_PI * inc.radii.prod();
  r.volume_ratio = volume / analytic;
  r.mean_edge = edges / (6.0 * r.elements);
  r.across = 2.0 * inc.radii.minCoeff() / r.mean_edge;
  r.resolved = r.across >= kMinAcross && std::fabs(r.volume_ratio - 1.0) <= kVolumeTolerance;
  return r;
}

Extrapolation richardson(const std::vector<double>& h, const std::vector<double>& f) {
  Extrapolation x;
  const std::size_t n = std::min(h.size(), f.size());
  if (n < 3) {
    x.why = "needs three levels";
    return x;
  }
  const double h1 = h[n - 3], h2 = h[n - 2], h3 = h[n - 1];
  const double f1 = f[n - 3], f2 = f[n - 2], f3 = f[n - 1];
  if (!(h1 > h2 && h2 > h3 && h3 > 0)) {
    x.why = "mesh sizes not decreasing";
    return x;
  }
  if (!std::isfinite(f1) || !std::isfinite(f2) || !std::isfinite(f3)) {
    x.why = "a value is not finite";
    return x;
  }
  if (f1 == f2 && f2 == f3) {
    x.ok = true;
    x.limit = f3;
    return x;
  }
  const double r = (f1 - f2) / (f2 - f3);
  if (!(r > 0) || !std::isfinite(r)) {
    x.why = "not monotone (the three finest levels go up and down)";
    return x;
  }
  auto ratio = [&](double p) { return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)); };
  double lo = 0.25, hi = 4.0;
  if (r < ratio(lo) || r > ratio(hi)) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "order outside [%.2f, %.0f]: not yet in the asymptotic range", lo, hi);
    x.why = buf;
    return x;
  }
  for (int k = 0; k < 200 && hi - lo > 1e-13; ++k) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < r ? lo : hi) = mid;  // ratio increases with p for h1 > h2 > h3
  }
  x.order = 0.5 * (lo + hi);
  const double a = std::pow(h2, x.order), b = std::pow(h3, x.order);
  const double limit = f3 - (f2 - f3) * b / (a - b);
  // A fit that moves the finest value by more than half of it (past zero, for a force)
  // extrapolates from levels outside the asymptotic range: an order near the low end
  // turns a slow decrease into any limit at all.
  if (std::fabs(limit - f3) > 0.5 * std::fabs(f3)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the fit (order %.2f) moves the finest value by %.0f %%: not yet in the asymptotic range",
                  x.order, 100.0 * std::fabs(limit - f3) / std::fabs(f3));
    x.why = buf;
    x.order = std::numeric_limits<double>::quiet_NaN();
    return x;
  }
  x.limit = limit;
  x.ok = true;
  return x;
}

namespace {

double level_edge(const Scenario& s, const std::string& level) {
  if (auto e = resolution_edge(s.patient.phantom, level)) return *e;
  char* end = nullptr;
  const double v = std::strtod(level.c_str(), &end);
  if (level.empty() || end != level.c_str() + level.size() || !std::isfinite(v))
    throw ScenarioError("levels: \"" + level + "\" is neither a resolution (coarse, paper, fine, xfine) nor an edge length in m");
  if (!edge_in_range(v)) throw ScenarioError("levels: \"" + level + "\": an edge length must be in " + kEdgeRange);
  return v;
}

// Where to press: above the first inclusion stiffer than the tissue, else above the
// highest node (the breast's apex, a box's top).
Eigen::Vector3d press_point(const Scenario& s, const Model& m) {
  for (const auto& inc : s.inclusions)
    if (inc.young_modulus > s.young_modulus) return inc.center;
  Eigen::Vector3d top = m.rest.front();
  for (const auto& p : m.rest)
    if (p.z() > top.z()) top = p;
  return top;
}

}  // namespace

std::string recommended_level(const ConvergenceStudy& st) {
  std::string rec;
  // A level is enough when what the trainee feels has converged on it. With a tumour that
  // is the contrast: the device's force scale is set by a deep press on the same mesh
  // (sim/press_probe.h, app/live/force_mapping.h), so a mesh's overall stiffness does not
  // reach the hand, but the tumour's share of the force does. Its excess (contrast - 1)
  // must be within 20 % of the reference's, or within 0.01 (a 1 % force change, far below
  // the 15 % a hand can tell apart) where that excess is near 0. Without a tumour, the
  // force itself within 5 %. The reference is the extrapolated limit; without one, the
  // next finer level (so the finest level is never recommended without a limit: nothing
  // shows it is converged). Every tumour must be resolved on the level.
  const std::size_t n = st.levels.size();
  const Extrapolation& felt = st.has_tumour ? st.contrast : st.force;
  auto value = [&](const ConvergenceLevel& lv) { return st.has_tumour ? lv.contrast - 1.0 : lv.force; };
  auto matches = [&](double v, double ref) {
    return st.has_tumour ? std::fabs(v - ref) <= std::max(kContrastTolerance * std::fabs(ref), 0.01)
                         : std::fabs(v - ref) <= kForceTolerance * std::fabs(ref);
  };
  for (std::size_t k = 0; k < n && rec.empty(); ++k) {
    if (k + 1 >= n && !felt.ok) break;
    // This level and every finer one (a level that matches by chance between two that
    // do not is not converged).
    bool ok = true;
    for (std::size_t i = k; i < n && ok; ++i) {
      const ConvergenceLevel& lv = st.levels[i];
      ok = lv.finite;
      for (const auto& t : lv.tumours) ok = ok && t.resolved;
      if (felt.ok)
        ok = ok && matches(value(lv), st.has_tumour ? felt.limit - 1.0 : felt.limit);
      else if (i + 1 < n)
        ok = ok && matches(value(lv), value(st.levels[i + 1]));
    }
    if (ok) rec = st.levels[k].name;
  }
  return rec;
}

ConvergenceStudy convergence_study(const Scenario& s0, const ConvergenceOptions& o) {
  if (s0.patient.phantom.empty())
    throw ScenarioError(s0.source + ": patient.mesh: a mesh file has one resolution; a convergence study needs a phantom");
  std::vector<std::pair<double, std::string>> levels;
  for (const auto& l : o.levels) {
    const double e = level_edge(s0, l);
    for (const auto& [e2, l2] : levels)
      if (e2 == e) throw ScenarioError("levels: \"" + l + "\" and \"" + l2 + "\" are the same edge length");
    levels.emplace_back(e, l);
  }
  if (levels.empty()) throw ScenarioError("levels: none given");
  std::sort(levels.begin(), levels.end(), [](const auto& a, const auto& b) { return a.first > b.first; });

  ConvergenceStudy st;
  st.scenario = s0.source;
  for (const auto& inc : s0.inclusions) st.has_tumour = st.has_tumour || inc.young_modulus > s0.young_modulus;
  Scenario s = s0;
  s.backend = "cpu";
  s.fingers.clear();
  s.params.solver.cg_tolerance = std::min(s.params.solver.cg_tolerance, o.cg_tolerance);
  s.params.solver.cg_rescue_tolerance = std::min(s.params.solver.cg_rescue_tolerance, s.params.solver.cg_tolerance);

  for (std::size_t k = 0; k < levels.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ConvergenceLevel lv;
    lv.edge = levels[k].first;
    lv.name = levels[k].second;
    s.patient.edge = lv.edge;
    s.patient.resolution = resolution_edge(s.patient.phantom, lv.name) ? lv.name : std::string();
    if (o.log) o.log("convergence: level " + lv.name + ": meshing");
    const Model m = build_scenario_model(s, patient_mesh(s, o.log));
    lv.nodes = m.num_nodes();
    lv.tets = m.num_tets();
    for (const auto& inc : s.inclusions) lv.tumours.push_back(tumour_resolution(m, inc));

    const Eigen::Vector3d p = press_point(s, m);
    auto site = skin_site_above(m, p, o.radius);
    if (!site) throw ScenarioError(s0.source + ": no skin above the press point on level " + lv.name);
    if (k == 0) {
      st.site = *site;
      st.depth = o.depth_fraction * site->thickness;
    }
    if (o.log) o.log("convergence: level " + lv.name + ": " + std::to_string(lv.nodes) + " nodes, pressing");
    const PressResult over = press_probe(s, m, m.materials, *site, o.radius, st.depth, o.schedule);
    lv.force = over.force_normal;
    lv.finite = over.finite;
    if (st.has_tumour) {
      Materials plain = m.materials;
      plain.young = m.tissue_young;  // every element its own tissue (its layer's): no tumour
      const PressResult p2 = press_probe(s, m, plain, *site, o.radius, st.depth, o.schedule);
      lv.force_plain = p2.force_normal;
      lv.finite = lv.finite && p2.finite;
      if (lv.force_plain > 0) lv.contrast = lv.force / lv.force_plain;
    } else {
      lv.force_plain = lv.force;
    }
    lv.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    st.levels.push_back(std::move(lv));
  }

  std::vector<double> h, f, c;
  for (const auto& lv : st.levels) {
    h.push_back(lv.edge);
    f.push_back(lv.force);
    c.push_back(lv.contrast);
  }
  st.force = richardson(h, f);
  if (st.has_tumour) st.contrast = richardson(h, c);

  st.recommended = recommended_level(st);
  return st;
}

}  // namespace palpation::sim
