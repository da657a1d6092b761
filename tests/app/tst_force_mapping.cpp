// The force scale between simulation and device (app/live/force_mapping.h): a deep press
// over the stiffest part of the patient maps to 90 % of the device's limit, so the
// tumour's extra force reaches the trainee instead of being cut off by the safety clamp.
//
// The contrast of a press over the paper's tumour against the same press on the same mesh
// without it (same depth below the skin, scripted fingertip, default patient: coarse
// breast, 19 kPa tissue, 107 kPa tumour), C = (F_tumour - F_none) / F_none, simulated and
// as sent to the device through
// the real chain: the simulation stepped in lockstep with the haptic loop (every 5 ticks,
// dt 5 ms), fingertips from the loop's poses through the virtual coupling
// (live/sim_fingers.h), contact models built with the scale (live/device_bridge.h),
// HapticLoop and SafetyFilter with the default HandHIRO configuration (4 N per finger).
// Measured (2-core VM): see the qInfo lines; docs/simulation.md, "Force scale", has them.
#include <QtTest>

#include <cmath>
#include <memory>

#include "live/device_bridge.h"
#include "live/device_config.h"
#include "live/force_mapping.h"
#include "live/session.h"
#include "live/sim_fingers.h"
#include "live/workstation.h"
#include "haptic_loop.h"
#include "press_probe.h"
#include "scripted_device.h"
#include "simulation.h"

using namespace palpation;
namespace dv = palpation::device;
namespace lv = palpation::app::live;

namespace {

constexpr std::int64_t kTick = 1000000;  // ns
constexpr int kEvery = 5;                // ticks per simulation step
// m below the skin: 4 mm deeper than the paper sweep's deep push, so that unscaled the
// press beside the tumour passes the device's limit too (the nodal-pressure element's
// tissue gives 3.5 N there at 18 mm, under the 4 N limit, and 4.0 N at 22 mm).
constexpr double kDepth = 0.022;
const Eigen::Vector3d kTumour(0.125, 0.0, 0.045);   // the paper's tumour centre (skin above it: the apex)

struct Press {
  double sim = 0;        // N, simulated force at the end of the hold (mean over its last 0.2 s)
  double sent = 0;       // N, sent to the device, same window
  double max_sent = 0;   // N, over the whole press
  bool finite = true;
  std::uint64_t clamped = 0;  // finger-ticks where the safety clamp acted
};

// One scripted press of the index fingertip, straight down above `where` from 3 mm above
// the skin to kDepth below it in 1 s, held 0.8 s; the patient's simulation stepped in
// lockstep with the haptic loop. `tumour` false: the same mesh with every element at the
// tissue's modulus (the patient without its tumour), so that the contrast is the tumour's
// alone, not that of two sites of different thickness and facets.
Press press(const sim::Scenario& sc, const sim::Model& model, const Eigen::Vector3d& where, double scale, bool tumour = true) {
  const lv::DeviceConfig cfg = lv::default_device_config();
  const auto& reg = cfg.hand.registration;
  const std::optional<sim::PressSite> site = sim::skin_site_above(model, where);
  if (!site) return {};
  const double r = 0.008;
  const Eigen::Vector3d top(where.x(), where.y(), site->skin.z() + r + 0.003);
  const Eigen::Vector3d bottom(where.x(), where.y(), site->skin.z() + r - kDepth);
  dv::HandScript script;
  script.set_path(dv::kIndex, {{0.0, reg.to_device(lv::to_dev(top))},
                               {0.3, reg.to_device(lv::to_dev(top))},
                               {1.3, reg.to_device(lv::to_dev(bottom))},
                               {100.0, reg.to_device(lv::to_dev(bottom))}});
  dv::ScriptedDevice device(script, cfg.hand.capabilities);
  dv::TripleBuffer<dv::PoseFrame> poses;
  dv::TripleBuffer<dv::ContactFrame> contacts;
  dv::HapticLoop loop(device, poses, contacts, nullptr, cfg.loop);
  const double limit = loop.params().safety.max_force;
  const double kc = loop.params().virtual_coupling ? loop.params().coupling_stiffness : 0.0;

  sim::Simulation simulation(sc, model);
  if (!tumour) {
    std::vector<std::pair<int, double>> tissue;
    for (int e = 0; e < model.num_tets(); ++e) tissue.emplace_back(e, sc.young_modulus);
    simulation.set_element_young(tissue);
  }
  simulation.reset();
  std::vector<sim::FingerInput> in(1);
  std::vector<sim::FingerOutput> out(1);
  in[0].radius = r;
  in[0].active = false;
  dv::FingerContactModel last;
  Eigen::Vector3d prev_force = Eigen::Vector3d::Zero();
  std::uint64_t seq = 0;
  Press p;
  double sum_sim = 0, sum_sent = 0, sim_f = 0;
  int n = 0;
  const int ticks = 1800;
  for (int k = 1; k <= ticks; ++k) {
    const std::int64_t t = k * kTick;
    loop.tick(t, t);
    const double f = dv::norm(loop.command().force[dv::kIndex]);
    p.finite = p.finite && std::isfinite(f);
    p.max_sent = std::max(p.max_sent, f);
    if (k % kEvery == 0) {
      // The simulation thread's step (as app/live/simulation_loop.cpp does it).
      poses.update();
      const dv::PoseFrame& pf = poses.read();
      lv::finger_from_pose(pf, dv::kIndex, last, kc, reg, kEvery * 1e-3, in[0]);
      const bool ok = simulation.advance(in, out, kEvery * 1e-3).ok;
      dv::ContactFrame& cf = contacts.write_slot();
      cf.fingers = {};
      if (ok && in[0].active) cf.fingers[dv::kIndex] = lv::contact_model(lv::guard_force_spike(out[0], prev_force), in[0].position, reg, scale);
      prev_force = ok && in[0].active && out[0].contacts > 0 ? Eigen::Vector3d(out[0].force) : Eigen::Vector3d::Zero();
      last = cf.fingers[dv::kIndex];
      cf.sequence = ++seq;
      cf.published_ns = t;
      contacts.publish();
      sim_f = ok ? out[0].force.norm() : 0.0;
    }
    if (k > ticks - 200) {
      sum_sim += sim_f;
      sum_sent += f;
      ++n;
    }
  }
  p.sim = sum_sim / n;
  p.sent = sum_sent / n;
  p.clamped = loop.safety().counters().clamped;
  if (device.received().over_limit != 0 || device.received().nonfinite != 0 || device.received().max_force > limit) p.finite = false;
  return p;
}

double contrast(double over, double beside) { return beside > 0 ? (over - beside) / beside : 0.0; }

}  // namespace

