// Hertz indentation through the whole dynamic pipeline (penalty contact + implicit
// Euler + CG), quasi-static: a rigid sphere R = 1 cm pressed d = 1 mm (d/R = 0.1) into a
// 10 x 10 x 5 cm block bonded to a rigid base.
#include <QtTest>

#include "hertz_probe.h"

using namespace palpation::sim;

namespace {

constexpr double kD = 0.001;

// n cells across (hertz_probe.h), on the CPU; a failed run says why.
HertzResult indent(int n, HertzCase c = {}) {
  c.cells = n;
  c.depth = kD;
  const HertzResult r = hertz_indent(c, "cpu");
  if (!r.ok) qWarning("Hertz n=%d: %s", n, r.why.c_str());
  return r;
}

}  // namespace

class TestHertz : public QObject {
  Q_OBJECT
 private slots:
  // Linear tetrahedra resolve the contact radius a = sqrt(R d) = 3.2 mm with a few
  // elements at these sizes: 10% (the bound) at the finest mesh, and the error
  // must shrink with refinement. Measured at nu 0.45: +66.9, +32.0, +14.0, +5.8% at 12,
  // 20, 28, 36 across (+1.7% at 44, a mesh of 256k tetrahedra that took half of this
  // suite's time for a bound 36 across already meets).
  void matchesHertzAndConverges() {
    // PALPATION_LIGHT_TESTS=1 (the sanitizer build in CI, .ci/run): coarser meshes only;
    // convergence is still asserted, the 10% bound needs the finest.
    const bool light = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0;
    const std::vector<int> sizes = light ? std::vector<int>{8, 12, 20} : std::vector<int>{12, 20, 28, 36};
    double prev = 1e9;
    for (int n : sizes) {
      const HertzResult r = indent(n);
      QVERIFY2(r.ok, r.why.c_str());
      const double ref = r.reference;
      const double err = std::abs(r.force - ref) / ref;
      qInfo("Hertz n=%d (%d tets): d = %.4f mm, F = %.5f N, Hertz %.5f N, error %.1f%%", n, r.tets, r.depth * 1e3, r.force,
            ref, 100 * err);
      QVERIFY(r.depth > 0.95 * kD && r.depth <= kD);
      QVERIFY2(err < prev, "error must shrink with refinement");
      prev = err;
    }
    if (light)
      QSKIP(qPrintable(QString("PALPATION_LIGHT_TESTS: convergence checked on %1-%2 across; the 10% bound against "
                               "Hertz is NOT checked (it needs the 36-across mesh; the finest here is %3% off)")
                           .arg(sizes.front())
                           .arg(sizes.back())
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
    HertzCase c;
    c.nu = nu;
    c.radius = radius;
    c.young = young;
    c.element = Element::NodalPressure;
    // PALPATION_LIGHT_TESTS: 12 and 20 across, refinement asserted, the 5% bound (28 across) not.
    const bool light = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0;
    double errs[2];
    const int sizes[2] = {light ? 12 : 20, light ? 20 : 28};
    for (int k = 0; k < 2; ++k) {
      const HertzResult r = indent(sizes[k], c);
      QVERIFY2(r.ok, r.why.c_str());
      const double ref = r.reference;
      errs[k] = r.error;
      qInfo("nodal pressure, n=%d: F = %.5f N, Hertz %.5f N, error %+.1f%%, CG up to %d iterations a step", sizes[k],
            r.force, ref, 100 * errs[k], r.max_iterations);
    }
    QVERIFY2(std::abs(errs[1]) < std::abs(errs[0]), "error must shrink with refinement");
    if (light)
      QSKIP(qPrintable(QString("PALPATION_LIGHT_TESTS: refinement checked on 12-20 across; the 5% bound (28 across) "
                               "is NOT checked (%1% at 20)").arg(100 * errs[1], 0, 'f', 1)));
    QVERIFY2(std::abs(errs[1]) < 0.05, qPrintable(QString::number(errs[1])));
  }

  // Beside it, the linear element on the same mesh at nu = 0.49 is far off: the locking
  // the nodal-pressure element removes (a test that would pass if the element did not lock
  // is no test of the nodal one either: this shows the scene can tell them apart). The
  // locking only grows on coarser meshes (+41% measured at 28 across), so the sanitizer
  // build's 20 across asserts the same.
  void linearElementLocksAtNu049() {
    HertzCase c;
    c.nu = 0.49;
    const int n = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0 ? 20 : 28;
    const HertzResult r = indent(n, c);
    QVERIFY2(r.ok, r.why.c_str());
    const double err = r.error;
    qInfo("linear, nu 0.49, n=%d: error %+.1f%%", n, 100 * err);
    QVERIFY2(err > 0.15, qPrintable(QString::number(err)));
  }
};

QTEST_APPLESS_MAIN(TestHertz)
#include "tst_hertz.moc"
