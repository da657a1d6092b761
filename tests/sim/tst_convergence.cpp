// The mesh-convergence study (sim/convergence.h): Richardson's extrapolation against
// values of known order and limit, how a tumour's meshing is judged, and a small study on
// a box with a stiff sphere (structured meshes: no Gmsh needed).
#include <QtTest>

#include <cmath>

#include "convergence.h"
#include "mesh.h"
#include "simulation.h"

using namespace palpation::sim;

namespace {

// A 6 x 6 x 3 cm block (the chest wall at z = 0) with a 1.2 cm stiff sphere 1.5 cm deep
// under the middle of its top: a press above it feels the sphere.
Scenario block(bool tumour) {
  Scenario s;
  s.source = tumour ? "block-with-sphere" : "block";
  s.patient.phantom = "box";
  s.patient.size = Eigen::Vector3d(0.06, 0.06, 0.03);
  s.patient.resolution.clear();
  s.patient.edge = 0.006;
  if (tumour) {
    Inclusion inc;
    inc.center = Eigen::Vector3d(0, 0, 0.015);
    inc.radii = Eigen::Vector3d::Constant(0.006);
    inc.young_modulus = 10 * s.young_modulus;
    s.inclusions.push_back(inc);
  }
  return s;
}

}  // namespace

class TestConvergence : public QObject {
  Q_OBJECT

 private slots:
  // f = limit + C h^p sampled at three sizes: the fit gives back p and the limit to
  // round-off (the bisection stops at 1e-13 in p).
  void richardsonRecoversOrderAndLimit_data() {
    QTest::addColumn<double>("limit");
    QTest::addColumn<double>("c");
    QTest::addColumn<double>("order");
    QTest::newRow("order 1.5, from above") << 2.0 << 300.0 << 1.5;
    QTest::newRow("order 1, from below") << 5.0 << -40.0 << 1.0;
    QTest::newRow("order 2") << 0.3 << 1e4 << 2.0;
    QTest::newRow("order 0.5") << 1.0 << 2.0 << 0.5;
  }
  void richardsonRecoversOrderAndLimit() {
    QFETCH(double, limit);
    QFETCH(double, c);
    QFETCH(double, order);
    // Unevenly spaced, as the named levels are (11.9, 5.35, 3.63, 2.4 mm).
    const std::vector<double> h = {0.0119, 0.00535, 0.00363, 0.0024};
    std::vector<double> f;
    for (double x : h) f.push_back(limit + c * std::pow(x, order));
    const Extrapolation x = richardson(h, f);
    QVERIFY2(x.ok, x.why.c_str());
    QVERIFY2(std::fabs(x.order - order) < 1e-8, qPrintable(QString::number(x.order, 'g', 12)));
    QVERIFY2(std::fabs(x.limit - limit) < 1e-9 * (1 + std::fabs(limit)), qPrintable(QString::number(x.limit, 'g', 12)));
  }

  void richardsonClaimsNoLimitItCannotShow() {
    const std::vector<double> h = {0.01, 0.005, 0.0025};
    // Up and down: no monotone sequence, no limit.
    Extrapolation x = richardson(h, {1.0, 2.0, 1.5});
    QVERIFY(!x.ok);
    QVERIFY(x.why.find("monotone") != std::string::npos);
    QVERIFY(std::isnan(x.limit));
    // Two levels are not enough to fit an order.
    x = richardson({0.01, 0.005}, {1.0, 0.9});
    QVERIFY(!x.ok);
    QVERIFY(x.why.find("three") != std::string::npos);
    // Order 6: the differences shrink 64-fold per halving, outside [0.25, 4].
    x = richardson(h, {1.0 + std::pow(0.01, 6) * 1e12, 1.0 + std::pow(0.005, 6) * 1e12, 1.0 + std::pow(0.0025, 6) * 1e12});
    QVERIFY(!x.ok);
    QVERIFY(x.why.find("order") != std::string::npos);
    // The breast's deep press with the nodal element, coarse to fine (4.76, 2.89, 2.23 N):
    // order 0.54 fits, with a limit below zero. Not claimed.
    x = richardson({0.0119, 0.00535, 0.00363}, {4.7629, 2.8853, 2.2275});
    QVERIFY(!x.ok);
    QVERIFY(x.why.find("asymptotic") != std::string::npos);
    // Sizes must decrease.
    QVERIFY(!richardson({0.005, 0.01, 0.0025}, {1.0, 2.0, 3.0}).ok);
    // Equal values converge to themselves.
    x = richardson(h, {3.0, 3.0, 3.0});
    QVERIFY(x.ok);
    QCOMPARE(x.limit, 3.0);
  }

