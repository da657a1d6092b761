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

constexpr double kD = 0.001;
constexpr double kW = 0.1, kT = 0.05;

// One indentation: the tissue's modulus and Poisson's ratio, the sphere's radius, the element.
struct Case {
  double E = 19000, nu = 0.45, R = 0.01;
  Element element = Element::Linear;
};

// Hertz for an elastic half-space, F = 4/3 E* sqrt(R) d^1.5, E* = E / (1 - nu^2),
// corrected for the finite layer bonded to its base (Dimitriadis et al. 2002, Biophys J
// 82:2798, eq. 12): F = F_H (1 - 2 a0/pi chi + 4 a0^2/pi^2 chi^2), chi = sqrt(R d)/T,
// a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu). Here chi = 0.063: +7%.
double hertz_force(const Case& c, double d) {
  const double fh = 4.0 / 3.0 * c.E / (1 - c.nu * c.nu) * std::sqrt(c.R) * std::pow(d, 1.5);
  const double chi = std::sqrt(c.R * d) / kT;
  const double a0 = -(1.2876 - 1.4678 * c.nu + 1.3442 * c.nu * c.nu) / (1 - c.nu);
  return fh * (1 - 2 * a0 / M_PI * chi + 4 * a0 * a0 / (M_PI * M_PI) * chi * chi);
}

struct Result {
  double force, depth;
  int tets;
  int max_iterations = 0;  // CG iterations of the hardest step
};

// n cells across x and y, n/2 through z, graded (exponent 2) toward the contact.
Result indent(int n, const Case& c = {}) {
  const double kR = c.R;
  TetMesh mesh = make_box_mesh(V3(kW, kW, kT), n, n, n / 2);
  grade_box_mesh(mesh, V3(kW, kW, kT), 2.0);
  const Model m = build_model(mesh, Material{c.E, c.nu, 1000}, fix_base());
  SimParams p;
  p.element = c.element;
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
  int max_it = 0;
  for (int k = 1; k <= ramp + hold; ++k) {
    const double s = std::min(1.0, double(k) / ramp);
    f[0].position = V3(0, 0, kT + kR - s * kD);
    f[0].velocity = V3(0, 0, k <= ramp ? -kD / ramp / p.solver.dt : 0.0);
    const StepStats st = b->step(f, out);
    max_it = std::max(max_it, st.cg_iterations);
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
  if (!(node_depth > 0.9 * kD && node_depth < 1.2 * kD)) return {NAN, node_depth, m.num_tets(), max_it};
  return {out[0].force_raw.z(), kD - penetration, m.num_tets(), max_it};
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
      const double ref = hertz_force(Case{}, r.depth);
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

  // Nearly incompressible tissue. The linear element locks as nu -> 0.5 (measured on this
  // scene at 36 across: +5.8% at 0.45, +25% at 0.49; at 20 across +350% at 0.499); the
  // nodal-pressure element does not: at 28 across it is within 5% of Hertz at 0.45,
  // 0.49 and 0.499 (measured +2.5, +1.9, +0.3%), at a second radius and modulus too, and
  // its error at 28 across is below that at 20 (+12 to +13% there, whatever nu). The 5%
  // is the bound: Hertz's half-space with the finite-layer correction is itself
  // ~1% here, the penalty penetration is subtracted (indent()), the rest is the mesh.
  void nodalPressureMatchesHertzNearlyIncompressible_data() {
    QTest::addColumn<double>("nu");
    QTest::addColumn<double>("radius");
    QTest::addColumn<double>("young");
    QTest::addColumn<bool>("heavy");  // minutes of CG: not in the sanitizer build
    QTest::newRow("nu 0.45") << 0.45 << 0.01 << 19000.0 << false;
    QTest::newRow("nu 0.49") << 0.49 << 0.01 << 19000.0 << false;
    QTest::newRow("nu 0.49, R 15 mm, 60 kPa") << 0.49 << 0.015 << 60000.0 << true;
    QTest::newRow("nu 0.499") << 0.499 << 0.01 << 19000.0 << true;
  }
  void nodalPressureMatchesHertzNearlyIncompressible() {
    QFETCH(double, nu);
    QFETCH(double, radius);
    QFETCH(double, young);
    QFETCH(bool, heavy);
    if (heavy && qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0)
      QSKIP("PALPATION_LIGHT_TESTS: this row (thousands of CG iterations a step) runs in the plain build only");
    Case c;
    c.nu = nu;
    c.R = radius;
    c.E = young;
    c.element = Element::NodalPressure;
    double errs[2];
    const int sizes[2] = {20, 28};
    for (int k = 0; k < 2; ++k) {
      const Result r = indent(sizes[k], c);
      QVERIFY(std::isfinite(r.force));
      const double ref = hertz_force(c, r.depth);
      errs[k] = r.force / ref - 1;
      qInfo("nodal pressure, n=%d: F = %.5f N, Hertz %.5f N, error %+.1f%%, CG up to %d iterations a step", sizes[k],
            r.force, ref, 100 * errs[k], r.max_iterations);
    }
    QVERIFY2(std::abs(errs[1]) < std::abs(errs[0]), "error must shrink with refinement");
    QVERIFY2(std::abs(errs[1]) < 0.05, qPrintable(QString::number(errs[1])));
  }

  // Beside it, the linear element on the same mesh at nu = 0.49 is far off: the locking
  // the nodal-pressure element removes (a test that would pass if the element did not lock
  // is no test of the nodal one either: this shows the scene can tell them apart).
  void linearElementLocksAtNu049() {
    Case c;
    c.nu = 0.49;
    const Result r = indent(28, c);
    const double err = r.force / hertz_force(c, r.depth) - 1;
    qInfo("linear, nu 0.49, n=28: error %+.1f%%", 100 * err);
    QVERIFY2(err > 0.15, qPrintable(QString::number(err)));
  }
};

QTEST_APPLESS_MAIN(TestHertz)
#include "tst_hertz.moc"
