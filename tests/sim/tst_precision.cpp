// Float agrees with double on the paper sweep (first pushes, coarse mesh).
#include <QtTest>

#include "backend.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation::sim;

namespace {

std::vector<double> force_series(Simulation& s, int steps) {
  std::vector<double> f;
  for (int k = 0; k < steps; ++k) {
    const StepStats st = s.step();
    if (!st.finite) return {};
    for (int c = 0; c < 3; ++c) f.push_back(s.outputs()[0].force[c]);
  }
  return f;
}

double rel_l2(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += (a[i] - b[i]) * (a[i] - b[i]);
    den += b[i] * b[i];
  }
  return std::sqrt(num / den);
}

}  // namespace

class TestPrecision : public QObject {
  Q_OBJECT
 private slots:
  // Both solved to a relative residual of 1e-5 (float's unit round-off is 6e-8; the
  // system's condition number at dt = 1 ms is ~1e3, so float solves are good to ~1e-4).
  // The force series over 600 steps (1.5 pushes) must agree to 5e-3 relative L2: the
  // difference is then below a haptic device's force resolution (~1% of full scale).
  void floatAgreesWithDouble() {
    Scenario sc = builtin_scenario("paper-sweep");
    sc.patient.resolution = "coarse";
    sc.patient.edge = *resolution_edge("breast", "coarse");
    sc.backend = "cpu";
    sc.params.solver.cg_tolerance = 1e-5;
    sc.params.solver.cg_max_iterations = 1000;
    const Model model = build_scenario_model(sc, patient_mesh(sc));
    Simulation d(sc, model);
    sc.params.solver.precision = Precision::Float;
    Simulation f(sc, model);
    QCOMPARE(f.backend().precision(), Precision::Float);
    const auto fd = force_series(d, 600), ff = force_series(f, 600);
    QVERIFY(!fd.empty() && !ff.empty());
    const double err = rel_l2(ff, fd);
    qInfo("float vs double force series: relative L2 %.2e", err);
    QVERIFY2(err < 5e-3, qPrintable(QString::number(err)));
    std::vector<double> xd, xf;
    d.backend().positions(xd);
    f.backend().positions(xf);
    double num = 0, den = 0;
    for (int i = 0; i < model.num_nodes(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double ud = xd[3 * i + c] - model.rest[i][c], uf = xf[3 * i + c] - model.rest[i][c];
        num += (ud - uf) * (ud - uf);
        den += ud * ud;
      }
    qInfo("float vs double displacement: relative L2 %.2e", std::sqrt(num / den));
    QVERIFY(std::sqrt(num / den) < 5e-3);
  }
};

QTEST_APPLESS_MAIN(TestPrecision)
#include "tst_precision.moc"
