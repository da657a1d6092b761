// Hertz indentation through the whole dynamic pipeline (penalty contact + implicit
// Euler + CG), quasi-static: a rigid sphere R = 1 cm pressed d = 1 mm (d/R = 0.1) into a
// 10 x 10 x 5 cm block bonded to a rigid base.
#include <QtTest>

#include <Eigen/Dense>

#include "backend.h"
#include "model.h"

using namespace palpation::sim;
using V3 = Eigen::Vector3d;

namespace {

constexpr double kE = 19000, kNu = 0.45, kR = 0.01, kD = 0.001;
constexpr double kW = 0.1, kT = 0.05;

// Hertz for an elastic half-space, F = 4/3 E* sqrt(R) d^1.5, E* = E / (1 - nu^2),
// corrected for the finite layer bonded to its base (Dimitriadis et al. 2002, Biophys J
// 82:2798, eq. 12): F = F_H (1 - 2 a0/pi chi + 4 a0^2/pi^2 chi^2), chi = sqrt(R d)/T,
// a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu). Here chi = 0.063: +7%.
double hertz_force(double d) {
  const double fh = 4.0 / 3.0 * kE / (1 - kNu * kNu) * std::sqrt(kR) * std::pow(d, 1.5);
  const double chi = std::sqrt(kR * d) / kT;
  const double a0 = -(1.2876 - 1.4678 * kNu + 1.3442 * kNu * kNu) / (1 - kNu);
  return fh * (1 - 2 * a0 / M_PI * chi + 4 * a0 * a0 / (M_PI * M_PI) * chi * chi);
}

struct Result {
  double force, depth;
  int tets;
};

// n cells across x and y, n/2 through z, graded (exponent 2) toward the contact.
Result indent(int n) {
  TetMesh mesh = make_box_mesh(V3(kW, kW, kT), n, n, n / 2);
  grade_box_mesh(mesh, V3(kW, kW, kT), 2.0);
  const Model m = build_model(mesh, Material{kE, kNu, 1000}, fix_base());
  SimParams p;
  p.solver.dt = 0.01;  // quasi-static: at this dt the system is stiffness-dominated
  p.solver.cg_tolerance = 1e-8;
  p.solver.cg_max_iterations = 20000;
  p.damping.mass = 0.0;
  p.damping.stiffness = 0.0;
  p.contact.stiffness = 2e6;  // N/m per finger cross-section (area-weighted): penetration << d
  p.contact.damping = 0.0;
  auto b = make_backend(BackendKind::Cpu, m, p);
  int top = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.rest[i] - V3(0, 0, kT)).norm() < (m.rest[top] - V3(0, 0, kT)).norm()) top = i;
  std::vector<FingerInput> f(1);
  std::vector<FingerOutput> out(1);
  f[0].radius = kR;
  const int ramp = 20, hold = 10;
  for (int k = 1; k <= ramp + hold; ++k) {
    const double s = std::min(1.0, double(k) / ramp);
    f[0].position = V3(0, 0, kT + kR - s * kD);
    f[0].velocity = V3(0, 0, k <= ramp ? -kD / ramp / p.solver.dt : 0.0);
    const StepStats st = b->step(f, out);
    if (!st.finite) return {NAN, NAN, m.num_tets()};
  }
  // Indentation: the sphere's travel from first touch (Hertz's rigid approach) less the
  // penalty penetration (below; a few micrometres, < 1% of d), subtracted; the surface node
  // under the sphere goes down by d plus the sag of its facets under the sphere.
  std::vector<double> x;
  b->positions(x);
  const double node_depth = kT - x[3 * top + 2];
  // Penalty penetration: F / k, k the reported contact stiffness along z (sum of the
  // area-weighted s k_s n_z^2 of the contacts).
  const double kzz = -out[0].stiffness(2, 2);
  const double penetration = kzz > 0 ? out[0].force_raw.z() / kzz : 0.0;
  if (!(node_depth > 0.9 * kD && node_depth < 1.2 * kD)) return {NAN, node_depth, m.num_tets()};
  return {out[0].force_raw.z(), kD - penetration, m.num_tets()};
}

}  // namespace

class TestHertz : public QObject {
  Q_OBJECT
 private slots:
  // Linear tetrahedra resolve the contact radius a = sqrt(R d) = 3.2 mm with a few
  // elements at these sizes: 10% (the bound) at the finest mesh, and the error
  // must shrink with refinement.
  void matchesHertzAndConverges() {
    // PALPATION_LIGHT_TESTS=1 (the sanitizer build in CI, .ci/run): the three coarser
    // meshes only; convergence is still asserted, the 10% bound needs the finest.
    const bool light = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0;
    const std::vector<int> sizes = light ? std::vector<int>{12, 20, 28} : std::vector<int>{12, 20, 28, 36, 44};
    double prev = 1e9;
    for (int n : sizes) {
      const Result r = indent(n);
      QVERIFY(std::isfinite(r.force));
      const double ref = hertz_force(r.depth);
      const double err = std::abs(r.force - ref) / ref;
      qInfo("Hertz n=%d (%d tets): d = %.4f mm, F = %.5f N, Hertz %.5f N, error %.1f%%", n, r.tets, r.depth * 1e3, r.force,
            ref, 100 * err);
      QVERIFY(r.depth > 0.95 * kD && r.depth <= kD);
      QVERIFY2(err < prev, "error must shrink with refinement");
      prev = err;
    }
    if (light)
      QSKIP(qPrintable(QString("PALPATION_LIGHT_TESTS: convergence checked on 12-28 across; the 10% bound against "
                               "Hertz is NOT checked (it needs the 44-across mesh; the finest here is %1% off)")
                           .arg(100 * prev, 0, 'f', 1)));
    QVERIFY2(prev < 0.10, qPrintable(QString::number(prev)));
  }
};

QTEST_APPLESS_MAIN(TestHertz)
#include "tst_hertz.moc"
