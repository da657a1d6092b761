// Scenario parsing: every bad input gets one line naming the file, the field and the
// reason; good input round-trips; output folders never hold half a result.
#include <QtTest>

#include <filesystem>
#include <fstream>

#include "live/device_bridge.h"
#include "store/output_dir.h"
#include "backend.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation;

namespace {

// The error message for `text`, or "" when it parses.
QString error_of(const std::string& text) {
  try {
    sim::parse_scenario(text, "case.json");
  } catch (const sim::ScenarioError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

const char* kFinger = R"("fingers": [{"path": [[0, 0, 0, 0.1], [1, 0, 0, 0.05]]}])";

std::string with(const std::string& body) { return "{\"patient\": {\"phantom\": \"box\"}, " + body + ", " + kFinger + "}"; }

}  // namespace

class TestScenario : public QObject {
  Q_OBJECT
 private slots:
  void badInputNamesFileFieldAndReason_data() {
    QTest::addColumn<QString>("text");
    QTest::addColumn<QString>("expected");
    QTest::newRow("malformed") << QString("{\"patient\": ") << QString("case.json: (syntax): malformed JSON");
    QTest::newRow("unknown key") << QString::fromStdString(with("\"colour\": 1")) << QString("case.json: colour: unknown key");
    QTest::newRow("wrong type") << QString::fromStdString(with("\"duration\": \"long\"")) << QString("case.json: duration: must be a number");
    QTest::newRow("E <= 0") << QString::fromStdString(with("\"tissue\": {\"young_modulus\": 0}"))
                            << QString("case.json: tissue.young_modulus: must be > 0");
    QTest::newRow("nu 0.5") << QString::fromStdString(with("\"tissue\": {\"poisson_ratio\": 0.5}"))
                            << QString("case.json: tissue.poisson_ratio: must be in (-1, 0.5)");
    QTest::newRow("unknown element") << QString::fromStdString(with("\"tissue\": {\"element\": \"quadratic\"}"))
                                     << QString("case.json: tissue.element: must be one of");
    QTest::newRow("unknown preconditioner") << QString::fromStdString(with("\"solver\": {\"preconditioner\": \"ilu\"}"))
                                            << QString("case.json: solver.preconditioner: must be one of");
    QTest::newRow("unknown warm start") << QString::fromStdString(with("\"solver\": {\"warm_start\": \"zero\"}"))
                                        << QString("case.json: solver.warm_start: must be one of");
    QTest::newRow("layers not an array") << QString::fromStdString(with("\"tissue\": {\"layers\": {}}"))
                                         << QString("case.json: tissue.layers: must be an array of 1 to 8 layers");
    QTest::newRow("layer without thickness")
        << QString::fromStdString(with(R"("tissue": {"layers": [{"name": "skin", "young_modulus": 56000}, {"name": "core", "young_modulus": 19000}]})"))
        << QString("case.json: tissue.layers[0].thickness: is required (m) for every layer but the last");
    QTest::newRow("core with thickness")
        << QString::fromStdString(with(R"("tissue": {"layers": [{"name": "core", "thickness": 0.01, "young_modulus": 19000}]})"))
        << QString("case.json: tissue.layers[0].thickness: the last layer takes all that lies deeper: it has no thickness");
    QTest::newRow("layer names twice")
        << QString::fromStdString(with(R"("tissue": {"layers": [{"name": "fat", "thickness": 0.01, "young_modulus": 19000}, {"name": "fat", "young_modulus": 19000}]})"))
        << QString("case.json: tissue.layers[1].name: \"fat\" names two layers");
    QTest::newRow("layer too stiff")
        << QString::fromStdString(with(R"("tissue": {"layers": [{"name": "skin", "thickness": 0.002, "young_modulus": 1e9}, {"name": "core", "young_modulus": 19000}]})"))
        << QString("case.json: tissue.layers[0].young_modulus: must be within 10000x of tissue.young_modulus");
    QTest::newRow("tumour too stiff for a layer")
        << QString::fromStdString(with(R"("tissue": {"layers": [{"name": "skin", "thickness": 0.002, "young_modulus": 1000}, {"name": "core", "young_modulus": 19000}]}, "inclusions": [{"center": [0, 0, 0.01], "radius": 0.005, "young_modulus": 1.5e7}])"))
        << QString("case.json: inclusions[0].young_modulus: must be within 10000x of tissue.layers[0].young_modulus (1000 Pa)");
    QTest::newRow("skin_edge on a box") << QString::fromStdString(
                                               "{\"patient\": {\"phantom\": \"box\", \"skin_edge\": 0.002}, " + std::string(kFinger) + "}")
                                        << QString("case.json: patient.skin_edge: only the breast phantom takes a skin_edge");
    QTest::newRow("skin_edge too fine") << QString::fromStdString(
                                               "{\"patient\": {\"phantom\": \"breast\", \"skin_edge\": 0.0001}, " + std::string(kFinger) + "}")
                                        << QString("case.json: patient.skin_edge: must be in [0.0005, 0.05] m");
    QTest::newRow("dt <= 0") << QString::fromStdString(with("\"solver\": {\"dt\": -0.001}")) << QString("case.json: solver.dt: must be > 0");
    QTest::newRow("radius <= 0") << QString::fromStdString(
                                        "{\"patient\": {\"phantom\": \"box\"}, \"fingers\": [{\"radius\": 0, \"path\": [[0, 0, 0, 0.1]]}]}")
                                 << QString("case.json: fingers[0].radius: must be > 0");
    QTest::newRow("NaN") << QString::fromStdString(with("\"inclusions\": [{\"center\": [0, NaN, 0], \"radius\": 0.01}]"))
                         << QString("case.json: (syntax)");
    QTest::newRow("keys not increasing")
        << QString("{\"patient\": {\"phantom\": \"box\"}, \"fingers\": [{\"path\": [[0, 0, 0, 0.1], [0, 0, 0, 0.2]]}]}")
        << QString("case.json: fingers[0].path[1]: keyframe times must increase");
    QTest::newRow("no fingers") << QString("{\"patient\": {\"phantom\": \"box\"}}") << QString("case.json: fingers: is required");
    QTest::newRow("six fingers")
        << QString::fromStdString("{\"patient\": {\"phantom\": \"box\"}, \"fingers\": [" + std::string(5, ' ') +
                                  "{\"path\": [[0,0,0,0.1]]},{\"path\": [[0,0,0,0.1]]},{\"path\": [[0,0,0,0.1]]},"
                                  "{\"path\": [[0,0,0,0.1]]},{\"path\": [[0,0,0,0.1]]},{\"path\": [[0,0,0,0.1]]}]}")
        << QString("case.json: fingers: must be an array of 1 to 5 fingers");
    QTest::newRow("unknown level") << QString::fromStdString(
                                          "{\"patient\": {\"phantom\": \"box\", \"resolution\": \"huge\"}, " + std::string(kFinger) + "}")
                                   << QString("case.json: patient.resolution: unknown level");
  }
  void badInputNamesFileFieldAndReason() {
    QFETCH(QString, text);
    QFETCH(QString, expected);
    const QString err = error_of(text.toStdString());
    QVERIFY2(err.startsWith(expected), qPrintable(err));
    QVERIFY(!err.contains('\n'));
  }

  void unreadableFileIsNamed() {
    try {
      sim::load_scenario("/nonexistent/scenario.json");
      QFAIL("no error");
    } catch (const sim::ScenarioError& e) {
      QVERIFY(QString(e.what()).startsWith("/nonexistent/scenario.json: (file): cannot be read"));
    }
  }

  void builtinsRoundTrip() {
    for (const auto& name : sim::builtin_scenario_names()) {
      const sim::Scenario a = sim::builtin_scenario(name);
      const std::string json = sim::scenario_to_json(a);
      const sim::Scenario b = sim::parse_scenario(json, name);
      QCOMPARE(sim::scenario_to_json(b), json);
      QCOMPARE(b.fingers.size(), a.fingers.size());
      QCOMPARE(b.inclusions.size(), a.inclusions.size());
    }
  }

  // No element named: nodal pressure from Poisson's ratio 0.45 (the tissue default), the
  // linear element below it; a named element is kept at any ratio, and every element is
  // written back by name so a scenario reads back as it was.
  void elementRoundTrips() {
    const auto runs = [](const sim::Scenario& s) { return sim::resolve_element(s.params.element, s.poisson_ratio); };
    const sim::Scenario plain = sim::parse_scenario(with("\"duration\": 1"), "case.json");
    QCOMPARE(plain.poisson_ratio, 0.45);
    QVERIFY(runs(plain) == sim::Element::NodalPressure);
    QVERIFY(sim::scenario_to_json(plain).find("\"element\": \"nodal-pressure\"") != std::string::npos);
    const sim::Scenario soft = sim::parse_scenario(with("\"tissue\": {\"poisson_ratio\": 0.449}"), "case.json");
    QVERIFY(runs(soft) == sim::Element::Linear);
    QVERIFY(sim::parse_scenario(sim::scenario_to_json(soft), "case.json").params.element == sim::Element::Linear);
    const sim::Scenario pinned = sim::parse_scenario(with("\"tissue\": {\"poisson_ratio\": 0.49, \"element\": \"linear\"}"), "case.json");
    QVERIFY(runs(pinned) == sim::Element::Linear);
    QVERIFY(sim::scenario_to_json(pinned).find("\"element\": \"linear\"") != std::string::npos);
    QVERIFY(sim::parse_scenario(sim::scenario_to_json(pinned), "case.json").params.element == sim::Element::Linear);
    const sim::Scenario np = sim::parse_scenario(with("\"tissue\": {\"poisson_ratio\": 0.3, \"element\": \"nodal-pressure\"}"), "case.json");
    QVERIFY(runs(np) == sim::Element::NodalPressure);
    const sim::Scenario back = sim::parse_scenario(sim::scenario_to_json(np), "case.json");
    QVERIFY(back.params.element == sim::Element::NodalPressure);
    for (const auto& name : sim::builtin_scenario_names())
      QVERIFY2(runs(sim::builtin_scenario(name)) == sim::Element::NodalPressure, name.c_str());
    // A scenario put together in code names no element either: the backend that runs it
    // resolves it from the tissue it is given, at 0.49 and at 0.3 alike.
    for (const double nu : {0.49, 0.3}) {
      sim::Scenario coded;
      coded.patient.phantom = "box";
      coded.patient.size = Eigen::Vector3d(0.04, 0.04, 0.02);
      coded.patient.resolution.clear();
      coded.patient.edge = 0.01;
      coded.poisson_ratio = nu;
      coded.backend = "cpu";
      QVERIFY(coded.params.element == sim::Element::Auto);
      const sim::Model m = sim::build_scenario_model(coded, sim::patient_mesh(coded));
      const auto b = sim::make_backend(sim::BackendKind::Cpu, m, coded.params);
      QVERIFY(b->params().element == sim::default_element(nu));
      sim::SimParams p = b->params();
      p.element = sim::Element::Auto;
      b->set_params(p);
      QVERIFY(b->params().element == sim::default_element(nu));
    }
    QVERIFY_THROWS_EXCEPTION(sim::ScenarioError, sim::parse_scenario(with("\"tissue\": {\"element\": \"quadratic\"}"), "case.json"));
  }

  // The CG preconditioner: auto unless a scenario names one; a named one is written back
  // out, so a scenario round-trips with it; multigrid runs on the cpu and cuda backends
  // (auto takes cuda where there is a GPU, as for block-Jacobi), and a library baseline
  // asked for by name refuses it with the reason.
  void preconditionerRoundTrips() {
    const sim::Scenario plain = sim::parse_scenario(with("\"solver\": {}"), "case.json");
    QVERIFY(plain.params.solver.preconditioner == sim::Preconditioner::Auto);
    // The default is not written: scenarios written before the key keep their text.
    QVERIFY(sim::scenario_to_json(plain).find("preconditioner") == std::string::npos);
    // Block-Jacobi named is no longer the default, so it is written and read back.
    const sim::Scenario bj = sim::parse_scenario(with("\"solver\": {\"preconditioner\": \"block-jacobi\"}"), "case.json");
    QVERIFY(bj.params.solver.preconditioner == sim::Preconditioner::BlockJacobi);
    QVERIFY(sim::scenario_to_json(bj).find("\"preconditioner\": \"block-jacobi\"") != std::string::npos);
    QVERIFY(sim::parse_scenario(sim::scenario_to_json(bj), "case.json").params.solver.preconditioner ==
            sim::Preconditioner::BlockJacobi);
    const sim::Scenario mg = sim::parse_scenario(with("\"solver\": {\"preconditioner\": \"multigrid\"}"), "case.json");
    QVERIFY(mg.params.solver.preconditioner == sim::Preconditioner::Multigrid);
    const std::string text = sim::scenario_to_json(mg);
    QVERIFY(text.find("\"preconditioner\": \"multigrid\"") != std::string::npos);
    QVERIFY(sim::parse_scenario(text, "case.json").params.solver.preconditioner == sim::Preconditioner::Multigrid);
    const sim::Model m = sim::build_scenario_model(mg, sim::patient_mesh(mg));
    std::string reason;
    const auto b = sim::make_backend(sim::BackendKind::Auto, m, mg.params, &reason);
    // Chosen automatically as for block-Jacobi: cuda where there is a GPU, else the CPU
    // backend saying why.
    std::string no_gpu;
    const bool gpu = sim::cuda_available(&no_gpu);
    QCOMPARE(QString::fromStdString(b->name()), QString(gpu ? "cuda" : "cpu"));
    if (!gpu) QVERIFY2(reason.find(no_gpu) != std::string::npos, reason.c_str());
    QVERIFY(b->params().solver.preconditioner == sim::Preconditioner::Multigrid);
    // A library baseline refuses it by name, before it looks for a GPU.
    auto baseline_refuses = [&](const sim::SimParams& params, const QString& what) {
      for (const char* name : {"cuda-bsr", "cuda-csr"}) {
        try {
          sim::make_named_backend(name, m, params);
          QFAIL(qPrintable(QString("%1 took the %2 preconditioner").arg(name, what)));
        } catch (const std::runtime_error& e) {
#ifdef PALPATION_HAVE_CUDA
          QVERIFY2(QString(e.what()).contains(what) && QString(e.what()).contains(name), e.what());
#else
          QVERIFY2(QString(e.what()).contains("not available in this build"), e.what());
#endif
        }
      }
    };
    baseline_refuses(mg.params, "\"multigrid\"");
    // The Chebyshev-smoothed variant reads, writes and is refused by the baselines the same way.
    const sim::Scenario ch =
        sim::parse_scenario(with("\"solver\": {\"preconditioner\": \"multigrid-chebyshev\"}"), "case.json");
    QVERIFY(ch.params.solver.preconditioner == sim::Preconditioner::MultigridChebyshev);
    QVERIFY(sim::parse_scenario(sim::scenario_to_json(ch), "case.json").params.solver.preconditioner ==
            sim::Preconditioner::MultigridChebyshev);
    baseline_refuses(ch.params, "multigrid-chebyshev");
    // So does the one that keeps one Jacobi sweep whatever the share.
    const sim::Scenario jac = sim::parse_scenario(with("\"solver\": {\"preconditioner\": \"multigrid-jacobi\"}"), "case.json");
    QVERIFY(jac.params.solver.preconditioner == sim::Preconditioner::MultigridJacobi);
    QVERIFY(sim::parse_scenario(sim::scenario_to_json(jac), "case.json").params.solver.preconditioner ==
            sim::Preconditioner::MultigridJacobi);
    baseline_refuses(jac.params, "multigrid-jacobi");
  }

  // The warm start: auto (the last solution, WarmStart::Last) unless a scenario names one,
  // not written when auto (older scenarios keep their text), written and read back when
  // named; a backend reports the one it runs.
  void warmStartRoundTrips() {
    const sim::Scenario plain = sim::parse_scenario(with("\"solver\": {}"), "case.json");
    QVERIFY(plain.params.solver.warm_start == sim::WarmStart::Auto);
    QVERIFY(sim::scenario_to_json(plain).find("warm_start") == std::string::npos);
    const sim::Scenario ex = sim::parse_scenario(with("\"solver\": {\"warm_start\": \"extrapolated\"}"), "case.json");
    QVERIFY(ex.params.solver.warm_start == sim::WarmStart::Extrapolated);
    const std::string text = sim::scenario_to_json(ex);
    QVERIFY(text.find("\"warm_start\": \"extrapolated\"") != std::string::npos);
    QVERIFY(sim::parse_scenario(text, "case.json").params.solver.warm_start == sim::WarmStart::Extrapolated);
    sim::Scenario coded = plain;
    coded.backend = "cpu";
    const sim::Model m = sim::build_scenario_model(coded, sim::patient_mesh(coded));
    QVERIFY(sim::make_backend(sim::BackendKind::Cpu, m, coded.params)->params().solver.warm_start == sim::WarmStart::Last);
    QVERIFY(sim::make_backend(sim::BackendKind::Cpu, m, ex.params)->params().solver.warm_start == sim::WarmStart::Extrapolated);
  }

  // Tissue layers read, write and read back as they were; the layered built-in sweep has
  // the built-in breasts' layers and its no-tumour twin differs only in the tumour.
  void layersRoundTrip() {
    const sim::Scenario s = sim::parse_scenario(
        with(R"("tissue": {"layers": [{"name": "skin", "thickness": 0.0015, "young_modulus": 56000}, )"
             R"({"name": "fat", "thickness": 0.01, "young_modulus": 19000}, {"name": "glandular", "young_modulus": 31500}]})"),
        "case.json");
    QCOMPARE(int(s.layers.size()), 3);
    QCOMPARE(s.layers[0].name, std::string("skin"));
    QCOMPARE(s.layers[1].thickness, 0.01);
    QCOMPARE(s.layers[2].thickness, 0.0);
    const sim::Scenario back = sim::parse_scenario(sim::scenario_to_json(s), "case.json");
    QCOMPARE(int(back.layers.size()), 3);
    for (std::size_t i = 0; i < 3; ++i) {
      QCOMPARE(back.layers[i].name, s.layers[i].name);
      QCOMPARE(back.layers[i].thickness, s.layers[i].thickness);
      QCOMPARE(back.layers[i].young_modulus, s.layers[i].young_modulus);
    }
    QVERIFY(sim::parse_scenario(with("\"duration\": 1"), "case.json").layers.empty());
    QVERIFY(sim::scenario_to_json(sim::parse_scenario(with("\"duration\": 1"), "case.json")).find("layers") == std::string::npos);
    const sim::Scenario layered = sim::builtin_scenario("paper-sweep-layered");
    const sim::Scenario twin = sim::builtin_scenario("paper-sweep-layered-no-tumour");
    QCOMPARE(int(layered.layers.size()), 2);
    QCOMPARE(layered.layers.front().name, std::string("fat"));
    QCOMPARE(layered.layers.back().name, std::string("glandular"));
    QCOMPARE(int(twin.layers.size()), 2);
    QVERIFY(layered.inclusions.at(0).young_modulus > twin.inclusions.at(0).young_modulus);
    QVERIFY(sim::builtin_scenario("paper-sweep").layers.empty());
  }

  // The skin's edge length is read, written back only when set, and read again.
  void skinEdgeRoundTrips() {
    const std::string breast = "{\"patient\": {\"phantom\": \"breast\"%1}, " + std::string(kFinger) + "}";
    auto text = [&](const std::string& extra) { return QString::fromStdString(breast).arg(QString::fromStdString(extra)).toStdString(); };
    const sim::Scenario plain = sim::parse_scenario(text(""), "case.json");
    QCOMPARE(plain.patient.skin_edge, 0.0);
    QVERIFY(sim::scenario_to_json(plain).find("skin_edge") == std::string::npos);
    const sim::Scenario s = sim::parse_scenario(text(", \"skin_edge\": 0.002"), "case.json");
    QCOMPARE(s.patient.skin_edge, 0.002);
    QCOMPARE(sim::parse_scenario(sim::scenario_to_json(s), "case.json").patient.skin_edge, 0.002);
  }

  void pathIsLinearBetweenKeys() {
    sim::FingerPath p;
    p.keys = {{0, 0, 0, 0.1}, {1, 0.02, 0, 0.05}};
    Eigen::Vector3d x, v;
    p.sample(0.5, x, v);
    QVERIFY((x - Eigen::Vector3d(0.01, 0, 0.075)).norm() < 1e-12);
    QVERIFY((v - Eigen::Vector3d(0.02, 0, -0.05)).norm() < 1e-12);
    p.sample(2.0, x, v);  // held after the last key
    QVERIFY((x - Eigen::Vector3d(0.02, 0, 0.05)).norm() < 1e-12 && v.norm() == 0);
  }

  // A curved path reaches the device's linear follower as keys every haptic tick: at each
  // tick the scripted hand is where the simulation's finger is, between ticks within a
  // chord's sag (max|x''| (1 ms)^2 / 8, below 1e-6 m on the paper sweep, whose |x''|
  // stays under 3 m/s^2), in the device frame of a registration that moves and turns.
  void curvedPathReachesTheDeviceEveryTick() {
    const sim::Scenario s = sim::builtin_scenario("paper-sweep");
    QVERIFY(s.fingers[0].interpolation == sim::PathInterpolation::MonotoneCubic);
    device::RigidFrame reg;
    reg.rotation = device::Mat3{{0, -1, 0, 1, 0, 0, 0, 0, 1}};  // a quarter turn about z
    reg.origin = {0.1, -0.2, 0.3};
    const device::HandScript script = app::live::script_from_scenario(s, reg, {0, 1, 2, 3, 4});
    // How far the scripted hand is from the path at time t (world frame, m).
    auto off = [&](double t) {
      Eigen::Vector3d x, v;
      s.fingers[0].sample(t, x, v);
      device::Vec3 p, pv;
      if (!script.sample(t, 0, p, pv)) return 1.0;
      return (app::live::to_eigen(reg.to_world(p)) - x).norm();
    };
    double at_ticks = 0, between = 0;
    for (int i = 0; i <= 2000; ++i) {
      at_ticks = std::max(at_ticks, off(0.001 * i));
      between = std::max(between, off(0.001 * i + 0.0004));
    }
    QVERIFY2(at_ticks < 1e-12, qPrintable(QString::number(at_ticks)));
    QVERIFY2(between < 1e-6, qPrintable(QString::number(between)));
    QCOMPARE(script.duration(), s.fingers[0].keys.back()[0]);
  }

  // A command that fails after writing leaves nothing in its folder; one that succeeds
  // replaces the files; files already there survive a failure.
  void outputFolderNeverHoldsHalfAResult() {
    const std::string dir = QDir::tempPath().toStdString() + "/palpation-tst-out";
    std::filesystem::remove_all(dir);
    {
      app::store::OutputDir out(dir);
      std::ofstream(out.path("fingers.csv")) << "half";
      out.commit();
    }
    QVERIFY(std::filesystem::exists(dir + "/fingers.csv"));
    {
      app::store::OutputDir out(dir);
      std::ofstream(out.path("fingers.csv")) << "new but failed";
      std::ofstream(out.path("summary.json")) << "{}";
      // no commit: the command failed
    }
    std::ifstream in(dir + "/fingers.csv");
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    QCOMPARE(QString::fromStdString(content), QString("half"));
    QVERIFY(!std::filesystem::exists(dir + "/summary.json"));
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    QCOMPARE(entries, 1);  // no staging folder left behind
    std::filesystem::remove_all(dir);
  }
};

QTEST_APPLESS_MAIN(TestScenario)
#include "tst_scenario.moc"
