// GPU against CPU. Where no GPU is usable (CI) the GPU comparisons skip with a
// visible QSKIP naming the reason, and what can be checked without one is checked: asking
// for cuda is a clear error and auto falls back to the CPU saying why. The full check
// (paper sweep and Hertz, 1,000 steps) is `palpation check-backends`, run on the GPU
// machine by tools/gpu-check.sh; this suite is its small, Qt-side twin.
#include <QtTest>

#include "box_scenario.h"
#include "relative_error.h"
#include "scoped_env.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <string>

#include "backend.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation::sim;

namespace {

struct Trace {
  std::vector<double> force;  // (steps x fingers x 3)
  std::vector<double> x;      // final positions
  long iterations = 0;        // CG iterations over all steps
  Backend::MultigridCounts multigrid;  // the backend's multigrid builds at the end
};

Trace run(const Scenario& s, const Model& m, const std::string& backend, int steps) {
  auto b = make_named_backend(backend, m, s.params);
  const int nf = static_cast<int>(s.fingers.size());
  std::vector<FingerInput> in(nf);
  std::vector<FingerOutput> out(nf);
  for (int f = 0; f < nf; ++f) in[f].radius = s.fingers[f].radius;
  Trace t;
  for (int k = 1; k <= steps; ++k) {
    for (int f = 0; f < nf; ++f) s.fingers[f].sample(k * s.params.solver.dt, in[f].position, in[f].velocity);
    const StepStats st = b->step(in, out);
    if (!st.finite) throw std::runtime_error("non-finite step");
    t.iterations += st.cg_iterations;
    for (int f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) t.force.push_back(out[f].force[c]);
  }
  b->positions(t.x);
  t.multigrid = b->multigrid_counts();
  return t;
}

// A knob of sim/cuda/tuning.h given as "NAME=value" (empty: none), set until the guard goes.
auto set_tuning(const QString& tuning) {
  const QByteArray name = tuning.section('=', 0, 0).toUtf8();
  return scoped_env({{name.constData(), tuning.section('=', 1).toUtf8()}});
}

// Hertz indentation on the coarse box: no contact for 500 steps (the rest path), then
// pressing: 700 steps cover both.
Scenario hertz_coarse() {
  Scenario s = hertz_coarse_box(1e-10);
  s.params.solver.corotation_tolerance = 0;  // every element every step on the CPU, as on the GPU
  return s;
}

// On a crash, the raw stack on stderr before QtTest's own report: the GPU machine that
// runs this suite has no debugger, and `addr2line -e` on the unstripped build maps the
// offsets printed.
struct sigaction g_qt_segv;
void print_stack(int sig, siginfo_t* info, void* ctx) {
  void* frames[64];
  backtrace_symbols_fd(frames, backtrace(frames, 64), STDERR_FILENO);
  if ((g_qt_segv.sa_flags & SA_SIGINFO) && g_qt_segv.sa_sigaction) {
    g_qt_segv.sa_sigaction(sig, info, ctx);
  } else if (g_qt_segv.sa_handler != SIG_DFL && g_qt_segv.sa_handler != SIG_IGN) {
    g_qt_segv.sa_handler(sig);
  }
  signal(sig, SIG_DFL);
  raise(sig);
}

}  // namespace

