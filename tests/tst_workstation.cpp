// app/workstation.h without widgets: the default patient loads on the simulation thread,
// the simulated HandHIRO palpates (tick and step telemetry reach the listeners, the index
// fingertip touches the breast), a material command reaches the running model, and a
// patient swap brings up a new model. Waits are for events (QTRY_*), never timing checks.
#include <QtTest>

#include <atomic>
#include <cmath>

#include "workstation.h"

using namespace palpation;

class TstWorkstation : public QObject {
  Q_OBJECT

 private slots:
  void runs_and_applies_materials() {
    app::WorkstationOptions opt;
    opt.scenario = app::default_workstation_scenario();
    opt.haptic_priority = 0;
    app::Workstation ws(opt);
    int ticks = 0, steps = 0, patient_events = 0;
    double max_fz = 0;
    ws.add_tick_listener([&](const app::TickSample& s) {
      ++ticks;
      QVERIFY(s.force.allFinite());
      if (s.finger == 1) max_fz = std::max(max_fz, s.force.z());
    });
    ws.add_step_listener([&](const app::StepSample&) { ++steps; });
    ws.add_event_listener([&](const app::Event& e) { patient_events += e.kind == "patient"; });
    ws.start();
    auto pump = [&] { ws.poll(); };
    QTRY_VERIFY_WITH_TIMEOUT((pump(), ws.geometry() != nullptr), 120000);
    const auto g = ws.geometry();
    QVERIFY(g->rest.size() > 300 && g->rest.size() < 5000);  // coarse breast: about 1,000 nodes
    // The patient's tumour (paper: 107 kPa sphere) is in the model.
    int stiff = 0;
    for (double E : g->young) stiff += E > 100000;
    QVERIFY(stiff > 0);
    // The scripted index finger presses: the tissue pushes back (fz > 0).
    QTRY_VERIFY_WITH_TIMEOUT((pump(), max_fz > 0.05), 60000);
    QTRY_VERIFY_WITH_TIMEOUT((pump(), ticks > 100 && steps > 10), 60000);
    QVERIFY(patient_events >= 1);
    QVERIFY(ws.poll() || ws.snapshot().sequence > 0);
    QCOMPARE(ws.snapshot().positions.size(), g->rest.size() * 3);

    // A material command: elements 0..9 to 250 kPa, applied between steps.
    std::vector<std::pair<int, double>> ch;
    for (int e = 0; e < 10; ++e) ch.emplace_back(e, 250000.0);
    ws.set_element_young(ch, "test");
    const std::uint64_t want = ws.commands_posted();
    QTRY_VERIFY_WITH_TIMEOUT(ws.commands_applied() >= want, 10000);
    const auto young = ws.applied_young();
    for (int e = 0; e < 10; ++e) QCOMPARE(young[e], 250000.0);
    QCOMPARE(young[10], g->young[10]);

    // Patient swap: a small box; forces fade, a new model comes up.
    sim::Scenario box = opt.scenario;
    box.patient.phantom = "box";
    box.patient.size = Eigen::Vector3d(0.06, 0.06, 0.03);
    box.patient.resolution = "";
    box.patient.edge = 0.012;
    box.inclusions.clear();
    ws.load_patient(box);
    QTRY_VERIFY_WITH_TIMEOUT((pump(), ws.geometry()->generation != g->generation), 60000);
    QVERIFY(ws.geometry()->rest.size() != g->rest.size());
    QTRY_VERIFY_WITH_TIMEOUT((pump(), ws.snapshot().model_generation == ws.geometry()->generation), 10000);
    ws.stop();
    QVERIFY(ws.stats().dropped == 0 || ticks > 0);
  }

  // The HandHIRO protocol path: the loop talks UDP to an in-process emulator whose hand
  // follows the same scripted palpation; forces come back through the link.
  void emulator_device() {
    app::WorkstationOptions opt;
    opt.scenario = app::default_workstation_scenario();
    opt.haptic_priority = 0;
    opt.device = "emulator";
    app::Workstation ws(opt);
    QVERIFY(!ws.simulated_device());
    QVERIFY(QString::fromStdString(ws.device_description()).contains(QLatin1String("emulator")));
    double max_fz = 0;
    int attached = 0;
    ws.add_tick_listener([&](const app::TickSample& s) {
      QVERIFY(s.force.allFinite());
      attached += s.attached;
      if (s.finger == 1) max_fz = std::max(max_fz, s.force.z());
    });
    ws.start();
    QTRY_VERIFY_WITH_TIMEOUT((ws.poll(), max_fz > 0.05), 120000);
    QVERIFY(attached > 0);
    QVERIFY(ws.stats().connected);
    ws.stop();
  }

  void bad_device_is_refused() {
    app::WorkstationOptions opt;
    opt.device = "robot-arm";
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, app::Workstation{opt});
  }
};

QTEST_GUILESS_MAIN(TstWorkstation)
#include "tst_workstation.moc"