  // Which level is enough: the contrast excess converged from there on, the tumour
  // resolved; the force need not converge (the device's scale is set per mesh).
  void recommendedLevelFollowsTheContrast() {
    auto study = [](std::vector<double> contrast, std::vector<double> force, bool resolved_coarse) {
      ConvergenceStudy st;
      st.has_tumour = true;
      const std::vector<double> h = {0.0119, 0.00535, 0.00363, 0.0024};
      const char* names[] = {"coarse", "paper", "fine", "xfine"};
      for (std::size_t k = 0; k < contrast.size(); ++k) {
        ConvergenceLevel lv;
        lv.name = names[k];
        lv.edge = h[k];
        lv.force = force[k];
        lv.contrast = contrast[k];
        TumourResolution t;
        t.resolved = k > 0 || resolved_coarse;
        lv.tumours.push_back(t);
        st.levels.push_back(lv);
      }
      std::vector<double> hh(h.begin(), h.begin() + long(contrast.size()));
      st.force = richardson(hh, force);
      st.contrast = richardson(hh, contrast);
      return st;
    };
    // The nodal element's paper case (measured): the contrast settles from coarse on while
    // the force keeps falling. Not monotone: compared level by level.
    ConvergenceStudy st = study({1.2295, 1.2849, 1.2673, 1.2741}, {4.76, 2.89, 2.23, 1.82}, true);
    QVERIFY(!st.contrast.ok);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString("coarse"));
    // The same with the tumour too coarse on the coarse mesh: paper.
    st = study({1.2295, 1.2849, 1.2673, 1.2741}, {4.76, 2.89, 2.23, 1.82}, false);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString("paper"));
    // The linear element's (measured): 1.30 on fine, 1.38 on xfine. No level is enough.
    st = study({1.2727, 1.3026, 1.2986, 1.3759}, {5.67, 3.56, 2.64, 2.22}, true);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString());
    // A contrast converging at order 2 to 1.5: the limit judges; coarse is 0.21 off in
    // excess 0.5 (beyond 20 %), paper within.
    std::vector<double> c;
    for (double x : {0.0119, 0.00535, 0.00363, 0.0024}) c.push_back(1.5 - 1500.0 * x * x);
    st = study(c, {4, 3, 2.5, 2.2}, true);
    QVERIFY(st.contrast.ok);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString("paper"));
    // Two levels that agree: the coarser is enough, the finer one cannot be shown to be.
    st = study({1.30, 1.31}, {3, 2}, true);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString("coarse"));
    st = study({1.10, 1.31}, {3, 2}, true);
    QCOMPARE(QString::fromStdString(recommended_level(st)), QString());
  }

  // A sphere meshed by the structured block mesher (staircase: elements whose centroid is
  // inside): with 6 elements across its diameter the volume comes out within 10 %; with
  // 1.5 across it is coarse, and a sphere smaller than an element may get none at all.
  void tumourResolutionJudgesTheMesh() {
    Scenario s = block(true);
    s.patient.edge = 0.002;  // 12 mm sphere: 6 cells of 2 mm across
    Model fine = build_scenario_model(s, patient_mesh(s));
    const TumourResolution r = tumour_resolution(fine, s.inclusions[0]);
    qInfo("2 mm cells: %d elements, %.2f across, volume ratio %.3f", r.elements, r.across, r.volume_ratio);
    QVERIFY(r.elements > 100);
    QVERIFY2(std::fabs(r.volume_ratio - 1.0) < kVolumeTolerance, qPrintable(QString::number(r.volume_ratio)));
    QVERIFY(r.across > 4.0);
    QVERIFY(r.resolved);

    s.patient.edge = 0.008;  // 1.5 cells across
    Model coarse = build_scenario_model(s, patient_mesh(s));
    const TumourResolution c = tumour_resolution(coarse, s.inclusions[0]);
    qInfo("8 mm cells: %d elements, %.2f across, volume ratio %.3f", c.elements, c.across, c.volume_ratio);
    QVERIFY(!c.resolved);
    QVERIFY(c.across < kMinAcross);

    Inclusion tiny = s.inclusions[0];
    tiny.radii = Eigen::Vector3d::Constant(0.0005);
    tiny.center = Eigen::Vector3d(0.0001, 0.0001, 0.0151);
    const TumourResolution t = tumour_resolution(coarse, tiny);
    QVERIFY(!t.resolved);
    QVERIFY(t.elements <= 1);
  }

  // The study on the block at three sizes, given out of order: run coarse to fine, the
  // same press depth on every level, finite forces, the stiff sphere felt (contrast > 1)
  // on every level, the no-tumour press softer, the tumour coarse on the coarsest level.
  void studyOnABlock() {
    ConvergenceOptions o;
    o.levels = {"0.004", "0.008", "0.0055"};
    const ConvergenceStudy st = convergence_study(block(true), o);
    QCOMPARE(int(st.levels.size()), 3);
    QCOMPARE(QString::fromStdString(st.levels[0].name), QString("0.008"));
    QCOMPARE(QString::fromStdString(st.levels[2].name), QString("0.004"));
    QVERIFY(st.has_tumour);
    QVERIFY(std::fabs(st.depth - 0.3 * 0.03) < 1e-6);  // 30 % of the block under the site
    for (const auto& lv : st.levels) {
      qInfo("%s: %d nodes, force %.4f N, without the sphere %.4f N, contrast %.4f, %.1f across", lv.name.c_str(),
            lv.nodes, lv.force, lv.force_plain, lv.contrast, lv.tumours.at(0).across);
      QVERIFY(lv.finite);
      QVERIFY(lv.force > 0.1 && lv.force < 100);
      QVERIFY(lv.contrast > 1.02);
      QVERIFY(lv.force_plain < lv.force);
    }
    QVERIFY(st.levels[0].nodes < st.levels[1].nodes && st.levels[1].nodes < st.levels[2].nodes);
    QVERIFY(!st.levels[0].tumours[0].resolved);
    // A level is recommended only with every tumour resolved on it.
    if (!st.recommended.empty()) QVERIFY(st.recommended != "0.008");

    // Without the sphere: no contrast, the force itself only.
    o.levels = {"0.008", "0.006"};
    const ConvergenceStudy plain = convergence_study(block(false), o);
    QVERIFY(!plain.has_tumour);
    for (const auto& lv : plain.levels) {
      QVERIFY(std::isnan(lv.contrast));
      QCOMPARE(lv.force_plain, lv.force);
    }
    QVERIFY(!plain.force.ok);  // two levels: no limit claimed
  }

  void badLevelsAreNamed() {
    ConvergenceOptions o;
    for (const auto& [levels, word] : std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"paper", "medium"}, "medium"}, {{"0.0001"}, "0.0001"}, {{"0.005", "paper"}, "same edge"}, {{}, "none"}}) {
      o.levels = levels;
      try {
        convergence_study(block(true), o);
        QFAIL("no error");
      } catch (const ScenarioError& e) {
        QVERIFY2(std::string(e.what()).find(word) != std::string::npos, e.what());
        QVERIFY(std::string(e.what()).find("levels") != std::string::npos);
      }
    }
  }
};

QTEST_GUILESS_MAIN(TestConvergence)
#include "tst_convergence.moc"