class TestForceMapping : public QObject {
  Q_OBJECT

  sim::Scenario sc_ = lv::default_workstation_scenario();
  std::unique_ptr<sim::Simulation> sim_;
  lv::ForceMapping mapping_;

 private slots:
  void initTestCase() {
    sc_.backend = "cpu";
    sim_ = std::make_unique<sim::Simulation>(sc_);
  }

  // The rule: the deep press over the stiffest part (the tumour) maps to 90 % of the limit.
  void deepPressMapsIntoTheDevicesRange() {
    const lv::DeviceConfig cfg = lv::default_device_config();
    const double limit = std::min(cfg.loop.safety.max_force, cfg.hand.capabilities.max_force);
    mapping_ = lv::measure_force_mapping(*sim_, 0.008, limit, cfg.force_mapping);
    qInfo("deep press: %.2f N simulated at (%.3f, %.3f, %.3f), depth %.1f mm of %.1f mm, %d sites, %.0f ms; scale %.3f -> %.2f N",
          mapping_.deep_press_n, mapping_.press_skin.x(), mapping_.press_skin.y(), mapping_.press_skin.z(),
          mapping_.press_depth_m * 1e3, mapping_.thickness_m * 1e3, mapping_.presses, mapping_.probe_ms, mapping_.scale,
          mapping_.deep_press_device_n);
    QCOMPARE(mapping_.rule, lv::ForceScaleRule::Patient);
    QVERIFY2(mapping_.deep_press_n > limit, "the default patient pushes harder than the device may");
    QVERIFY(mapping_.scale > 0.1 && mapping_.scale < 1.0);
    QVERIFY(std::fabs(mapping_.deep_press_device_n - 0.9 * limit) < 1e-9);
    // The stiffest site is the skin above the tumour (the apex), pressed 30 % of 6.5 cm.
    QVERIFY2((mapping_.press_skin.head<2>() - kTumour.head<2>()).norm() < 0.004, "pressed above the tumour");
    QVERIFY(std::fabs(mapping_.thickness_m - 0.065) < 0.004);
    QVERIFY(std::fabs(mapping_.press_depth_m - 0.3 * mapping_.thickness_m) < 1e-12);

    // Never above 1; a configured scale wins; a soft patient is not amplified.
    lv::ForceMappingConfig fixed;
    fixed.scale = 0.5;
    QCOMPARE(lv::force_mapping_for(12.0, limit, fixed).scale, 0.5);
    QCOMPARE(lv::force_mapping_for(12.0, limit, fixed).rule, lv::ForceScaleRule::Configured);
    QCOMPARE(lv::force_mapping_for(1.0, limit, {}).scale, 1.0);
    QCOMPARE(lv::force_mapping_for(0.0, limit, {}).rule, lv::ForceScaleRule::Unscaled);
    QCOMPARE(lv::force_mapping_for(std::nan(""), limit, {}).scale, 1.0);
  }

