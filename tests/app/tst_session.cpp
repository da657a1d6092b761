// `palpation session` end to end (app/live/session.h): the real threads (1 kHz haptic thread,
// simulation thread, emulator thread or process) over loopback UDP on a small box. Checks
// what must hold on any machine, however loaded: every force sent finite and within the
// limit, the books balanced, the files and their fields there, bad input refused with
// exit code 2. No assertions on speed.
#include <QtTest>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "live/device_config.h"
#include "live/headless_run.h"
#include "multigrid_keeper.h"
#include "scenario.h"
#include "live/session.h"

using namespace palpation;

namespace {

// A 6 x 6 x 3 cm block, coarse; one fingertip pressing 3 mm into the top and holding.
sim::Scenario small_press(double duration = 1.5) {
  sim::Scenario s;
  s.source = "small-press";
  s.patient.phantom = "box";
  s.patient.size = Eigen::Vector3d(0.06, 0.06, 0.03);
  s.patient.resolution = "";
  s.patient.edge = 0.01;
  s.backend = "cpu";
  s.params.contact.stiffness = 2000;
  sim::FingerPath fp;
  fp.radius = 0.008;
  const double top = 0.03;
  fp.keys = {{0.0, 0.0, 0.0, top + 0.008 + 0.002}, {0.5, 0.0, 0.0, top + 0.008 - 0.003}, {10.0, 0.0, 0.0, top + 0.008 - 0.003}};
  s.fingers.push_back(fp);
  s.duration = duration;
  return s;
}

void check_forces(const app::live::SessionResult& r, double limit) {
  QVERIFY(!r.samples.empty());
  double max_f = 0;
  for (const auto& smp : r.samples) {
    QVERIFY(smp.f.allFinite());
    QVERIFY(smp.x.allFinite());
    QVERIFY(smp.f.norm() <= limit);
    max_f = std::max(max_f, smp.f.norm());
  }
  QVERIFY(max_f > 0.05);  // the finger did press
  QVERIFY(r.ok);
  QCOMPARE(r.loop["forces"]["nonfinite_sent"].get<int>(), 0);
  QCOMPARE(r.loop["forces"]["above_limit_sent"].get<int>(), 0);
  for (const char* k : {"rate_hz", "ticks", "overruns", "missed_deadlines", "scheduling"}) QVERIFY2(r.loop["haptic"].contains(k), k);
  for (const char* k : {"p50", "p99", "max"}) QVERIFY(r.loop["haptic"]["jitter_us"].contains(k));
  QVERIFY(r.loop["simulation"]["steps"].get<int>() > 0);
  QVERIFY(r.loop["simulation"]["finite"].get<bool>());
  QVERIFY(r.loop.contains("safety") && r.loop.contains("watchdog_events") && r.loop.contains("vibration"));
  // One row per tick per finger, in time order, up to the duration.
  for (std::size_t i = 1; i < r.samples.size(); ++i) QVERIFY(r.samples[i].t >= r.samples[i - 1].t);
  QVERIFY(r.samples.back().t <= r.loop["duration_s"].get<double>() + 1e-9);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = QDir::temp().filePath(QString::fromStdString(name)).toStdString();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

class TestSession : public QObject {
  Q_OBJECT
 private slots:
  void emulatorOverLoopback() {
    app::live::SessionOptions opt;
    opt.device = "emulator";
    opt.priority = 0;  // CI: normal scheduling
    const auto r = app::live::run_session(small_press(), opt);
    check_forces(r, opt.config.hand.capabilities.max_force);
    const auto& link = r.loop["link"];
    QVERIFY(link["states_accepted"].get<int>() > 100);
    QCOMPARE(link["states_corrupt"].get<int>(), 0);
    const auto& emu = r.loop["emulator"];
    QVERIFY(emu["commands_accepted"].get<int>() > 100);
    QCOMPARE(emu["commands_refused_nonfinite"].get<int>(), 0);
    QCOMPARE(emu["commands_over_limit"].get<int>(), 0);
    QVERIFY(emu["largest_force_received_n"].get<double>() <= opt.config.hand.capabilities.max_force);
    // The fingertip reached the block: the recorded path goes below the skin + radius.
    double zmin = 1;
    for (const auto& smp : r.samples) zmin = std::min(zmin, smp.x.z());
    QVERIFY(zmin < 0.03 + 0.008);
  }

  void scriptedDeviceFollowsThePath() {
    app::live::SessionOptions opt;
    opt.device = "scripted";
    opt.priority = 0;
    const sim::Scenario s = small_press(1.0);
    const auto r = app::live::run_session(s, opt);
    check_forces(r, opt.config.hand.capabilities.max_force);
    QCOMPARE(r.loop["device_received"]["nonfinite"].get<int>(), 0);
    QCOMPARE(r.loop["device_received"]["over_limit"].get<int>(), 0);
    // Real-time steps start on a grid of dt (app/live/simulation_loop.h): a step shorter
    // than dt covers exactly dt, so the median step of this small block (tens of
    // microseconds) is dt itself, not dt plus the wake-up's lateness (the rate fell to
    // 0.87-0.94 steps a millisecond when each period began at the last start).
    QCOMPARE(r.loop["simulation"]["dt_mode"].get<std::string>(), std::string("realtime"));
    QCOMPARE(r.loop["simulation"]["preconditioner"].get<std::string>(), std::string("block-jacobi"));
    QCOMPARE(r.loop["simulation"]["multigrid_smoother"].get<std::string>(), std::string("none"));
    const double dt_median = r.loop["simulation"]["dt_ms_median"].get<double>();
    const double step_median = r.loop["simulation"]["step_ms_median"].get<double>(), dt_ms = 1e3 * s.params.solver.dt;
    const double limit = r.loop["simulation"]["dt_ms_limit"].get<double>();
    if (step_median < 0.5 * dt_ms) {
      QVERIFY2(std::abs(dt_median - dt_ms) < 1e-6, qPrintable(QString::number(dt_median, 'g', 12)));
      // Every step fits: the pacer never weighs a shorter dt against the longest, and
      // the tissue keeps the wall clock's pace (the simulated time over the steps' wall
      // time: one dt more than the span between the first and last step's start).
      QCOMPARE(r.loop["simulation"]["dt_sweeps"].get<int>(), 0);
      QCOMPARE(limit, 1e3 * opt.sim_max_dt);
      const double pace = r.loop["simulation"]["pace"].get<double>();
      QVERIFY2(pace > 0.95 && pace < 1.05, qPrintable(QString::number(pace)));
    } else {
      // Steps longer than dt (the sanitizer build on a 2-core machine: 2.2 ms in contact)
      // cover their own time: the grid rule has nothing to show, only that dt never
      // falls below the scenario's.
      qInfo("the median step takes %.3f ms here, over half of dt: dt median %.3f ms", step_median, dt_median);
      QVERIFY2(dt_median >= dt_ms - 1e-6, qPrintable(QString::number(dt_median, 'g', 12)));
      QVERIFY2(limit >= dt_ms - 1e-9 && limit <= 1e3 * opt.sim_max_dt + 1e-9, qPrintable(QString::number(limit)));
    }
    // Positions are the scenario's path (the script clock starts one tick before the
    // first record: allow that tick's motion, 10 mm/s x 1 ms).
    for (const auto& smp : r.samples) {
      Eigen::Vector3d x, v;
      s.fingers[0].sample(smp.t - 0.001, x, v);
      QVERIFY((smp.x - x).norm() < 2e-5);
    }
  }

  // `palpation run`'s summary (and loop.json's "simulation") names the preconditioner and
  // what its multigrid levels did: built at least once, and smoothed as the preconditioner
  // says: "multigrid" by the nodal-pressure share at the build (Chebyshev from
  // MultigridKeeper::kChebyshevShare up), the other two whatever the share. The box in
  // nodal-pressure tissue at 0.40 and 0.499 puts the share either side of the switch
  // (measured 0.125 and 0.946); the rule is what is asserted, so a share that moves with
  // the mesh or the step does not make the test wrong.
  void runSummaryNamesTheMultigrid() {
    for (double nu : {0.40, 0.499}) {
      double share = -1;
      for (sim::Preconditioner pc : {sim::Preconditioner::Multigrid, sim::Preconditioner::MultigridJacobi,
                                     sim::Preconditioner::MultigridChebyshev}) {
        sim::Scenario s = small_press(0.1);
        s.poisson_ratio = nu;
        s.params.element = sim::Element::NodalPressure;
        s.params.solver.preconditioner = pc;
        const nlohmann::json j = app::live::run_headless(s, {}).summary;
        const std::string name = sim::preconditioner_name(pc), smoother = j["multigrid_smoother"].get<std::string>();
        const double sh = j["multigrid_pressure_share"].get<double>();
        qInfo("nu %.3f, %s: %d level builds, %s at a share of %.3f", nu, name.c_str(), j["multigrid_builds"].get<int>(),
              smoother.c_str(), sh);
        QCOMPARE(j["preconditioner"].get<std::string>(), name);
        QVERIFY(j["multigrid_builds"].get<int>() >= 1);
        QCOMPARE(j["multigrid_build_failures"].get<int>(), 0);
        QVERIFY(sh > 0 && sh < 1);
        if (share < 0) share = sh;
        QCOMPARE(sh, share);  // the same system at the build, whichever smoother follows
        const bool chebyshev = pc == sim::Preconditioner::MultigridChebyshev ||
                               (pc == sim::Preconditioner::Multigrid && sh >= sim::MultigridKeeper::kChebyshevShare);
        QCOMPARE(smoother, std::string(chebyshev ? "chebyshev" : "jacobi"));
      }
    }
  }

  // handhiro-emulator as a separate process, talking UDP on loopback. Two seconds: the
  // session's clock runs from its first tick, before the child (a sanitized build starts
  // slowly) answers, and the force ramps in over the half second after it connects.
  void emulatorChildProcess() {
    const sim::Scenario s = small_press(2.0);
    const std::string path = write_temp("tst_session_press.json", sim::scenario_to_json(s));
    app::live::SessionOptions opt;
    opt.device = "emulator";
    opt.priority = 0;
    opt.emulator_exe = PALPATION_EMULATOR_EXE;
    opt.scenario_arg = path;
    const auto r = app::live::run_session(sim::load_scenario(path), opt);
    check_forces(r, opt.config.hand.capabilities.max_force);
    QVERIFY(r.loop["link"]["states_accepted"].get<int>() > 100);
    QVERIFY(!r.loop.contains("emulator"));  // its counters stay in the child
    std::remove(path.c_str());
  }

  void badInputIsRefused() {
    app::live::SessionOptions opt;
    opt.priority = 0;
    sim::Scenario six = small_press();
    while (six.fingers.size() < 6) six.fingers.push_back(six.fingers[0]);
    QVERIFY_THROWS_EXCEPTION(sim::ScenarioError, app::live::run_session(six, opt));
    opt.device = "phantom";
    QVERIFY_THROWS_EXCEPTION(sim::ScenarioError, app::live::run_session(small_press(), opt));
    opt.device = "replay";
    QVERIFY_THROWS_EXCEPTION(sim::ScenarioError, app::live::run_session(small_press(), opt));
    opt.recording = "/nonexistent/fingers.csv";
    QVERIFY_THROWS_EXCEPTION(sim::ScenarioError, app::live::run_session(small_press(), opt));
  }

  // The command line: exit 2 with one line naming the file and field; nothing written.
  void commandLineExitCodes() {
    const QString exe = PALPATION_EXE;
    const QString out = QDir::temp().filePath("tst_session_out");
    QDir(out).removeRecursively();
    const std::string bad = write_temp("tst_session_bad.json", R"({"duration": -1})");
    QProcess p;
    p.start(exe, {"session", QString::fromStdString(bad), "--device", "scripted", "--out", out, "--no-rt"});
    QVERIFY(p.waitForFinished(600000));
    QCOMPARE(p.exitCode(), 2);
    const QString err = QString::fromLocal8Bit(p.readAllStandardError()).trimmed();
    QVERIFY2(err.contains("tst_session_bad.json: patient: "), qPrintable(err));  // file: field: reason
    QCOMPARE(err.count('\n'), 0);
    QVERIFY(!QFileInfo::exists(out + "/loop.json"));
    const std::string cfg = write_temp("tst_session_cfg.json", R"({"capabilities": {"max_force": "strong"}})");
    p.start(exe, {"session", "hertz", "--device", "scripted", "--out", out, "--device-config", QString::fromStdString(cfg)});
    QVERIFY(p.waitForFinished(600000));
    QCOMPARE(p.exitCode(), 2);
    QVERIFY(QString::fromLocal8Bit(p.readAllStandardError()).contains("capabilities.max_force"));
    std::remove(bad.c_str());
    std::remove(cfg.c_str());
  }

  // The whole command with the emulator, small: files written, loop.json readable.
  void commandLineSession() {
    const sim::Scenario s = small_press(1.0);
    const std::string path = write_temp("tst_session_cli.json", sim::scenario_to_json(s));
    const QString out = QDir::temp().filePath("tst_session_cli_out");
    QDir(out).removeRecursively();
    QProcess p;
    p.start(PALPATION_EXE, {"session", QString::fromStdString(path), "--device", "emulator", "--out", out, "--no-rt", "--quiet"});
    QVERIFY(p.waitForFinished(600000));
    QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
    QFile csv(out + "/fingers.csv");
    QVERIFY(csv.open(QIODevice::ReadOnly));
    QCOMPARE(csv.readLine().trimmed(), QByteArray("t,finger,x,y,z,fx,fy,fz"));
    QFile js(out + "/loop.json");
    QVERIFY(js.open(QIODevice::ReadOnly));
    const auto j = nlohmann::json::parse(js.readAll().toStdString());
    QVERIFY(j["haptic"]["ticks"].get<int>() > 100);
    QDir(out).removeRecursively();
    std::remove(path.c_str());
  }
};

QTEST_GUILESS_MAIN(TestSession)
#include "tst_session.moc"
