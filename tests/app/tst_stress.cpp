// Numerical stability: a subset of the `palpation stress` matrix (app/cli/stress.h)
// asserting its properties, and the divergence guard of design.md section 7 (NaN or an
// energy blow-up is detected, the body reset to rest, the event logged).
#include <QtTest>

#include <cmath>

#include "fault_backend.h"
#include "mesh_gmsh.h"
#include "simulation.h"
#include "cli/stress.h"

using namespace palpation;

namespace {

const app::cli::StressCase& find_case(const std::vector<app::cli::StressCase>& cs, const std::string& name) {
  for (const auto& c : cs)
    if (c.name == name) return c;
  throw std::runtime_error("no stress case " + name);
}

// A 4 x 4 x 2 cm box, one finger pressing 4 mm.
sim::Scenario small_box() {
  sim::Scenario s;
  s.source = "tst_stress";
  s.patient.phantom = "box";
  s.patient.size = Eigen::Vector3d(0.04, 0.04, 0.02);
  s.patient.edge = 0.008;
  s.backend = "cpu";
  s.params.solver.threads = 1;
  sim::FingerPath f;
  f.keys = {{0, 0, 0, 0.03}, {0.05, 0, 0, 0.024}};
  s.fingers = {f};
  s.duration = 0.1;
  return s;
}

double max_displacement(sim::Simulation& sim) {
  std::vector<double> x;
  sim.backend().positions(x);
  double d = 0;
  for (int i = 0; i < sim.model().num_nodes(); ++i)
    d = std::max(d, (Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - sim.model().rest[i]).norm());
  return d;
}

}  // namespace

class TestStress : public QObject {
  Q_OBJECT
 private slots:
  // Each case: finite, bounded, the device within its limit, back at rest, CG converged.
  void matrixSubset_data() {
    QTest::addColumn<QString>("name");
    for (const char* n : {"dt-50ms", "contrast-30x", "contrast-1000x", "poisson-0.499", "jump-through", "squeeze-5",
                          "inverted-order", "sliver-2%", "sliver-0.1%", "held-1%-coarse"})
      QTest::newRow(n) << QString(n);
  }
  void matrixSubset() {
    QFETCH(QString, name);
    const auto cases = app::cli::stress_cases(true);
    const app::cli::StressResult r = app::cli::run_stress_case(find_case(cases, name.toStdString()), "cpu");
    QString why;
    for (const auto& f : r.failures) why += QString::fromStdString(f) + "; ";
    QVERIFY2(!r.skipped, r.skip_reason.c_str());
    QVERIFY2(r.pass, qPrintable(why));
    QCOMPARE(r.divergences, 0);
    QCOMPARE(r.device_nonfinite, std::uint64_t(0));
    QCOMPARE(r.device_over_limit, std::uint64_t(0));
    QVERIFY(r.max_device_force <= 4.0);
    QVERIFY(r.max_raw_force > 0.05);  // the fingers did touch the body
    QVERIFY(r.rest_displacement >= 0 && r.rest_displacement <= std::max(5e-4, 0.05 * r.max_displacement));
    QCOMPARE(r.cg_unconverged, 0);
  }

  // The hard cases need more CG iterations than the cap: the rescue takes them to the
  // tolerance (matrixSubset asserts that), and the steps that went past the cap are counted.
  void hardCasesAreRescued() {
    const auto cases = app::cli::stress_cases(true);
    for (const char* n : {"contrast-1000x", "sliver-0.1%"}) {
      const app::cli::StressResult r = app::cli::run_stress_case(find_case(cases, n), "cpu");
      QVERIFY2(r.pass && !r.skipped, n);
      QVERIFY2(r.cg_max_iterations > find_case(cases, n).scenario.params.solver.cg_max_iterations || r.cg_rescued == 0, n);
    }
    const app::cli::StressResult m = app::cli::run_stress_case(find_case(cases, "sliver-0.1%"), "cpu");
    QVERIFY2(m.cg_rescued > 0, "the 0.1 % slivers need more than the cap of 500 iterations");
    QVERIFY(m.min_quality > sim::kMinTetQuality && m.min_quality < 0.01);
  }

