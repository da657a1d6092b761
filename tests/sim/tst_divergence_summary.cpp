// The divergence guard's summary formed within the step (StepStats::max_speed,
// max_displacement, kinetic_energy): the same figures as computed from the state read
// back, on the CPU and the CUDA backend, and a session whose guard never reads the state
// back (the read-back cost a step 0.3-0.4 ms on the GPU). The CUDA row skips with a
// visible reason where no GPU is usable.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "backend.h"
#include "box_scenario.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation::sim;

namespace {

constexpr double kTop = 0.02;
constexpr double kR = 0.008;

Scenario box(const std::string& backend) {
  Scenario s = box_scenario("tst_divergence_summary", Eigen::Vector3d(0.04, 0.04, kTop), 0.005, backend);
  s.params.solver.cg_tolerance = 1e-8;
  s.params.solver.cg_max_iterations = 2000;
  return s;
}

struct Summary {
  double speed = 0, displacement = 0, energy = 0;
};

Summary read_back(Simulation& sim) {
  std::vector<double> x, v;
  sim.backend().positions(x);
  sim.backend().velocities(v);
  const Model& m = sim.model();
  Summary s;
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]), vi(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    s.speed = std::max(s.speed, vi.norm());
    s.displacement = std::max(s.displacement, (xi - m.rest[i]).norm());
    s.energy += 0.5 * m.mass[i] * vi.squaredNorm();
  }
  return s;
}

// |a - b| within a relative 1e-9 of b (or 1e-15 absolute near zero): the same sums in
// double, in another order on the GPU.
bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b) + 1e-15; }

}  // namespace

class TestDivergenceSummary : public QObject {
  Q_OBJECT
 private slots:
  void summaryMatchesTheState_data() {
    QTest::addColumn<QString>("backend");
    QTest::newRow("cpu") << "cpu";
    QTest::newRow("cuda") << "cuda";
  }

  void summaryMatchesTheState() {
    QFETCH(QString, backend);
    std::string why;
    if (backend != "cpu" && !cuda_available(&why))
      QSKIP(("no usable GPU (" + why + "): the CUDA step's summary is not checked here").c_str());
    const Scenario s = box(backend.toStdString());
    Simulation sim(s, build_scenario_model(s, patient_mesh(s)));
    std::vector<FingerInput> in(1);
    std::vector<FingerOutput> out(1);
    in[0].radius = kR;
    int compared = 0, skipped = 0;
    double largest = 0;
    // Press 4 mm over 50 ms, lift, and let the body come to rest (then steps are skipped).
    for (int k = 1; k <= 1500; ++k) {
      const double t = k * 1e-3;
      const double depth = t < 0.05 ? 0.08 * t : (t < 0.1 ? 0.004 : -0.02);
      in[0].position = Eigen::Vector3d(0.002, -0.001, kTop + kR - depth);
      const auto o = sim.advance(in, out, 1e-3);
      QVERIFY2(o.ok, qPrintable(QString("step %1").arg(k)));
      if (!o.stats.solved) {
        ++skipped;
        continue;
      }
      QVERIFY2(o.stats.max_speed >= 0 && o.stats.max_displacement >= 0 && o.stats.kinetic_energy >= 0,
               "a solved step forms the summary");
      const Summary r = read_back(sim);
      const auto& c = sim.last_check();
      QVERIFY2(same(c.max_speed, r.speed), qPrintable(QString("step %1: speed %2 vs %3").arg(k).arg(c.max_speed).arg(r.speed)));
      QVERIFY2(same(c.max_displacement, r.displacement),
               qPrintable(QString("step %1: displacement %2 vs %3").arg(k).arg(c.max_displacement).arg(r.displacement)));
      QVERIFY2(same(c.kinetic_energy, r.energy),
               qPrintable(QString("step %1: energy %2 vs %3").arg(k).arg(c.kinetic_energy).arg(r.energy)));
      largest = std::max(largest, r.displacement);
      ++compared;
    }
    qInfo("%s: %d solved steps compared (largest displacement %.2f mm), %d skipped at rest, %d read-backs by the guard",
          qPrintable(backend), compared, largest * 1e3, skipped, sim.readbacks());
    QVERIFY(largest > 1e-3);  // the press did move the body
    QVERIFY(skipped > 0);     // and it came to rest
    QCOMPARE(sim.readbacks(), 0);
  }

  // A state the step reports as blown up is caught without a read-back and reset to rest.
  void reportedBlowUpIsCaught() {
    const Scenario s = box("cpu");
    Simulation sim(s, build_scenario_model(s, patient_mesh(s)));
    StepStats st;
    st.solved = true;
    st.max_speed = 1e3;
    st.max_displacement = 0;
    st.kinetic_energy = 1;
    const auto c = sim.check_divergence(st, {});
    QVERIFY(c.diverged);
    QVERIFY2(c.reason.find("node speed") != std::string::npos, c.reason.c_str());
    st.max_speed = INFINITY;
    QVERIFY(sim.check_divergence(st, {}).reason.find("non-finite") != std::string::npos);
    QCOMPARE(sim.readbacks(), 0);
  }
};

QTEST_APPLESS_MAIN(TestDivergenceSummary)
#include "tst_divergence_summary.moc"
