// Training feedback against scripted exams of known answer (docs/training.md): pressure
// levels, coverage, the search pattern, marks against tumours, and scoring a recording.
// The scripted trainee (train::vertical_strip_exam) presses at depths inside each level's
// band on the default patient's rest skin; what it covers is known by construction.
#include <QtTest>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "live/live_exam.h"
#include "live/patient_choice.h"
#include "train/case_generator.h"
#include "live/workstation.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"
#include "store/recording.h"
#include "train/exam.h"
#include "train/score_recording.h"

using namespace palpation;
using namespace palpation::app::train;
namespace fs = std::filesystem;

namespace {

struct Patient {
  sim::Scenario scenario;
  std::shared_ptr<const sim::Model> model;
  std::shared_ptr<const SkinMap> skin;
  std::vector<TumourTruth> tumours;
};

Patient make_patient(sim::Scenario s) {
  Patient p;
  p.scenario = s;
  p.model = std::make_shared<sim::Model>(sim::build_scenario_model(s, sim::patient_mesh(s)));
  p.skin = std::make_shared<const SkinMap>(build_skin_map(*p.model));
  p.tumours = find_tumours(p.model->rest, p.model->tets, p.model->materials.young, p.model->tissue_young, *p.skin, kPadRadius);
  return p;
}

ExamTracker run(const Patient& p, const StripExamSpec& spec, const PressureThresholds& t = {}) {
  ExamTracker tr(p.skin, t);
  for (const FingerSample& s : vertical_strip_exam(*p.skin, t, spec)) tr.add(s);
  return tr;
}

}  // namespace

class TestTraining : public QObject {
  Q_OBJECT
  Patient paper_;  // the default patient: the paper's breast and tumour, coarse
  double cx() const { return 0.5 * (paper_.skin->lo.x() + paper_.skin->hi.x()); }  // the breast's axis

 private slots:
  void initTestCase() {
    paper_ = make_patient(app::live::default_workstation_scenario());
    QVERIFY(paper_.skin->faces.size() > 100);
    QCOMPARE(int(paper_.tumours.size()), 1);
  }

  // The levels: depth as a fraction of the thickness, or force, whichever is higher.
  void pressureLevels() {
    const PressureThresholds t;
    QCOMPARE(classify(0.0, 0.05, 0.0, t), Level::None);
    QCOMPARE(classify(0.002, 0.05, 0.0, t), Level::Light);    // 4 % of 5 cm
    QCOMPARE(classify(0.008, 0.05, 0.0, t), Level::Medium);   // 16 %
    QCOMPARE(classify(0.016, 0.05, 0.0, t), Level::Deep);     // 32 %
    QCOMPARE(classify(0.001, 0.05, 11.0, t), Level::Deep);    // shallow but 11 N
    QCOMPARE(classify(0.001, 0.05, 4.0, t), Level::Medium);
    // An instructor's thresholds: read, checked, and used.
    const PressureThresholds mine = thresholds_from_json(nlohmann::json{{"deep_depth", 0.5}});
    QCOMPARE(classify(0.016, 0.05, 0.0, mine), Level::Medium);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, thresholds_from_json(nlohmann::json{{"deep_depth", 0.1}}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, thresholds_from_json(nlohmann::json{{"deepest", 0.9}}));
  }