  // Beyond the measured bounds the input is refused with one line naming the field:
  // stiffness contrast above 10,000x, elements below quality 0.001 in a mesh file
  // (docs/stability.md).
  void outOfBoundsIsRefused() {
    const auto cases = app::cli::stress_cases(true);
    app::cli::StressCase stiff = find_case(cases, "contrast-10000x");
    stiff.scenario.inclusions[0].young_modulus *= 3;
    const app::cli::StressResult c = app::cli::run_stress_case(stiff, "cpu");
    QVERIFY2(c.skipped && c.steps == 0, c.skip_reason.c_str());
    QVERIFY(c.skip_reason.find('\n') == std::string::npos);
    QVERIFY2(c.skip_reason.find("inclusions[0].young_modulus: must be within 10000x") != std::string::npos,
             c.skip_reason.c_str());
    app::cli::StressCase flat = find_case(cases, "sliver-0.1%");
    flat.mesh_edit = [](sim::TetMesh& m) {  // the top cell layer flattened to 0.02 % of its 6 mm
      for (auto& p : m.nodes)
        if (std::abs(p.z() - 0.024) < 1e-9) p.z() = 0.03 - 0.0002 * 0.006;
    };
    const app::cli::StressResult m = app::cli::run_stress_case(flat, "cpu");
    QVERIFY2(m.skipped && m.steps == 0, m.skip_reason.c_str());
    QVERIFY(m.skip_reason.find('\n') == std::string::npos);
    QVERIFY2(m.skip_reason.find("patient.mesh") != std::string::npos && m.skip_reason.find("sliver") != std::string::npos,
             m.skip_reason.c_str());
    QVERIFY(m.min_quality > 0 && m.min_quality < sim::kMinTetQuality);
  }

  // A NaN from the backend: detected, body back at rest, outputs zeroed, event counted and
  // logged; the next steps run normally.
  void divergenceNaNResetsToRest() {
    sim::Scenario s = small_box();
    std::vector<std::string> log;
    sim::Simulation sim(s, [&log](const std::string& m) { log.push_back(m); });
    sim.replace_backend(std::make_unique<test::FaultBackend>(
        sim::make_backend(sim::BackendKind::Cpu, sim.model(), s.params), test::FaultBackend::Fault::NaN, 60, "cpu"));
    sim.reset();
    for (int k = 0; k < 60; ++k) QVERIFY(sim.step().finite);
    QVERIFY(max_displacement(sim) > 1e-4);  // pressed in
    const sim::StepStats st = sim.step();
    QVERIFY(!st.finite);
    QCOMPARE(sim.divergences(), 1);
    QVERIFY(sim.last_check().diverged);
    QVERIFY(sim.last_check().reason.find("non-finite") != std::string::npos);
    QCOMPARE(max_displacement(sim), 0.0);
    for (const auto& o : sim.outputs()) QVERIFY(o.force.allFinite() && o.force.norm() == 0.0);
    bool logged = false;
    for (const auto& m : log) logged = logged || m.find("divergence at t") != std::string::npos;
    QVERIFY(logged);
    for (int k = 0; k < 20; ++k) QVERIFY(sim.step().finite);
    QCOMPARE(sim.divergences(), 1);
  }

  // An energy blow-up (a node far faster than any palpation) is divergence too.
  void divergenceBlowUpResetsToRest() {
    sim::Scenario s = small_box();
    sim::Simulation sim(s);
    sim.replace_backend(std::make_unique<test::FaultBackend>(
        sim::make_backend(sim::BackendKind::Cpu, sim.model(), s.params), test::FaultBackend::Fault::BlowUp, 70, "cpu"));
    sim.reset();
    for (int k = 0; k < 70; ++k) QVERIFY(sim.step().finite);
    QVERIFY(!sim.step().finite);
    QCOMPARE(sim.divergences(), 1);
    QVERIFY(sim.last_check().reason.find("node speed") != std::string::npos);
    QCOMPARE(max_displacement(sim), 0.0);
  }

  // A backend error mid-run (a CUDA error): the simulation continues on the CPU.
  void backendErrorFallsBackToCpu() {
    sim::Scenario s = small_box();
    std::vector<std::string> log;
    sim::Simulation sim(s, [&log](const std::string& m) { log.push_back(m); });
    sim.replace_backend(std::make_unique<test::FaultBackend>(
        sim::make_backend(sim::BackendKind::Cpu, sim.model(), s.params), test::FaultBackend::Fault::Throw, 30));
    sim.reset();
    for (int k = 0; k < 80; ++k) QVERIFY(sim.step().finite);
    QCOMPARE(sim.fallbacks(), 1);
    QCOMPARE(sim.backend().name(), std::string("cpu"));
    QVERIFY(sim.backend_reason().find("injected CUDA error") != std::string::npos);
    QVERIFY(sim.outputs()[0].force.norm() > 0.01);  // still pressing, now on the CPU
    // The CPU backend failing has nothing to fall back to: the error propagates.
    QVERIFY(!sim.fall_back_to_cpu("again"));
  }