  // The probe presses with block-Jacobi whatever the patient's preconditioner: a multigrid
  // patient's deep press builds no levels, and its force is the multigrid press's at the
  // same site. Both hold the CG residual at 1e-6 here (the error controller off); the two
  // preconditioners' last iterates then differ by 4e-7 of the force (2-core VM, coarse
  // breast). 1e-4 allows for that and still fails a press at another site or depth, which
  // moves the force by percents.
  void deepPressBuildsNoMultigridLevels() {
    sim::Scenario sc = sc_;
    sc.params.solver.preconditioner = sim::Preconditioner::Multigrid;
    sc.params.solver.force_error = 0;
    sc.params.solver.cg_tolerance = 1e-6;
    sim::Simulation patient(sc);
    const sim::DeepPress dp = sim::deep_press(sc, patient.model(), patient.materials(), 0.008);
    QVERIFY(!dp.tried.empty());
    for (const sim::PressResult& t : dp.tried) QCOMPARE(t.multigrid_builds, 0);
    const sim::PressResult own =
        sim::press_probe(sc, patient.model(), patient.materials(), dp.press.site, 0.008, dp.press.depth);
    qInfo("deep press %.6f N with block-Jacobi, %.6f N with the multigrid (%d level builds)", dp.press.force, own.force,
          own.multigrid_builds);
    QVERIFY(own.multigrid_builds >= 1);
    QVERIFY(dp.press.finite && own.finite);
    QVERIFY(std::fabs(own.force - dp.press.force) < 1e-4 * own.force);
  }

  // The tumour's contrast reaches the device with the scale; without it the clamp eats it.
  // Measured (2-core VM, nodal-pressure element): s = 0.740: with the tumour 4.87 N
  // simulated / 3.61 N sent (75 of 1,800 ticks clamped on the way down), without 4.04 /
  // 2.99 N, C 0.205 simulated, 0.206 sent; s = 1: with 4.76 / 4.00 N (876 ticks clamped),
  // without 4.00 / 4.00 N (506), C 0.192 simulated, 0.001 sent.
  void tumourContrastReachesTheDevice() {
    QVERIFY(mapping_.scale < 1.0);
    const lv::DeviceConfig cfg = lv::default_device_config();
    const double limit = std::min(cfg.loop.safety.max_force, cfg.hand.capabilities.max_force);
    double c_sim[2] = {}, c_sent[2] = {};
    const double scales[2] = {mapping_.scale, 1.0};
    for (int i = 0; i < 2; ++i) {
      const Press over = press(sc_, sim_->model(), kTumour, scales[i]);
      const Press beside = press(sc_, sim_->model(), kTumour, scales[i], /*tumour=*/false);
      c_sim[i] = contrast(over.sim, beside.sim);
      c_sent[i] = contrast(over.sent, beside.sent);
      qInfo("scale %.3f: over the tumour %.2f N simulated, %.2f N sent (clamped %llu finger-ticks); without it %.2f N simulated, "
            "%.2f N sent (clamped %llu); contrast simulated %.3f, sent %.3f",
            scales[i], over.sim, over.sent, (unsigned long long)over.clamped, beside.sim, beside.sent,
            (unsigned long long)beside.clamped, c_sim[i], c_sent[i]);
      for (const Press* p : {&over, &beside}) {
        QVERIFY(p->finite);
        QVERIFY2(p->max_sent <= limit * (1 + 1e-12), qPrintable(QString::number(p->max_sent)));
        QVERIFY(p->sim > 0.5);  // the finger did press
      }
      QVERIFY2(over.sim > beside.sim, "the tumour is stiffer");
    }
    // With the scale: at least 80 % of the simulated contrast is sent.
    // The tumour must show in the simulation for the test to measure what survives: the
    // coarse mesh gives 0.205 (above); 0.05 asks for a quarter of it.
    QVERIFY2(c_sim[0] > 0.05, qPrintable(QString::number(c_sim[0])));
    QVERIFY2(c_sent[0] >= 0.8 * c_sim[0], qPrintable(QString("sent %1 simulated %2").arg(c_sent[0]).arg(c_sim[0])));
    // Unscaled (s = 1) both presses reach the clamp: most of the contrast is lost.
    QVERIFY2(c_sent[1] < 0.5 * c_sim[1], qPrintable(QString("sent %1 simulated %2").arg(c_sent[1]).arg(c_sim[1])));
  }