  // The skin and its thickness: the dome's apex is 6.5 cm above the chest wall.
  void skinThickness() {
    const SkinMap& s = *paper_.skin;
    const int apex = s.nearest_face(Eigen::Vector3d(cx(), 0, 0.07));
    QVERIFY(apex >= 0);
    QVERIFY2(std::abs(s.thickness[std::size_t(apex)] - 0.065) < 0.004,
             qPrintable(QString("apex thickness %1 m").arg(s.thickness[std::size_t(apex)])));
    for (double th : s.thickness) QVERIFY(th >= 0 && th < 0.08);
    // Every skin face faces away from the chest wall or sideways, none into it.
    // The skin's area against the half-ellipsoid's (semi-axes 8, 8, 6.5 cm: 353 cm^2 by
    // Knud Thomsen's formula, within 1.1 %); the coarse mesh's facets differ by about 1 %.
    const double a = 0.08, c = 0.065, pp = 1.6075;
    const double analytic = 0.5 * 4 * M_PI * std::pow((2 * std::pow(a * c, pp) + std::pow(a * a, pp)) / 3, 1 / pp);
    qInfo("skin area %.1f cm^2 (half-ellipsoid %.1f cm^2), %zu faces", s.total_area * 1e4, analytic * 1e4, s.faces.size());
    QVERIFY(std::abs(s.total_area / analytic - 1) < 0.03);
    // Hardly any skin looks into the chest wall: the coarse mesh's small internal void is
    // not skin (six faces, dropped as a piece of the boundary apart from the chest wall's);
    // three faces of a pocket joined to the outer skin by an edge near the rim remain.
    double down = 0;
    for (std::size_t i = 0; i < s.normal.size(); ++i)
      if (s.normal[i].z() < -0.2) down += s.area[i];
    qInfo("skin facing down: %.2f cm^2", down * 1e4);
    QVERIFY(down < 0.01 * s.total_area);
  }

  // A vertical-strip exam over the whole breast at all three levels covers it at each.
  void wholeBreastAtEveryLevel() {
    const ExamTracker tr = run(paper_, {});
    const auto c = tr.coverage();
    qInfo("coverage light %.3f medium %.3f deep %.3f, touched %.3f", c[0], c[1], c[2], tr.touched());
    for (int l = 0; l < kLevels; ++l) QVERIFY2(c[std::size_t(l)] >= 0.95, qPrintable(QString("level %1: %2").arg(l + 1).arg(c[std::size_t(l)])));
    const PatternFigures pf = tr.pattern();
    const double width = paper_.skin->hi.x() - paper_.skin->lo.x();
    qInfo("strips %d (breast %.1f cm wide, 0.6 cm apart), vertical %.2f, overlap %.2f, skipped %zu", pf.strips,
          width * 100, pf.vertical_fraction, pf.mean_overlap, pf.skipped.size());
    // Strips of at least a third of the breast's length: all but the few short ones at the
    // sides, where the round base is shorter than that.
    QVERIFY(pf.strips >= int(0.7 * width / 0.006));
    QVERIFY(pf.vertical_fraction > 0.8);
    QVERIFY(std::abs(pf.mean_overlap - (1 - 0.006 / 0.016)) < 0.1);  // 6 mm apart, 16 mm pads
    // What is left: slivers at the rim, where the skin meets the chest wall steeply.
    double skipped = 0;
    for (const auto& r : pf.skipped) skipped += r.area;
    QVERIFY(skipped < 0.05 * paper_.skin->total_area);
  }

  // Strips over the left half (x < 0) cover about half, and leave the right half skipped.
  void leftHalfIsHalf() {
    StripExamSpec spec;
    spec.x_max = cx();
    const ExamTracker tr = run(paper_, spec);
    const auto c = tr.coverage();
    qInfo("left half: light %.3f medium %.3f deep %.3f", c[0], c[1], c[2]);
    for (int l = 0; l < kLevels; ++l) QVERIFY(c[std::size_t(l)] > 0.45 && c[std::size_t(l)] < 0.6);
    const PatternFigures pf = tr.pattern();
    QVERIFY(!pf.skipped.empty());
    QVERIFY(pf.skipped.front().centre.x() > cx() + 0.01);  // the largest skipped region is on the right
    QVERIFY(pf.skipped.front().area > 0.4 * paper_.skin->total_area);
  }