class TestBackendAgreement : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    void* warm[1];
    backtrace(warm, 1);  // loads the unwinder now, not inside the handler
    struct sigaction sa {};
    sa.sa_sigaction = print_stack;
    sa.sa_flags = SA_SIGINFO;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGSEGV, &sa, &g_qt_segv);
  }

  void cudaWithoutGpuIsAClearError() {
    std::string why;
    if (cuda_available(&why)) QSKIP("a GPU is usable here: nothing to check about its absence");
    const Scenario s = hertz_coarse();
    const Model m = build_scenario_model(s, patient_mesh(s));
    try {
      make_backend(BackendKind::Cuda, m, s.params);
      QFAIL("solver.backend cuda without a GPU must throw");
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      QVERIFY2(what.find("cuda") != std::string::npos, what.c_str());
    }
    std::string reason;
    auto b = make_backend(BackendKind::Auto, m, s.params, &reason);
    QCOMPARE(QString::fromStdString(b->name()), QString("cpu"));
    QVERIFY2(reason.find("cpu (") == 0, reason.c_str());  // says why: "cpu (<reason>)"
  }

  void autoPicksCudaWithGpu() {
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): the CUDA backend is not compared here").c_str());
    const Scenario s = hertz_coarse();
    const Model m = build_scenario_model(s, patient_mesh(s));
    std::string reason;
    auto b = make_backend(BackendKind::Auto, m, s.params, &reason);
    qInfo("auto picked %s on %s", b->name().c_str(), b->device_name().c_str());
    QCOMPARE(QString::fromStdString(b->name()), QString("cuda"));
  }

  // The CPU backend's kept stiffness (corotation_tolerance > 0: an element's rotation is
  // re-extracted when its F moved more than the tolerance, its blocks in K re-rotated
  // when that rotation moved more than it) against re-assembling every element every step
  // (tolerance 0, the GPU's arithmetic): the first push of the coarse paper sweep, where
  // the whole dome strains and rotates. A rotation off by at most tol changes each
  // element's force and the implicit step by C * tol. C depends on the mesh: Gmsh's mesh of
  // the same dome differs between CPUs, and the error at the default 1e-3 measured 1.1e-4
  // on one machine's mesh and 1.1e-3 on another's. The bound is C <= 5 at 1e-3 (a force
  // error below 0.5 %, half what the capped real-time CG below is allowed), and at 1e-5
  // the error must fall at least a hundredfold (measured 1e-8: the knob must work).
  void keptStiffnessAgreesWithFullReassembly() {
    Scenario s = builtin_scenario("paper-sweep");
    s.patient.resolution = "coarse";
    s.patient.edge = *resolution_edge("breast", "coarse");
    s.params.solver.precision = Precision::Double;
    s.params.solver.cg_tolerance = 1e-10;  // the solver's own error out of the comparison
    s.params.solver.cg_max_iterations = 5000;
    const Model m = build_scenario_model(s, patient_mesh(s));
    const int steps = 500;  // the fingertip reaches the dome at ~0.1 s and pushes 1.8 cm
    s.params.solver.corotation_tolerance = 0;
    const Trace full = run(s, m, "cpu", steps);
    s.params.solver.corotation_tolerance = 1e-3;
    const Trace kept3 = run(s, m, "cpu", steps);
    s.params.solver.corotation_tolerance = 1e-5;
    const Trace kept5 = run(s, m, "cpu", steps);
    // Under a force-error target the tolerance follows it (params.h,
    // resolve_corotation_tolerance): at 1 %, 3e-3 however the scenario set it. The CG is
    // still run to 1e-10 here (the backend alone has no controller), so what differs from
    // the full run is the kept rotations' share of the target, which must stay within the
    // third of it that kCorotationPerForceError allots (C <= 1.1 seen; measured 7e-4).
    s.params.solver.corotation_tolerance = 1e-3;
    s.params.solver.force_error = 0.01;
    {
      const auto b = make_named_backend("cpu", m, s.params);
      QCOMPARE(b->params().solver.corotation_tolerance, kCorotationPerForceError * 0.01);
      // Parameters read back and passed again with the target off: the tolerance first
      // given comes back, not the one the target had resolved.
      SimParams q = b->params();
      q.solver.force_error = 0;
      b->set_params(q);
      QCOMPARE(b->params().solver.corotation_tolerance, 1e-3);
      q = b->params();
      q.solver.force_error = 0.02;
      b->set_params(q);
      QCOMPARE(b->params().solver.corotation_tolerance, kCorotationPerForceError * 0.02);
    }
    const Trace held = run(s, m, "cpu", steps);
    double fmax = 0;
    for (double f : full.force) fmax = std::max(fmax, std::abs(f));
    const double e3 = relative_error(kept3.force, full.force), e5 = relative_error(kept5.force, full.force);
    const double eh = relative_error(held.force, full.force);
    qInfo("peak force component %.2f N; force error at tolerance 1e-3: %.2e, at 1e-5: %.2e, at the 1 %% target's %.0e: %.2e",
          fmax, e3, e5, kCorotationPerForceError * 0.01, eh);
    QVERIFY2(fmax > 1.0, "the fingertip never pressed: nothing compared");
    QVERIFY2(e3 <= 5e-3, qPrintable(QString("force error %1 at 1e-3").arg(e3)));
    QVERIFY2(e5 <= 1e-2 * e3 && e5 <= 1e-5, qPrintable(QString("force error %1 at 1e-5").arg(e5)));
    QVERIFY2(eh <= 0.01 / 3, qPrintable(QString("force error %1 at the 1 % target's tolerance").arg(eh)));
    QVERIFY2(relative_error(kept3.x, full.x) <= 5e-3, "positions differ");
  }

  // Too few CG iterations for the tolerance (a real-time budget: 5 per step on the coarse
  // sweep) must cost accuracy, never stability. The extrapolated warm start diverged here
  // (NaN within 1,500 steps) while it was also applied after unconverged solves; bench's
  // capped settings caught it. Float and double; the force must stay finite and near the
  // converged one (bench: 1.1e-3 relative).
  void cappedIterationsStayStable_data() {
    QTest::addColumn<int>("precision");
    QTest::newRow("double") << int(Precision::Double);
    QTest::newRow("float") << int(Precision::Float);
  }
  void cappedIterationsStayStable() {
    QFETCH(int, precision);
    Scenario s = builtin_scenario("paper-sweep");
    s.patient.resolution = "coarse";
    s.patient.edge = *resolution_edge("breast", "coarse");
    s.params.solver.precision = Precision(precision);
    const Model m = build_scenario_model(s, patient_mesh(s));
    const int steps = 1500;
    const Trace converged = run(s, m, "cpu", steps);
    s.params.solver.cg_tolerance = 1e-10;
    s.params.solver.cg_max_iterations = 5;
    s.params.solver.cg_rescue_iterations = 0;  // a fixed-iteration solver: no rescue past the cap
    Trace capped;
    try {
      capped = run(s, m, "cpu", steps);
    } catch (const std::exception& e) {
      QFAIL(e.what());
    }
    const double e = relative_error(capped.force, converged.force);
    qInfo("5 CG iterations per step: force error %.2e against CG 1e-3", e);
    QVERIFY2(e <= 1e-2, qPrintable(QString("force error %1").arg(e)));
  }

  // Both elements: the nodal-pressure term (sim/cuda/pressure.cuh) on the GPU against the
  // CPU's, the same arithmetic at corotation tolerance 0.
  void doubleAgreesWithCpu_data() {
    QTest::addColumn<QString>("backend");
    QTest::addColumn<bool>("nodal");
    QTest::addColumn<QString>("preconditioner");
    QTest::addColumn<QString>("resolution");
    QTest::addColumn<int>("steps");
    QTest::addColumn<bool>("skin");
    QTest::addColumn<QString>("tuning");  // a knob of sim/cuda/tuning.h, "NAME=value" (empty: the defaults)
    QTest::newRow("cuda") << "cuda" << false << "block-jacobi" << "coarse" << 700 << false << "";
    QTest::newRow("cuda-csr") << "cuda-csr" << false << "block-jacobi" << "coarse" << 700 << false << "";
    QTest::newRow("cuda-bsr") << "cuda-bsr" << false << "block-jacobi" << "coarse" << 700 << false << "";
    QTest::newRow("cuda nodal-pressure") << "cuda" << true << "block-jacobi" << "coarse" << 700 << false << "";
    // The persistent kernel's forms of the same PCG (PALPATION_CUDA_CG; by default the
    // one-reduction form on the linear element, the two-barrier one with the nodal-pressure
    // term): the same iterates in other recurrences and summation orders.
    QTest::newRow("cuda, two-barrier form") << "cuda" << false << "block-jacobi" << "coarse" << 700 << false << "PALPATION_CUDA_CG=fused";
    QTest::newRow("cuda nodal-pressure, one-reduction form") << "cuda" << true << "block-jacobi" << "coarse" << 700 << false << "PALPATION_CUDA_CG=1sync";
    QTest::newRow("cuda, three-barrier form") << "cuda" << false << "block-jacobi" << "coarse" << 700 << false << "PALPATION_CUDA_CG=3sync";
    QTest::newRow("cuda nodal-pressure, three-barrier form") << "cuda" << true << "block-jacobi" << "coarse" << 700 << false << "PALPATION_CUDA_CG=3sync";
    QTest::newRow("cuda nodal-pressure, paper box") << "cuda" << true << "block-jacobi" << "paper" << 700 << false << "";
    // `auto` takes the three-barrier form with the nodal-pressure term where the rows stream
    // from memory (the large meshes; the boxes' rows fit in registers).
    QTest::newRow("cuda nodal-pressure, rows streamed") << "cuda" << true << "block-jacobi" << "coarse" << 700 << false << "PALPATION_CUDA_CACHE=0";
    // The multigrid's levels built on the host from the system the GPU assembled, its
    // V-cycle run inside the persistent kernel: the CPU's preconditioner, so the same
    // iterations and forces.
    // The paper box (8x the coarse box's nodes) takes the V-cycle through intermediate
    // coarse levels (smoothed, restricted, prolonged), which the coarse box may not have.
    QTest::newRow("cuda multigrid") << "cuda" << false << "multigrid" << "coarse" << 700 << false << "";
    QTest::newRow("cuda multigrid nodal-pressure") << "cuda" << true << "multigrid" << "coarse" << 700 << false << "";
    QTest::newRow("cuda multigrid-chebyshev nodal-pressure") << "cuda" << true << "multigrid-chebyshev" << "coarse" << 700 << false << "";
    QTest::newRow("cuda multigrid nodal-pressure, paper box") << "cuda" << true << "multigrid" << "paper" << 700 << false << "";
    // Its PCG in three barriers: forced, and as `auto` takes it where the rows stream.
    QTest::newRow("cuda multigrid nodal-pressure, three-barrier form")
        << "cuda" << true << "multigrid" << "coarse" << 700 << false << "PALPATION_CUDA_CG=3sync";
    QTest::newRow("cuda multigrid nodal-pressure, paper box, rows streamed")
        << "cuda" << true << "multigrid" << "paper" << 700 << false << "PALPATION_CUDA_CACHE=0";
    // Every coarse-level and transfer product read at each of its row widths (multigrid.cuh,
    // CsrDev::lanes: the boxes' levels are too small for `auto` to take 2 lanes, and take a
    // block per row only for the coarsest's inverse): the same products in other summation
    // orders.
    QTest::newRow("cuda multigrid nodal-pressure, paper box, 2 lanes a row")
        << "cuda" << true << "multigrid" << "paper" << 700 << false << "PALPATION_CUDA_MG_LANES=2";
    QTest::newRow("cuda multigrid nodal-pressure, paper box, a block a row")
        << "cuda" << true << "multigrid" << "paper" << 700 << false << "PALPATION_CUDA_MG_LANES=block";
    // The skin membrane (fem_membrane.h): the CPU's serial pass against the GPU's atomic
    // adds and its re-inverted diagonal, on both elements, a library baseline and the
    // multigrid (whose levels then include the membrane's blocks).
    QTest::newRow("cuda skin") << "cuda" << false << "block-jacobi" << "coarse" << 700 << true << "";
    QTest::newRow("cuda skin nodal-pressure") << "cuda" << true << "block-jacobi" << "coarse" << 700 << true << "";
    QTest::newRow("cuda-bsr skin") << "cuda-bsr" << false << "block-jacobi" << "coarse" << 700 << true << "";
    QTest::newRow("cuda multigrid skin nodal-pressure") << "cuda" << true << "multigrid" << "coarse" << 700 << true << "";
  }
  void doubleAgreesWithCpu() {
    QFETCH(QString, backend);
    QFETCH(bool, nodal);
    QFETCH(QString, preconditioner);
    QFETCH(QString, resolution);
    QFETCH(int, steps);
    QFETCH(bool, skin);
    QFETCH(QString, tuning);
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): GPU/CPU agreement not checked").c_str());
    const auto restore = set_tuning(tuning);
    Scenario s = hertz_coarse();
    if (skin) s.skin = SkinSpec{0.0015, 56000};
    s.patient.resolution = resolution.toStdString();
    s.patient.edge = *resolution_edge("box", s.patient.resolution);
    // Named either way: the scene's Poisson's ratio (0.45) would resolve an unnamed element
    // to the nodal-pressure one, which the library baselines do not have.
    s.params.element = nodal ? Element::NodalPressure : Element::Linear;
    s.params.solver.preconditioner = parse_preconditioner(preconditioner.toStdString());
    const Model m = build_scenario_model(s, patient_mesh(s));
    const Trace cpu = run(s, m, "cpu", steps);
    const Trace gpu = run(s, m, backend.toStdString(), steps);
    const double ef = relative_error(gpu.force, cpu.force), ex = relative_error(gpu.x, cpu.x);
    qInfo("%s double against cpu double (Hertz, %s box, %d nodes, %d steps, %s element, %s, %d skin triangles): force error %.2e, "
          "position error %.2e",
          qPrintable(backend), qPrintable(resolution), m.num_nodes(), steps, nodal ? "nodal-pressure" : "linear",
          qPrintable(preconditioner), m.skin.size(), ef, ex);
    QCOMPARE(m.skin.empty(), !skin);
    if (is_multigrid(s.params.solver.preconditioner)) {
      // The levels did their work on the GPU: far fewer iterations than block-Jacobi's.
      Scenario bj = s;
      bj.params.solver.preconditioner = Preconditioner::BlockJacobi;
      const long bj_iterations = run(bj, m, "cpu", steps).iterations;
      qInfo("CG iterations with block-Jacobi on the cpu: %ld; multigrid builds cuda %ld (%ld failed), cpu %ld (%ld failed)",
            bj_iterations, gpu.multigrid.builds, gpu.multigrid.failures, cpu.multigrid.builds, cpu.multigrid.failures);
      // Built when the same rule says so on both (multigrid_keeper.h), and none threw.
      QVERIFY(gpu.multigrid.builds >= 1);
      QCOMPARE(gpu.multigrid.builds, cpu.multigrid.builds);
      QCOMPARE(gpu.multigrid.failures, 0L);
      QCOMPARE(cpu.multigrid.failures, 0L);
      QVERIFY2(2 * gpu.iterations < bj_iterations, qPrintable(QString("%1 against %2").arg(gpu.iterations).arg(bj_iterations)));
    }
    QVERIFY2(ef <= 1e-6, qPrintable(QString("force error %1").arg(ef)));
    QVERIFY2(ex <= 1e-6, qPrintable(QString("position error %1").arg(ex)));
    // The same algorithm (warm start, restart and stopping rules): the same iterations, up
    // to a step whose last iteration lands on the tolerance in one summation order and not
    // in the other (1 % of about 90 a step over the 200 steps in contact).
    qInfo("CG iterations over the run: %s %ld, cpu %ld", qPrintable(backend), gpu.iterations, cpu.iterations);
    QVERIFY2(std::abs(gpu.iterations - cpu.iterations) <= cpu.iterations / 100,
             qPrintable(QString("%1 against %2 iterations").arg(gpu.iterations).arg(cpu.iterations)));
  }

  // A real-time cap below convergence (5 iterations a step, no rescue) on the GPU: the
  // same truncated solve as the CPU's, step for step. The graph-replayed baseline runs in
  // chunks of four iterations, so this checks that its stopping rule ends each solve at the
  // cap, not at the chunk's end.
  void cappedAgreesWithCpu_data() {
    QTest::addColumn<QString>("backend");
    QTest::addColumn<QString>("tuning");  // "NAME=value", as doubleAgreesWithCpu's
    QTest::newRow("cuda") << "cuda" << "";
    QTest::newRow("cuda, two-barrier form") << "cuda" << "PALPATION_CUDA_CG=fused";
    QTest::newRow("cuda-bsr") << "cuda-bsr" << "";
  }
  void cappedAgreesWithCpu() {
    QFETCH(QString, backend);
    QFETCH(QString, tuning);
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): GPU/CPU agreement not checked").c_str());
    const auto restore = set_tuning(tuning);
    Scenario s = hertz_coarse();
    s.params.element = Element::Linear;
    s.params.solver.cg_tolerance = 1e-3;
    s.params.solver.cg_max_iterations = 5;
    s.params.solver.cg_rescue_iterations = 0;
    const Model m = build_scenario_model(s, patient_mesh(s));
    const Trace cpu = run(s, m, "cpu", 700);
    const Trace gpu = run(s, m, backend.toStdString(), 700);
    const double ef = relative_error(gpu.force, cpu.force);
    qInfo("%s capped at 5 against cpu capped at 5: force error %.2e, iterations %ld and %ld", qPrintable(backend), ef,
          gpu.iterations, cpu.iterations);
    // Double arithmetic in another summation order: 1e-6 leaves five orders of magnitude
    // above the 1e-13 seen converged, and far below the 1e-2 the cap itself costs.
    QVERIFY2(ef <= 1e-6, qPrintable(QString("force error %1").arg(ef)));
    QVERIFY2(std::abs(gpu.iterations - cpu.iterations) <= cpu.iterations / 100,
             qPrintable(QString("%1 against %2 iterations").arg(gpu.iterations).arg(cpu.iterations)));
    QVERIFY2(gpu.iterations <= 5L * 700, "the cap of 5 a step was passed");
  }

  // The library baselines have the linear element only: asked for the nodal-pressure one
  // they say so, rather than run the wrong element.
  void baselinesRefuseNodalPressure_data() {
    QTest::addColumn<QString>("backend");
    QTest::newRow("cuda-csr") << "cuda-csr";
    QTest::newRow("cuda-bsr") << "cuda-bsr";
  }
  void baselinesRefuseNodalPressure() {
    QFETCH(QString, backend);
    QVERIFY(is_library_baseline(backend.toStdString()));
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): the baseline cannot be made here").c_str());
    Scenario s = hertz_coarse();
    s.params.element = Element::NodalPressure;
    const Model m = build_scenario_model(s, patient_mesh(s));
    try {
      make_named_backend(backend.toStdString(), m, s.params);
      QFAIL(qPrintable(backend + " with the nodal-pressure element must throw"));
    } catch (const std::runtime_error& e) {
      QVERIFY2(std::string(e.what()).find("nodal-pressure") != std::string::npos, e.what());
    }
  }

  // Float on the GPU against double on the CPU: 2e-2 (float arithmetic itself, on the CPU
  // too, is 1.3e-2 off where a first touch decides contacts: docs/gpu-notes.md, section 4).
  // With the multigrid, whose coarse levels' matrices a float solve reads in float
  // (multigrid.cuh): the same bound, and the rounded levels still precondition (far fewer
  // iterations than block-Jacobi's, as doubleAgreesWithCpu asks in double).
  void floatAgreesWithinTolerance_data() {
    QTest::addColumn<QString>("preconditioner");
    QTest::newRow("block-jacobi") << "block-jacobi";
    QTest::newRow("multigrid") << "multigrid";
  }
  void floatAgreesWithinTolerance() {
    QFETCH(QString, preconditioner);
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): float agreement not checked").c_str());
    Scenario s = hertz_coarse();
    s.params.solver.preconditioner = parse_preconditioner(preconditioner.toStdString());
    const Model m = build_scenario_model(s, patient_mesh(s));
    Scenario sf = s;
    sf.params.solver.precision = Precision::Float;
    sf.params.solver.cg_tolerance = 1e-6;
    sf.params.solver.cg_max_iterations = 1000;
    const Trace cpu = run(s, m, "cpu", 700);
    const Trace gpu = run(sf, m, "cuda", 700);
    const double ef = relative_error(gpu.force, cpu.force), ex = relative_error(gpu.x, cpu.x);
    qInfo("cuda float against cpu double (Hertz, coarse box, 700 steps, %s): force error %.2e, position error %.2e",
          qPrintable(preconditioner), ef, ex);
    QVERIFY2(ef <= 2e-2, qPrintable(QString("force error %1").arg(ef)));
    QVERIFY2(ex <= 2e-2, qPrintable(QString("position error %1").arg(ex)));
    if (is_multigrid(s.params.solver.preconditioner)) {
      Scenario bj = sf;
      bj.params.solver.preconditioner = Preconditioner::BlockJacobi;
      const long bj_iterations = run(bj, m, "cuda", 700).iterations;
      qInfo("CG iterations in float: multigrid %ld, block-Jacobi %ld", gpu.iterations, bj_iterations);
      QVERIFY(gpu.multigrid.builds >= 1);
      QCOMPARE(gpu.multigrid.failures, 0L);
      QVERIFY2(2 * gpu.iterations < bj_iterations, qPrintable(QString("%1 against %2").arg(gpu.iterations).arg(bj_iterations)));
    }
  }
};

QTEST_GUILESS_MAIN(TestBackendAgreement)
#include "tst_backend_agreement.moc"
