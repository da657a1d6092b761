// The paper's Fig. 6 experiment: the index finger pushes and releases while sweeping
// along x over the tumour (x = 0.125 m), left to right and back, twice, with and without
// the tumour (same mesh).
#include <QtTest>

#include <cstdlib>
#include <thread>

#include "live/headless_run.h"
#include "phantom.h"
#include "scenario.h"
#include "cli/sweep_analysis.h"

using namespace palpation;

namespace {

// PALPATION_LIGHT_TESTS (the sanitizer stage of .ci/run): the coarse mesh and the first
// pass only (6 s).
// Read as tst_hertz and tst_cantilever read it.
bool light_tests() { return qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0; }

sim::Scenario sweep(const std::string& name) {
  sim::Scenario s = sim::builtin_scenario(name);
  // A 7.5 mm edge by default (3,417 nodes, 16,821 tetrahedra: between "coarse" and
  // "paper"); PALPATION_SWEEP_RESOLUTION names another level (paper: the paper's mesh).
  // The first two passes (12 s of the 24: left to right and back), as the sweep with the
  // nodal-pressure element takes about 31 ms a step on CI's kind of VM (one core each):
  // two 12 s runs take about 6 minutes, the whole 24 s sweep took 19 (`palpation run`
  // and tools/gpu-check.sh's sweep stage run all four passes).
  const bool is_light = light_tests();
  const char* env = std::getenv("PALPATION_SWEEP_RESOLUTION");
  if (env && *env) {
    s.patient.resolution = env;
    s.patient.edge = *sim::resolution_edge("breast", s.patient.resolution);
  } else if (is_light) {
    s.patient.resolution = "coarse";
    s.patient.edge = *sim::resolution_edge("breast", "coarse");
  } else {
    s.patient.resolution.clear();  // a numeric edge, as the scenario format keeps it
    s.patient.edge = 0.0075;
  }
  s.backend = "cpu";
  s.params.solver.threads = 1;  // the two runs go in parallel, one core each
  s.duration = is_light ? 6.0 : 12.0;  // one pass takes 6 s
  return s;
}

}  // namespace

class TestPaperSweep : public QObject {
  Q_OBJECT
 private slots:
  // Asserted on the 7.5 mm mesh: the sweep stays finite with bounded forces, both
  // passes are found, each has its largest push within 1 cm of the tumour (the
  // issue's criterion), and the pushes over the tumour (within 1.2 cm of x = 0.125 m)
  // are at least 15% stronger with it than without. Measured with the nodal-pressure
  // element (this VM, 2026-11-29): both passes peak 0.2 mm from the tumour, ratio 1.17,
  // 431 s for the two runs side by side. Earlier, with the linear element
  // (docs/benchmarks.md, "Paper sweep"): on this mesh all 4 passes peaked 4.2-4.6 mm from
  // the tumour, ratio 1.25; on the paper mesh all 4 within 4 mm, ratio 1.25-1.32; on the
  // coarse mesh only 2 of 4
  // (the others 1.2 cm off: the tumour spans two or three coarse elements), which is why
  // CI does not sweep the coarse mesh. Pushes are 4 mm apart, so a peak one push further
  // off (Gmsh's meshes differ a little from run to run) still passes.
  void tumourRaisesTheForceOverIt() {
    const sim::Scenario with = sweep("paper-sweep"), without = sweep("paper-sweep-no-tumour");
    sim::patient_mesh(with);  // mesh once (cached) before the two runs share it
    app::live::RunResult rt, rn;
    std::thread other([&] { rn = app::live::run_headless(without, {}); });
    rt = app::live::run_headless(with, {});
    other.join();
    QVERIFY(rt.summary["finite"].get<bool>() && rn.summary["finite"].get<bool>());
    // A fingertip pressed 1.8 cm into 19 kPa tissue: a few newtons (measured 2-6 N from
    // the fine to the coarse mesh); 20 N would mean the contact went unstable.
    QVERIFY(rt.summary["max_force_n"].get<double>() < 20.0);
    // Step times are quoted without the first kWarmupSteps solved steps, as the bench does.
    const std::vector<double> timed = app::live::after_warmup(rt.step_ms);
    QVERIFY(rt.step_ms.size() > app::live::kWarmupSteps);
    QCOMPARE(timed.size(), rt.step_ms.size() - app::live::kWarmupSteps);
    QCOMPARE(timed.front(), rt.step_ms[app::live::kWarmupSteps]);
    QCOMPARE(rt.summary["warmup_steps"].get<std::size_t>(), app::live::kWarmupSteps);
    QCOMPARE(rt.summary["step_ms_median"].get<double>(), app::live::percentile(timed, 50));
    const std::vector<double> few(rt.step_ms.begin(), rt.step_ms.begin() + 10);
    QCOMPARE(app::live::after_warmup(few), few);  // a run shorter than the warm-up keeps all
    const app::cli::SweepAnalysis at = app::cli::analyze_sweep(rt.samples), an = app::cli::analyze_sweep(rn.samples);
    const bool light = light_tests();
    QCOMPARE(int(at.passes.size()), light ? 1 : 2);
    int within = 0;
    for (const auto& p : at.passes) {
      qInfo("pass %d (%s): largest push peak %.3f N at x = %.4f m (%.1f mm from the tumour)", p.pass,
            p.direction > 0 ? "left to right" : "right to left", p.fz, p.x, 1e3 * std::abs(p.x - 0.125));
      if (std::abs(p.x - 0.125) <= 0.01) ++within;
    }
    qInfo("passes peaking within 1 cm of the tumour: %d of %d", within, int(at.passes.size()));
    if (!light) QVERIFY2(within == 2, qPrintable(QString::number(within)));
    auto mean_over_tumour = [](const app::cli::SweepAnalysis& a) {
      double sum = 0;
      int n = 0;
      for (const auto& q : a.pushes)
        if (std::abs(q.x - 0.125) <= 0.012 && q.fz > 1.0) {  // whole pushes, not fragments
          sum += q.fz;
          ++n;
        }
      return n ? sum / n : 0.0;
    };
    const double ft = mean_over_tumour(at), fn = mean_over_tumour(an);
    qInfo("mean push peak within 1.2 cm of the tumour: %.3f N with it, %.3f N without: ratio %.3f", ft, fn, ft / fn);
    QVERIFY(fn > 1.0);
    QVERIFY2(ft / fn > 1.15, qPrintable(QString::number(ft / fn)));
    if (light)
      QSKIP(qPrintable(QString("PALPATION_LIGHT_TESTS: the first pass on the coarse mesh only; the count of 2 passes "
                               "and both peaking within 1 cm of the tumour are NOT checked (%1 of %2 here)")
                           .arg(within)
                           .arg(int(at.passes.size()))));
  }
};

QTEST_APPLESS_MAIN(TestPaperSweep)
#include "tst_paper_sweep.moc"