  // A mark beside the tumour and one elsewhere: one hit with its error, one false positive.
  void marksAgainstTheTumour() {
    const ExamTracker tr = run(paper_, {});
    const TumourTruth& t = paper_.tumours.front();
    const Eigen::Vector3d beside = paper_.skin->project(t.skin_point + Eigen::Vector3d(0.004, 0, 0));
    const Eigen::Vector3d far = paper_.skin->skin_above(Eigen::Vector3d(cx() - 0.04, 0.02, 0));
    const ExamScore s = score_exam(tr, paper_.tumours, {{12.0, beside, 0.75}, {30.0, far, 0.5}}, 60.0);
    QCOMPARE(s.hits, 1);
    QCOMPARE(s.false_positives, 1);
    QCOMPARE(s.false_positive_marks, std::vector<int>{1});
    QVERIFY(s.tumours[0].found);
    QVERIFY2(std::abs(s.tumours[0].error - 0.004) < 0.001, qPrintable(QString("error %1 m").arg(s.tumours[0].error)));
    QCOMPARE(s.tumours[0].time_to_find, 12.0);
    QCOMPARE(*s.sensitivity, 1.0);
    QCOMPARE(*s.ppv, 0.5);
    QVERIFY(!s.specific);
    QVERIFY(s.tumours[0].deep_reached);
    // A mark just outside the tolerance misses.
    const Eigen::Vector3d off = paper_.skin->project(t.skin_point + Eigen::Vector3d(t.tolerance + 0.004, 0, 0));
    const ExamScore miss = score_exam(tr, paper_.tumours, {{5.0, off, 1.0}}, 60.0);
    QCOMPARE(miss.hits, 0);
    QCOMPARE(*miss.sensitivity, 0.0);
    const nlohmann::json j = to_json(s);
    QCOMPARE(j["tumours"][0]["hit"].get<bool>(), true);
    QVERIFY(j["tumours"][0]["position_error_m"].get<double>() > 0.003);
    QCOMPARE(j["false_positives"].get<int>(), 1);
    QVERIFY(j["coverage"].contains("total") && j["coverage"].contains("deep"));
  }

  // A light-only exam over a deep tumour: deep pressure not reached over it, and the advice
  // says so; the same strips at every level reach it.
  void lightOnlyMissesDeepPressure() {
    sim::Scenario s = app::live::default_workstation_scenario();
    s.inclusions.clear();
    sim::Inclusion deep;
    deep.center = Eigen::Vector3d(cx(), 0.0, 0.02);  // 3.7 cm under the apex's skin
    deep.radii = Eigen::Vector3d::Constant(0.008);
    deep.young_modulus = 107000;
    s.inclusions.push_back(deep);
    const Patient p = make_patient(s);
    QCOMPARE(int(p.tumours.size()), 1);
    QVERIFY(p.tumours[0].depth > 0.03);
    StripExamSpec light;
    light.levels = {Level::Light};
    const ExamScore sl = score_exam(run(p, light), p.tumours, {}, 60.0);
    QVERIFY(!sl.tumours[0].deep_reached);
    QCOMPARE(sl.tumours[0].max_level_over, Level::Light);
    QVERIFY(sl.coverage[0] > 0.95 && sl.coverage[2] < 0.01);
    bool advised = false;
    for (const auto& a : sl.advice) advised |= a.kind == app::train::Advice::Kind::PressDeep;
    QVERIFY(advised);
    const ExamScore sa = score_exam(run(p, {}), p.tumours, {}, 60.0);
    QVERIFY(sa.tumours[0].deep_reached);
  }

