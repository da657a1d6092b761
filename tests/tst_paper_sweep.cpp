// The paper's Fig. 6 experiment: the index finger pushes and releases while sweeping
// along x over the tumour (x = 0.125 m), left to right and back, twice. The push with
// the highest force in each pass must lie within 1 cm of the tumour, and the same sweep
// without the tumour must give a clearly lower force there.
#include <QtTest>

#include <cstdlib>
#include <thread>

#include "headless_run.h"
#include "phantom.h"
#include "scenario.h"
#include "sweep_analysis.h"

using namespace palpation;

namespace {

sim::Scenario sweep(const std::string& name) {
  sim::Scenario s = sim::builtin_scenario(name);
  // The coarse breast by default (CI has two cores); PALPATION_SWEEP_RESOLUTION=paper
  // runs the paper's mesh size.
  const char* env = std::getenv("PALPATION_SWEEP_RESOLUTION");
  s.patient.resolution = env && *env ? env : "coarse";
  s.patient.edge = *sim::resolution_edge("breast", s.patient.resolution);
  s.backend = "cpu";
  s.params.solver.threads = 1;  // the two runs go in parallel, one core each
  return s;
}

}  // namespace

class TestPaperSweep : public QObject {
  Q_OBJECT
 private slots:
  void tumourIsWhereTheForcePeaks() {
    const sim::Scenario with = sweep("paper-sweep"), without = sweep("paper-sweep-no-tumour");
    sim::patient_mesh(with);  // mesh once (cached) before the two runs share it
    app::RunResult rt, rn;
    std::thread other([&] { rn = app::run_headless(without, {}); });
    rt = app::run_headless(with, {});
    other.join();
    QVERIFY(rt.summary["finite"].get<bool>() && rn.summary["finite"].get<bool>());
    const app::SweepAnalysis at = app::analyze_sweep(rt.samples), an = app::analyze_sweep(rn.samples);
    QCOMPARE(int(at.passes.size()), 4);
    for (const auto& p : at.passes) {
      qInfo("pass %d (%s): largest push peak %.3f N at x = %.4f m", p.pass, p.direction > 0 ? "left to right" : "right to left",
            p.fz, p.x);
      QVERIFY2(std::abs(p.x - 0.125) <= 0.01, qPrintable(QString("pass %1 peaks at x = %2").arg(p.pass).arg(p.x)));
    }
    // The push nearest the tumour, with and without it. A force difference of about 10%
    // is what a fingertip just notices (Weber fraction for force); ask for more.
    const auto ft = app::peaks_near(at, 0.125), fn = app::peaks_near(an, 0.125);
    QCOMPARE(ft.size(), fn.size());
    for (std::size_t i = 0; i < ft.size(); ++i) {
      const double ratio = ft[i] / fn[i];
      qInfo("pass %zu: push nearest x = 0.125: %.3f N with the tumour, %.3f N without: ratio %.3f", i, ft[i], fn[i], ratio);
      QVERIFY2(ratio > 1.1, qPrintable(QString::number(ratio)));
    }
  }
};

QTEST_APPLESS_MAIN(TestPaperSweep)
#include "tst_paper_sweep.moc"