  // `palpation session` sends scale x the simulated force: with a configured scale of
  // 0.05 an 18 mm press over the tumour (5 N simulated, single steps at the real-time dt
  // up to 27 N, docs/stability.md) stays far below the device's limit; unscaled it
  // reaches the clamp. loop.json reports the mapping.
  void sessionSendsScaledForces() {
    const auto site = sim::skin_site_above(sim_->model(), kTumour);
    QVERIFY(site.has_value());
    sim::Scenario s = sc_;
    sim::FingerPath fp;
    fp.radius = 0.008;
    const double z0 = site->skin.z() + 0.008 + 0.003, z1 = site->skin.z() + 0.008 - kDepth;
    fp.keys = {{0.0, kTumour.x(), 0.0, z0}, {0.3, kTumour.x(), 0.0, z0}, {1.0, kTumour.x(), 0.0, z1}, {100.0, kTumour.x(), 0.0, z1}};
    s.fingers = {fp};
    s.duration = 1.6;
    lv::SessionOptions opt;
    opt.device = "scripted";
    opt.priority = 0;
    opt.config.force_mapping.scale = 0.05;
    const lv::SessionResult r = lv::run_session(s, opt);
    const auto& fm = r.loop["force_mapping"];
    qInfo("session, scale %.2f (%s): largest desired %.3f N, largest sent %.3f N",
          fm["scale"].get<double>(), fm["rule"].get<std::string>().c_str(),
          r.loop["forces"]["largest_desired_n"].get<double>(), r.loop["forces"]["largest_sent_n"].get<double>());
    QCOMPARE(fm["scale"].get<double>(), 0.05);
    QCOMPARE(fm["rule"].get<std::string>(), std::string("configured"));
    QVERIFY(r.ok);
    const double desired = r.loop["forces"]["largest_desired_n"].get<double>();
    QVERIFY2(desired > 0.1 && desired < 2.0, qPrintable(QString::number(desired)));
    QCOMPARE(r.loop["safety"]["clamped_finger_ticks"].get<int>(), 0);
  }

  // The workstation measures the patient's scale when it loads and hands it to the GUI
  // (LiveStats, every StepSample).
  void workstationUsesThePatientsScale() {
    lv::WorkstationOptions opt;
    opt.scenario = lv::default_workstation_scenario();
    opt.haptic_priority = 0;
    lv::Workstation ws(opt);
    QCOMPARE(ws.force_mapping().scale, 1.0);  // nothing measured before the patient loads
    lv::ForceMapping seen;
    int steps = 0;
    ws.add_step_listener([&](const lv::StepSample& ss) {
      seen = ss.mapping;
      ++steps;
    });
    ws.start();
    QTRY_VERIFY_WITH_TIMEOUT((ws.poll(), steps > 10 && seen.rule == lv::ForceScaleRule::Patient), 120000);
    const lv::ForceMapping fm = ws.force_mapping();
    qInfo("workstation: scale %.3f, deep press %.2f N simulated, probe %.0f ms", fm.scale, fm.deep_press_n, fm.probe_ms);
    QCOMPARE(fm.rule, lv::ForceScaleRule::Patient);
    QVERIFY(std::fabs(fm.scale - mapping_.scale) < 0.02 * mapping_.scale);
    QCOMPARE(seen.scale, fm.scale);
    QCOMPARE(ws.stats().force_mapping.scale, fm.scale);
    ws.stop();
  }
};

QTEST_GUILESS_MAIN(TestForceMapping)
#include "tst_force_mapping.moc"