  // The advice is data (its kind and figures); its English line, what score.json, the report
  // and `palpation score` show, is word for word the scorer's wording.
  void adviceInEnglish() {
    using K = Advice::Kind;
    auto advice = [](K k) {
      Advice a;
      a.kind = k;
      return a;
    };
    Advice cover = advice(K::Coverage);
    cover.level = Level::Medium;
    cover.percent = 47;
    QCOMPARE(cover.text(), std::string("Cover the whole breast at medium pressure: 47% of the skin was reached at that level."));
    cover.level = Level::Light;
    cover.percent = 5;
    QCOMPARE(cover.text(), std::string("Cover the whole breast at light pressure: 5% of the skin was reached at that level."));
    cover.level = Level::Deep;
    cover.percent = 0;
    QCOMPARE(cover.text(), std::string("Cover the whole breast at deep pressure: 0% of the skin was reached at that level."));
    Advice strips = advice(K::Strips);
    strips.count = 2;
    strips.percent = 31;
    QCOMPARE(strips.text(), std::string("Search in vertical strips, head to foot, overlapping each by about a third of a finger pad: "
                                        "2 strips covered 31% of the path."));
    QCOMPARE(advice(K::Overlap).text(), std::string("Overlap neighbouring strips: they left gaps between them."));
    Advice deep = advice(K::PressDeep);
    deep.depth_mm = 37;
    QCOMPARE(deep.text(), std::string("Press deep at every spot: a lump 37 mm below the skin was missed where deep pressure was not reached."));
    Advice fp = advice(K::FalsePositives);
    fp.count = 3;
    QCOMPARE(fp.text(), std::string("Check a suspected lump at all three pressure levels before marking it: 3 mark(s) found no lump."));
    QCOMPARE(advice(K::Complete).text(), std::string("A complete examination: keep this pattern and pressure."));

    // From a score: the figures rounded as the lines write them, score.json the English lines.
    StripExamSpec spec;
    spec.x_max = cx();
    spec.levels = {Level::Light};
    const ExamScore s = score_exam(run(paper_, spec), paper_.tumours, {{3.0, paper_.skin->skin_above(Eigen::Vector3d(cx() + 0.04, 0, 0)), 1.0}}, 30.0);
    QVERIFY(!s.advice.empty());
    QCOMPARE(s.advice.front().kind, K::Coverage);
    QCOMPARE(s.advice.front().level, Level::Light);
    QCOMPARE(s.advice.front().percent, int(std::lround(100 * s.coverage[0])));
    QCOMPARE(s.advice.back().kind, K::FalsePositives);
    QCOMPARE(s.advice.back().count, 1);
    const nlohmann::json j = to_json(s);
    QCOMPARE(j["advice"].size(), s.advice.size());
    for (std::size_t i = 0; i < s.advice.size(); ++i) QCOMPARE(j["advice"][i].get<std::string>(), s.advice[i].text());
  }

  // The coverage as it grew: the time each face first reached each level gives the levels and
  // the fractions at any time, growing with it, and the tracker's at the end.
  void coverageGrowsWithTime() {
    const ExamTracker tr = run(paper_, {});
    const auto& reached = tr.face_reached();
    QCOMPARE(reached.size(), paper_.skin->faces.size());
    const double end = tr.last_contact();
    QVERIFY(end > 10);
    QVERIFY(levels_at(reached, end) == tr.face_level());
    QVERIFY(levels_at(reached, kNever) == tr.face_level());
    QVERIFY(coverage_at(*paper_.skin, reached, end) == tr.coverage());
    for (const auto& r : reached) QVERIFY(r[0] <= r[1] && r[1] <= r[2]);
    const auto none = levels_at(reached, tr.first_contact() - 1);
    QVERIFY(std::all_of(none.begin(), none.end(), [](unsigned char l) { return l == 0; }));
    std::vector<unsigned char> before = none;
    std::array<double, kLevels> was{};
    int covered_before = 0;
    for (int k = 1; k <= 10; ++k) {
      const double t = end * k / 10.0;
      const auto now = levels_at(reached, t);
      const auto c = coverage_at(*paper_.skin, reached, t);
      int covered = 0;
      for (std::size_t i = 0; i < now.size(); ++i) {
        QVERIFY(now[i] >= before[i]);
        covered += now[i] > 0;
      }
      for (int l = 0; l < kLevels; ++l) QVERIFY(c[std::size_t(l)] >= was[std::size_t(l)]);
      if (k == 2) QVERIFY2(covered < int(0.5 * now.size()), qPrintable(QString("%1 of %2 faces by a fifth of the exam").arg(covered).arg(now.size())));
      QVERIFY(covered >= covered_before);
      covered_before = covered;
      before = now;
      was = c;
    }
    // Forgotten with the rest.
    ExamTracker again = tr;
    again.reset();
    for (const auto& r : again.face_reached()) QVERIFY(r[0] == kNever && r[2] == kNever);
  }

  // No tumour: specificity counts whether anything was marked.
  void noTumourCase() {
    const ExamTracker tr = run(paper_, {});
    const Eigen::Vector3d top = paper_.skin->skin_above(Eigen::Vector3d(cx(), 0, 0));
    QCOMPARE(*score_exam(tr, {}, {}, 30.0).specific, true);
    const ExamScore s = score_exam(tr, {}, {{3.0, top, 1.0}}, 30.0);
    QCOMPARE(*s.specific, false);
    QVERIFY(!s.sensitivity);
    QCOMPARE(s.false_positives, 1);
  }

