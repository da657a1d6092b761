#include "press_probe.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "simulation.h"

namespace palpation::sim {

std::optional<PressSite> skin_site_above(const Model& m, const Eigen::Vector3d& p, double footprint) {
  // The highest boundary triangle on the vertical line through p.
  double best_z = -std::numeric_limits<double>::infinity();
  for (const auto& tri : m.surface) {
    const Eigen::Vector3d &a = m.rest[std::size_t(tri[0])], &b = m.rest[std::size_t(tri[1])], &c = m.rest[std::size_t(tri[2])];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::fabs(det) < 1e-16) continue;  // vertical in the xy projection
    const double l1 = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
    const double l2 = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
    const double l0 = 1.0 - l1 - l2;
    constexpr double eps = -1e-12;
    if (l0 < eps || l1 < eps || l2 < eps) continue;
    best_z = std::max(best_z, l0 * a.z() + l1 * b.z() + l2 * c.z());
  }
  if (!std::isfinite(best_z)) return std::nullopt;
  PressSite site;
  site.skin = Eigen::Vector3d(p.x(), p.y(), best_z);
  // Normal: area-weighted over the triangles whose centroid lies within the footprint
  // (facets of a coarse mesh tilt by several degrees from one to the next).
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double nearest = std::numeric_limits<double>::infinity();
  Eigen::Vector3d nearest_n = Eigen::Vector3d::UnitZ();
  for (const auto& tri : m.surface) {
    const Eigen::Vector3d &a = m.rest[std::size_t(tri[0])], &b = m.rest[std::size_t(tri[1])], &c = m.rest[std::size_t(tri[2])];
    const Eigen::Vector3d area2 = (b - a).cross(c - a);
    const double dist = ((a + b + c) / 3.0 - site.skin).norm();
    if (dist <= footprint) n += area2;
    if (dist < nearest && area2.norm() > 0) {
      nearest = dist;
      nearest_n = area2.normalized();
    }
  }
  site.normal = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : nearest_n;
  // Thickness: to the first boundary triangle that the inward ray leaves through.
  double t_exit = std::numeric_limits<double>::infinity();
  for (const auto& tri : m.surface) {
    const double t = ray_triangle(site.skin, -site.normal, m.rest[std::size_t(tri[0])], m.rest[std::size_t(tri[1])],
                                  m.rest[std::size_t(tri[2])]);
    if (t > 1e-4) t_exit = std::min(t_exit, t);
  }
  if (!std::isfinite(t_exit)) {
    double zmin = site.skin.z();
    for (const auto& r : m.rest) zmin = std::min(zmin, r.z());
    t_exit = site.skin.z() - zmin;
  }
  site.thickness = t_exit;
  return site;
}

PressResult press_probe(const Scenario& s, const Model& m, const Materials& materials, const PressSite& site,
                        double radius, double depth, const PressSchedule& schedule) {
  Scenario ps = s;
  if (ps.backend == "auto") ps.backend = "cpu";
  ps.params.solver.dt = schedule.dt;
  Simulation sim(ps, m);
  // The patient's current materials (painted tumours) where they differ from the model's.
  std::vector<std::pair<int, double>> changes;
  for (int e = 0; e < materials.size() && e < m.materials.size(); ++e)
    if (materials.young[std::size_t(e)] != m.materials.young[std::size_t(e)]) changes.emplace_back(e, materials.young[std::size_t(e)]);
  if (!changes.empty()) sim.set_element_young(changes);
  sim.reset();

  PressResult r;
  r.site = site;
  r.radius = radius;
  r.depth = depth;
  std::vector<FingerInput> in(1);
  std::vector<FingerOutput> out(1);
  in[0].radius = radius;
  in[0].active = true;
  const double travel = schedule.clearance + depth;
  const int n_ramp = std::max(1, int(std::ceil(schedule.ramp / schedule.dt - 1e-9)));
  const int n_hold = std::max(1, int(std::ceil(schedule.hold / schedule.dt - 1e-9)));
  const Eigen::Vector3d start = site.skin + site.normal * (radius + schedule.clearance);
  for (int k = 1; k <= n_ramp + n_hold; ++k) {
    const double u = std::min(1.0, double(k) / double(n_ramp));
    in[0].position = start - site.normal * (u * travel);
    in[0].velocity = k <= n_ramp ? Eigen::Vector3d(-site.normal * (travel / (n_ramp * schedule.dt))) : Eigen::Vector3d::Zero();
    const Simulation::Outcome o = sim.advance(in, out, schedule.dt);
    ++r.steps;
    if (!o.ok) {
      r.finite = false;
      break;
    }
  }
  r.multigrid_builds = sim.backend().multigrid_counts().builds;
  r.force = r.finite ? out[0].force.norm() : 0.0;
  r.force_normal = r.finite ? out[0].force.dot(site.normal) : 0.0;
  return r;
}

DeepPress deep_press(const Scenario& s, const Model& m, const Materials& materials, double radius, double depth_fraction,
                     const PressSchedule& schedule) {
  DeepPress dp;
  dp.depth_fraction = depth_fraction;
  Scenario ps = s;
  ps.params.solver.preconditioner = Preconditioner::BlockJacobi;
  std::vector<Eigen::Vector3d> points;
  for (const auto& inc : s.inclusions)
    if (inc.young_modulus > s.young_modulus) points.push_back(inc.center);
  if (materials.size() == m.num_tets() && int(m.tissue_young.size()) == m.num_tets() && m.num_tets() > 0) {
    // The stiffest tumour element (the tumour rule against each element's own tissue: a
    // layered breast's skin and glandular tissue are stiffer than the reference and no tumour).
    int e = -1;
    for (int k = 0; k < m.num_tets(); ++k)
      if (is_tumour_modulus(materials.young[std::size_t(k)], m.tissue_young[std::size_t(k)]) &&
          (e < 0 || materials.young[std::size_t(k)] > materials.young[std::size_t(e)]))
        e = k;
    if (e >= 0) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) c += m.rest[std::size_t(m.tets[std::size_t(e)][a])];
      c /= 4.0;
      // Inside an inclusion already listed: that inclusion's centre is the better site.
      bool listed = false;
      for (const auto& inc : s.inclusions) listed = listed || (inc.young_modulus > s.young_modulus && inc.contains(c));
      if (!listed) points.push_back(c);
    }
  }
  {
    int top = -1;
    for (int i : m.surface_nodes)
      if (!m.fixed[std::size_t(i)] && (top < 0 || m.rest[std::size_t(i)].z() > m.rest[std::size_t(top)].z())) top = i;
    if (top >= 0) points.push_back(m.rest[std::size_t(top)]);
  }
  for (const auto& p : points) {
    const std::optional<PressSite> site = skin_site_above(m, p, radius);
    if (!site) continue;
    bool near = false;
    for (const auto& t : dp.tried) near = near || (t.site.skin - site->skin).norm() < radius;
    if (near) continue;
    dp.tried.push_back(press_probe(ps, m, materials, *site, radius, depth_fraction * site->thickness, schedule));
    if (dp.tried.size() == 1 || dp.tried.back().force > dp.press.force) dp.press = dp.tried.back();
  }
  return dp;
}

}  // namespace palpation::sim
