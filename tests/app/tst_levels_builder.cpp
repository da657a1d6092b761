// The simulation thread's multigrid builder (app/live/levels_builder.h): a rebuild that
// falls due while stepping runs on the builder's thread while the steps go on with the
// levels they had, and goes in use between two steps; a forgotten job is never installed.
#include <QtTest>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "../sim/box_scenario.h"
#include "backend_cpu.h"
#include "live/levels_builder.h"
#include "model.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation;
using namespace palpation::sim;

namespace {

// The sim tests' 6 x 6 x 3 cm box at 4 mm cells, multigrid-preconditioned to CG 1e-6.
Scenario press_box() {
  Scenario s = box_scenario("tst_levels_builder", Eigen::Vector3d(0.06, 0.06, 0.03), 0.004, "cpu");
  s.params.solver.cg_tolerance = 1e-6;
  s.params.solver.preconditioner = Preconditioner::Multigrid;
  return s;
}

struct Press {
  std::vector<FingerInput> in = std::vector<FingerInput>(1);
  std::vector<FingerOutput> out = std::vector<FingerOutput>(1);
  int k = 0;
  // One step of the press (3 mm in 30 steps, then held); its CG iterations.
  int step(Backend& b) {
    ++k;
    in[0].radius = 0.008;
    in[0].position = Eigen::Vector3d(0.005, 0, 0.03 + 0.008 - 1e-4 * std::min(k, 30));
    const StepStats st = b.step(in, out);
    if (!st.finite) throw std::runtime_error("step " + std::to_string(k) + " not finite");
    return st.cg_iterations;
  }
};

}  // namespace

class TestLevelsBuilder : public QObject {
  Q_OBJECT
  Scenario s_ = press_box();
  Model m_;
  // A CPU backend of the box, deferred builds on or off.
  std::unique_ptr<Backend> backend(bool deferred) {
    auto b = make_cpu_backend(m_, s_.params);
    b->set_deferred_levels(deferred);
    return b;
  }

 private slots:
  void initTestCase() { m_ = build_scenario_model(s_, patient_mesh(s_)); }

  // New materials (a painted tumour) make the levels due again: with deferred builds the
  // step that finds them due does not build, the builder's thread does, the steps in
  // between keep the old levels (a few CG iterations, as multigrid-preconditioned steps
  // take; block-Jacobi takes several times more here, tst_multigrid), and the new levels
  // go in use at a poll after the thread finished: one build more, no failure.
  void rebuildRunsBesideTheSteps() {
    auto b = backend(true);
    app::live::LevelsBuilder builder;
    Press p;
    for (int i = 0; i < 10; ++i) p.step(*b);
    QCOMPARE(b->multigrid_counts().builds, 1L);  // the first build, in the step: no levels to keep
    QVERIFY(!builder.poll(*b));
    QCOMPARE(builder.started(), 0L);

    Materials mat = m_.materials;
    for (auto& e : mat.mu) e *= 1.5;
    b->set_materials(mat);
    const int iterations = p.step(*b);
    QCOMPARE(b->multigrid_counts().builds, 1L);  // not in the step
    QVERIFY2(iterations > 0 && iterations < 40, qPrintable(QString::number(iterations)));
    bool installed = builder.poll(*b);
    QCOMPARE(builder.started(), 1L);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!installed && std::chrono::steady_clock::now() < until) {
      p.step(*b);
      installed = builder.poll(*b);
      if (!installed) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    QVERIFY(installed);
    QCOMPARE(b->multigrid_counts().builds, 2L);
    QCOMPARE(b->multigrid_counts().failures, 0L);
    QCOMPARE(builder.started(), 1L);
    for (int i = 0; i < 5; ++i) p.step(*b);
    QVERIFY(!builder.poll(*b));  // nothing more due
    QCOMPARE(builder.started(), 1L);
  }

  // Another simulation (a new patient, a fallback): the job under way is dropped, not put
  // into the backend that now runs; the backend builds the levels it needs itself.
  void forgottenJobIsNeverInstalled() {
    auto b = backend(true);
    app::live::LevelsBuilder builder;
    Press p;
    for (int i = 0; i < 5; ++i) p.step(*b);
    b->set_materials(m_.materials);
    p.step(*b);
    builder.poll(*b);
    QCOMPARE(builder.started(), 1L);
    builder.forget();
    auto other = backend(true);
    Press q;
    for (int i = 0; i < 20; ++i) {
      q.step(*other);
      QVERIFY(!builder.poll(*other));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    QCOMPARE(other->multigrid_counts().builds, 1L);  // its own first build
    QCOMPARE(b->multigrid_counts().builds, 1L);      // the forgotten job went nowhere
  }

  // Off (the default of a backend): every build in the step that finds it due, no job.
  void offBuildsInTheStep() {
    auto b = backend(false);
    Press p;
    p.step(*b);
    b->set_materials(m_.materials);
    p.step(*b);
    QCOMPARE(b->multigrid_counts().builds, 2L);
    QVERIFY(!b->take_levels_job());
  }
};

QTEST_APPLESS_MAIN(TestLevelsBuilder)
#include "tst_levels_builder.moc"