  // The workstation's live exam: simulation steps in, the overlay's per-face levels and the
  // score out, the same as the tracker's.
  void liveExam() {
    auto g = std::make_shared<app::live::PatientGeometry>();
    g->rest = paper_.model->rest;
    g->tets = paper_.model->tets;
    g->surface = paper_.model->surface;
    g->young = paper_.model->materials.young;
    g->tissue_young = paper_.scenario.young_modulus;
    g->base_young = paper_.model->tissue_young;
    g->skin = paper_.skin;
    app::live::LiveExam ex;
    ex.set_patient(g);
    ex.restart(100.0);  // the exam starts 100 s into the session
    for (const FingerSample& f : vertical_strip_exam(*paper_.skin, {}, {})) {
      app::live::StepSample st;
      st.t = 100.0 + f.t;
      for (auto& in : st.in) in.active = false;
      st.in[2] = {f.centre, Eigen::Vector3d::Zero(), f.radius, true};
      st.force[2] = Eigen::Vector3d(0, 0, 1.0);
      ex.add_step(st);
    }
    ex.add_mark(112.0, paper_.tumours.front().skin_point, 0.5);
    const auto levels = ex.surface_levels();
    QCOMPARE(levels.size(), g->surface.size());
    int deep = 0, chest = 0;
    for (std::size_t f = 0; f < levels.size(); ++f) {
      const auto& t = g->surface[f];
      const bool on_chest = paper_.model->fixed[std::size_t(t[0])] && paper_.model->fixed[std::size_t(t[1])] &&
                            paper_.model->fixed[std::size_t(t[2])];
      if (on_chest) chest += levels[f] > 0;
      else deep += levels[f] == 3;
    }
    QCOMPARE(chest, 0);
    QVERIFY(deep > int(0.9 * paper_.skin->faces.size()));
    const ScoredExam e = ex.score(g->young, 400.0);
    QCOMPARE(e.score.hits, 1);
    QCOMPARE(e.score.marks.front().t, 12.0);
    QCOMPARE(e.score.tumours.front().time_to_find, 12.0);
    QCOMPARE(e.score.duration, 300.0);
    QVERIFY(e.score.coverage[2] >= 0.95);
    // An instructor's painted tumour counts at the end: a second, superficial stiff region.
    std::vector<double> young = g->young;
    int painted = 0;
    for (std::size_t el = 0; el < g->tets.size(); ++el) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : g->tets[el]) c += g->rest[std::size_t(v)] / 4;
      if ((c - Eigen::Vector3d(cx() - 0.04, 0, 0.02)).norm() < 0.01) {
        young[el] = 60000;
        ++painted;
      }
    }
    QVERIFY(painted > 0);
    const ScoredExam e2 = ex.score(young, 400.0);
    QCOMPARE(int(e2.score.tumours.size()), 2);
    QCOMPARE(e2.score.hits, 1);
    QCOMPARE(*e2.score.sensitivity, 0.5);
  }

  // A generated case examined at the workstation (palpation-trainer --case FILE): its
  // breast and tumours, the workstation's resolution and real-time solver; a bad file is
  // refused naming it.
  void caseFileAsThePatient() {
    const fs::path dir = fs::temp_directory_path() / ("palpation-tst-training-case-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const GeneratedCase c = generate_case(7);
    const std::string path = (dir / "case.json").string();
    std::ofstream(path) << sim::scenario_to_json(c.scenario);
    const sim::Scenario s = app::live::case_patient(path, "coarse");
    const sim::Scenario ws = app::live::default_workstation_scenario();
    QCOMPARE(s.inclusions.size(), c.scenario.inclusions.size());
    for (std::size_t i = 0; i < s.inclusions.size(); ++i) {
      QCOMPARE(s.inclusions[i].center, c.scenario.inclusions[i].center);
      QCOMPARE(s.inclusions[i].young_modulus, c.scenario.inclusions[i].young_modulus);
    }
    QCOMPARE(s.patient.base_radius, c.scenario.patient.base_radius);
    // The case's tissue layers come with it (a tumour's hardness is against its layer).
    QCOMPARE(s.layers.size(), c.scenario.layers.size());
    QVERIFY(!s.layers.empty());
    for (std::size_t i = 0; i < s.layers.size(); ++i) QCOMPARE(s.layers[i].young_modulus, c.scenario.layers[i].young_modulus);
    QCOMPARE(s.patient.height, c.scenario.patient.height);
    QCOMPARE(s.patient.resolution, std::string("coarse"));
    QCOMPARE(s.params.solver.precision, ws.params.solver.precision);
    QCOMPARE(s.params.solver.cg_tolerance, ws.params.solver.cg_tolerance);
    const std::string bad = (dir / "bad.json").string();
    std::ofstream(bad) << "{\"patient\": {\"phantom\": \"breast\"}, \"fingers\": 3}";
    try {
      app::live::case_patient(bad, "coarse");
      QFAIL("a bad case file was taken");
    } catch (const sim::ScenarioError& e) {
      QVERIFY2(std::string(e.what()).find(bad) != std::string::npos, e.what());
    }
    fs::remove_all(dir);
  }

  // A recording scores like the live exam: the scripted strips as the workstation's steps,
  // a mark event at the tumour and the scenario's scripted mark elsewhere. A recording cut
  // short and a mark outside the body are refused with the file named.
  void scoresARecording() {
    const fs::path dir = fs::temp_directory_path() / ("palpation-tst-training-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    sim::Scenario sc = paper_.scenario;
    const TumourTruth& t = paper_.tumours.front();
    const Eigen::Vector3d far = paper_.skin->skin_above(Eigen::Vector3d(cx() - 0.04, 0.02, 0));
    sc.duration = 3600;
    sc.marks.push_back({20.0, far, 0.4});
    const auto samples = vertical_strip_exam(*paper_.skin, {}, {});
    auto write = [&](const std::string& path, const Eigen::Vector3d& mark_at, bool close) {
      auto w = std::make_unique<app::store::RecordingWriter>(
          path, nlohmann::json{{"scenario", nlohmann::json::parse(sim::scenario_to_json(sc))}}, 5);
      for (const FingerSample& s : samples) {
        app::store::RecordedStep st;
        st.t = s.t;
        st.h = 0.004;
        st.fingers.assign(5, {false, 0.008, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
        st.fingers[1] = {true, s.radius, s.centre, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1.0)};
        w->add_step(st);
      }
      w->add_event(10.0, "mark", {{"mark", 1}, {"position", {mark_at.x(), mark_at.y(), mark_at.z()}}, {"confidence", 0.9}});
      if (close) w->close();
      else w->flush(true);
      return w;
    };
    const std::string good = (dir / "good.palrec").string();
    write(good, t.skin_point, true);
    const ScoredExam e = score_recording(app::store::read_recording(good));
    QCOMPARE(e.score.hits, 1);
    QCOMPARE(e.score.false_positives, 1);
    QCOMPARE(int(e.score.marks.size()), 2);
    QCOMPARE(e.score.marks[0].confidence, 0.9);
    QCOMPARE(e.score.marks[1].confidence, 0.4);
    QVERIFY(e.score.coverage[2] >= 0.95);
    QVERIFY(e.score.pattern.strips > 10);
    // Cut short: the writer never closed (no end chunk).
    const std::string cut = (dir / "cut.palrec").string();
    {
      auto w = write(cut, t.skin_point, false);
      const auto rec = app::store::read_recording(cut);
      QVERIFY(!rec.complete);
      try {
        score_recording(rec);
        QFAIL("a recording cut short was scored");
      } catch (const ScoreError& err) {
        QVERIFY2(std::string(err.what()).find("cut short") != std::string::npos, err.what());
        QVERIFY(std::string(err.what()).find(cut) != std::string::npos);
      }
      w->close();
    }
    // A mark 5 cm above the skin.
    const std::string outside = (dir / "outside.palrec").string();
    write(outside, t.skin_point + Eigen::Vector3d(0, 0, 0.05), true);
    try {
      score_recording(app::store::read_recording(outside));
      QFAIL("a mark outside the body was scored");
    } catch (const ScoreError& err) {
      QVERIFY2(std::string(err.what()).find("mark 1") != std::string::npos, err.what());
      QVERIFY(std::string(err.what()).find("outside the body") != std::string::npos);
    }
    fs::remove_all(dir);
  }
};

QTEST_GUILESS_MAIN(TestTraining)
#include "tst_training.moc"