  // An error in a case is that case's failure with its message, never a skip or a pass
  // (a CUDA error must not count as passed): an injected backend error that cannot fall
  // back (the backend is named "cpu") on a box case and on a breast case. The breast case
  // may be skipped only where its mesh is unavailable (no Gmsh, nothing cached), saying so.
  void errorInACaseIsAFailure_data() {
    QTest::addColumn<QString>("only");
    QTest::newRow("box") << "dt-1ms";
    QTest::newRow("breast") << "breast-tumour-10x";
  }
  void errorInACaseIsAFailure() {
    QFETCH(QString, only);
    app::cli::StressOptions opt;
    opt.quick = true;
    opt.only = only.toStdString();
    opt.backends = {"cpu"};
    opt.make_backend = [](const std::string&, const sim::Model& m, const sim::SimParams& p) -> std::unique_ptr<sim::Backend> {
      return std::make_unique<test::FaultBackend>(sim::make_backend(sim::BackendKind::Cpu, m, p),
                                                  test::FaultBackend::Fault::Throw, 5, "cpu");
    };
    const auto rs = app::cli::run_stress(opt);
    QCOMPARE(rs.size(), std::size_t(1));
    const auto& r = rs.front();
    if (r.skipped) {
      QVERIFY2(r.skip_reason.rfind("mesh unavailable: ", 0) == 0, r.skip_reason.c_str());
      QVERIFY(!sim::gmsh_available());
      QSKIP(qPrintable(QString::fromStdString("the breast case is skipped here: " + r.skip_reason)));
    }
    QVERIFY(!r.pass);
    QCOMPARE(r.failures.size(), std::size_t(1));
    QVERIFY2(r.failures[0].find("error: ") == 0 && r.failures[0].find("injected CUDA error") != std::string::npos,
             r.failures[0].c_str());
    const auto j = app::cli::stress_json(rs, opt, 0);
    QCOMPARE(j["failed"].get<int>(), 1);
    QCOMPARE(j["skipped"].get<int>(), 0);
    QCOMPARE(j["all_pass"].get<bool>(), false);
    QVERIFY(app::cli::stress_markdown(rs, opt, 0).find("**FAIL**") != std::string::npos);
  }

  // A backend error the simulation survives by falling back to the CPU: the case ran,
  // but not on the backend under test: a failure naming the error.
  void fallbackToCpuIsAFailure() {
    const auto cases = app::cli::stress_cases(true);
    const app::cli::StressResult r = app::cli::run_stress_case(
        find_case(cases, "dt-1ms"), "cuda", [](const std::string&, const sim::Model& m, const sim::SimParams& p) {
          return std::make_unique<test::FaultBackend>(sim::make_backend(sim::BackendKind::Cpu, m, p),
                                                      test::FaultBackend::Fault::Throw, 5, "cuda");
        });
    QVERIFY(!r.skipped);
    QVERIFY(!r.pass);
    QCOMPARE(r.steps, 600);  // the run went on (on the CPU) to its end
    bool named = false;
    for (const auto& f : r.failures)
      named = named || (f.find("backend: cuda failed") == 0 && f.find("injected CUDA error") != std::string::npos);
    QVERIFY(named);
  }

  // Divergence limits: a stable press stays far inside them.
  void stablePressIsFarFromTheLimits() {
    sim::Scenario s = small_box();
    sim::Simulation sim(s);
    double vmax = 0, dmax = 0;
    for (int k = 0; k < 100; ++k) {
      QVERIFY(sim.step().finite);
      vmax = std::max(vmax, sim.last_check().max_speed);
      dmax = std::max(dmax, sim.last_check().max_displacement);
    }
    QVERIFY(vmax < 0.1 * sim.divergence_limits().max_speed);
    QVERIFY(dmax > 1e-3 && dmax < 0.02);
    QCOMPARE(sim.divergences(), 0);
  }
};

QTEST_GUILESS_MAIN(TestStress)
#include "tst_stress.moc"
