#include "hertz_probe.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "backend.h"
#include "mesh.h"
#include "model.h"

namespace palpation::sim {

namespace {
constexpr double kWidth = 0.1, kThickness = 0.05;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double hertz_force(const HertzCase& c, double d) {
  const double fh = 4.0 / 3.0 * c.young / (1 - c.nu * c.nu) * std::sqrt(c.radius) * std::pow(d, 1.5);
  const double chi = std::sqrt(c.radius * d) / kThickness;
  const double a0 = -(1.2876 - 1.4678 * c.nu + 1.3442 * c.nu * c.nu) / (1 - c.nu);
  return fh * (1 - 2 * a0 / kPi * chi + 4 * a0 * a0 / (kPi * kPi) * chi * chi);
}

HertzResult hertz_indent(const HertzCase& c, const std::string& backend) {
  using V3 = Eigen::Vector3d;
  HertzResult res;
  const int n = c.cells;
  TetMesh mesh = make_box_mesh(V3(kWidth, kWidth, kThickness), n, n, std::max(n / 2, 1));
  grade_box_mesh(mesh, V3(kWidth, kWidth, kThickness), 2.0);
  const Model m = build_model(mesh, Material{c.young, c.nu, 1000}, fix_base());
  res.nodes = m.num_nodes();
  res.tets = m.num_tets();
  SimParams p;
  p.element = c.element;
  p.solver.preconditioner = c.preconditioner;
  p.solver.dt = 0.01;  // quasi-static: at this dt the system is stiffness-dominated
  p.solver.precision = c.precision;
  p.solver.cg_tolerance = c.cg_tolerance;
  p.solver.cg_max_iterations = 20000;
  p.damping.mass = 0.0;
  p.damping.stiffness = 0.0;
  p.contact.stiffness = 2e6;  // N/m per finger cross-section (area-weighted): penetration << d
  p.contact.damping = 0.0;
  auto b = make_named_backend(backend, m, p);
  int top = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.rest[i] - V3(0, 0, kThickness)).norm() < (m.rest[top] - V3(0, 0, kThickness)).norm()) top = i;
  std::vector<FingerInput> f(1);
  std::vector<FingerOutput> out(1);
  f[0].radius = c.radius;
  const int ramp = 20, hold = 10;
  std::vector<double> ms;
  for (int k = 1; k <= ramp + hold; ++k) {
    const double s = std::min(1.0, double(k) / ramp);
    f[0].position = V3(0, 0, kThickness + c.radius - s * c.depth);
    f[0].velocity = V3(0, 0, k <= ramp ? -c.depth / ramp / p.solver.dt : 0.0);
    const auto t0 = std::chrono::steady_clock::now();
    const StepStats st = b->step(f, out);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    res.max_iterations = std::max(res.max_iterations, st.cg_iterations);
    res.total_iterations += st.cg_iterations;
    if (!st.finite) {
      res.why = "step " + std::to_string(k) + " is not finite";
      return res;
    }
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  res.step_ms = ms[ms.size() / 2];
  res.smoother = b->multigrid_counts().smoother();
  res.pressure_share = b->multigrid_counts().pressure_share;
  // Indentation: the sphere's travel from first touch (Hertz's rigid approach) less the
  // penalty penetration (a few micrometres, < 1% of d); the surface node under the sphere
  // goes down by d plus the sag of its facets under the sphere.
  std::vector<double> x;
  b->positions(x);
  const double node_depth = kThickness - x[3 * top + 2];
  // Penalty penetration: F / k, k the reported contact stiffness along z (sum of the
  // area-weighted s k_s n_z^2 of the contacts).
  const double kzz = -out[0].stiffness(2, 2);
  const double penetration = kzz > 0 ? out[0].force_raw.z() / kzz : 0.0;
  if (!(node_depth > 0.9 * c.depth && node_depth < 1.2 * c.depth)) {
    res.why = "the surface under the sphere went down " + std::to_string(node_depth * 1e3) + " mm, not about " +
              std::to_string(c.depth * 1e3) + " mm";
    res.depth = node_depth;
    return res;
  }
  res.force = out[0].force_raw.z();
  res.depth = c.depth - penetration;
  res.reference = hertz_force(c, res.depth);
  res.error = res.force / res.reference - 1;
  res.ok = std::isfinite(res.force);
  if (!res.ok) res.why = "the force is not finite";
  return res;
}

}  // namespace palpation::sim
