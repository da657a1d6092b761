// Generated exam cases and curricula (app/train/case_generator.h, curriculum.h) and their
// commands: the same seed gives the same case, byte for byte; every case keeps its
// ranges and clearances and is a valid scenario that meshes; curricula name the field of
// a bad value; scores are judged against the criteria; `palpation case`, `curriculum`
// and `trainee` do what docs/training.md says.
#include <QtTest>

#include <QTemporaryDir>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "cli_run.h"
#include "phantom.h"
#include "scenario.h"
#include "simulation.h"
#include "store/patient_library.h"
#include "train/case_generator.h"
#include "train/curriculum.h"
#include "test_databases.h"

using namespace palpation;
using namespace palpation::app;

namespace {

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The curriculum parser's message for `text`, or empty when it parses.
QString curriculum_error(const std::string& text) {
  try {
    train::parse_curriculum(text, "cur.json");
  } catch (const sim::ScenarioError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

QString ranges_error(const nlohmann::json& j) {
  try {
    train::ranges_from_json(j, "r.json", "ranges");
  } catch (const sim::ScenarioError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

// A hand-made score: `found` of `tumours` tumours found, deep pressure over the first
// `deep` of them.
train::ExamScore score(int tumours, int found, int deep, int false_positives, std::array<double, 3> coverage, double exam_time) {
  train::ExamScore s;
  for (int i = 0; i < tumours; ++i) {
    train::TumourResult t;
    t.found = i < found;
    t.deep_reached = i < deep;
    t.max_level_over = t.deep_reached ? train::Level::Deep : train::Level::Medium;
    s.tumours.push_back(t);
  }
  s.hits = found;
  if (tumours > 0) s.sensitivity = double(found) / tumours;
  s.false_positives = false_positives;
  s.coverage = coverage;
  s.exam_time = exam_time;
  return s;
}

}  // namespace

class TestCases : public QObject {
  Q_OBJECT
 private slots:
  void sameSeedSameCaseByteForByte() {
    for (std::uint64_t seed : {0ull, 1ull, 1234ull, 18446744073709551615ull}) {
      const auto a = train::generate_case(seed), b = train::generate_case(seed);
      QCOMPARE(sim::scenario_to_json(a.scenario), sim::scenario_to_json(b.scenario));
      QCOMPARE(a.difficulty, b.difficulty);
    }
    // Fixed values: the sampling does not depend on the standard library's distributions,
    // so these hold on every machine (a change here changes every curriculum's cases).
    const auto c = train::generate_case(1234);
    QCOMPARE(QString::fromStdString(c.name), QString("Generated case 1234"));
    const std::string j = sim::scenario_to_json(c.scenario);
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the scenario's JSON
    for (unsigned char ch : j) h = (h ^ ch) * 1099511628211ull;
    qInfo("seed 1234: %zu tumours, difficulty %d, base radius %.4f, height %.4f, JSON hash %llu", c.scenario.inclusions.size(),
          c.difficulty, c.scenario.patient.base_radius, c.scenario.patient.height, static_cast<unsigned long long>(h));
    QCOMPARE(h, 17875743711063377574ull);  // since the layered tissue (2491436305401873305 before)
    // Different seeds, different cases.
    std::set<std::string> distinct;
    for (std::uint64_t seed = 0; seed < 20; ++seed) distinct.insert(sim::scenario_to_json(train::generate_case(seed).scenario));
    QCOMPARE(distinct.size(), std::size_t(20));
  }

  void casesKeepTheirRangesAndClearances() {
    train::CaseRanges r;  // the defaults: 0-3 tumours, 0.3-2 cm, 2-13x
    std::array<int, 4> counts{};
    std::array<int, 2> layer_counts{};  // tumours centred in the fat, in the gland
    std::set<std::string> shapes;
    std::set<int> grades;
    for (std::uint64_t seed = 0; seed < 150; ++seed) {
      const auto c = train::generate_case(seed, r);
      const sim::Scenario& s = c.scenario;
      const QByteArray where = QByteArray("seed ") + QByteArray::number(qulonglong(seed));
      QVERIFY2(int(s.inclusions.size()) >= r.tumours_min && int(s.inclusions.size()) <= r.tumours_max, where);
      ++counts[s.inclusions.size()];
      grades.insert(c.difficulty);
      QCOMPARE(c.tumours.size(), s.inclusions.size());
      // The trainee's name says nothing of the tumours.
      QCOMPARE(QString::fromStdString(c.name), QString("Generated case %1").arg(qulonglong(seed)));
      QVERIFY(s.patient.base_radius >= r.base_radius_min && s.patient.base_radius <= r.base_radius_max);
      QVERIFY(s.patient.height >= r.height_min && s.patient.height <= r.height_max);
      sim::BreastShape dome;
      dome.base_radius = s.patient.base_radius;
      dome.height = s.patient.height;
      for (std::size_t i = 0; i < s.inclusions.size(); ++i) {
        const sim::Inclusion& inc = s.inclusions[i];
        shapes.insert(inc.shape);
        const double diameter = 2 * inc.radii.maxCoeff();
        QVERIFY2(diameter >= r.diameter_min - 1e-9 && diameter <= r.diameter_max + 1e-9, where);
        // Hardness against the layer around the centre: the fat (the ranges' tissue
        // modulus) within the first centimetre, the gland (1.66x) below it.
        const double centre_depth = dome.surface_z(inc.center.x(), inc.center.y()) - inc.center.z();
        const double around = train::surrounding_modulus(s, centre_depth);
        QCOMPARE(around, centre_depth < 0.010 ? r.tissue_young : std::round(r.tissue_young * 31500.0 / 19000.0));
        ++layer_counts[centre_depth < 0.010 ? 0 : 1];
        const double ratio = inc.young_modulus / around;
        QVERIFY2(ratio >= r.hardness_min - 1e-9 && ratio <= r.hardness_max + 1e-9 && ratio <= app::train::CaseRanges::kMaxHardness, where);
        // Depth: tissue over the top, vertically (drawn on 0.1 mm, the centre on 1 um).
        const double depth = dome.surface_z(inc.center.x(), inc.center.y()) - (inc.center.z() + inc.radii.z());
        QVERIFY2(depth >= r.depth_min - 1e-9 && depth <= r.depth_max + 2e-6, where);
        // Off the chest wall, inside the skin with its clearance (points of the tumour's
        // surface, pushed out by the clearance, are still inside the dome).
        QVERIFY2(inc.center.z() - inc.radii.z() >= train::kChestWallClearance - 1e-9, where);
        for (int k = 0; k < 2000; ++k) {
          const double u = (k + 0.5) / 2000 * 2 - 1, phi = k * 2.399963;  // Fibonacci sphere
          const Eigen::Vector3d d(std::sqrt(1 - u * u) * std::cos(phi), std::sqrt(1 - u * u) * std::sin(phi), u);
          const Eigen::Vector3d p = inc.center + (inc.radii.array() * d.array()).matrix();
          QVERIFY2(dome.contains(p + 0.8 * train::kSkinClearance * Eigen::Vector3d(d.x(), d.y(), std::max(0.0, d.z()))), where);
        }
        // Not touching another tumour.
        for (std::size_t j = 0; j < i; ++j) {
          const sim::Inclusion& o = s.inclusions[j];
          QVERIFY2((inc.center - o.center).norm() >= inc.radii.maxCoeff() + o.radii.maxCoeff() + train::kTumourGap - 1e-9, where);
        }
      }
    }
    for (int n = 0; n <= 3; ++n) QVERIFY2(counts[std::size_t(n)] > 10, qPrintable(QString("%1 tumours").arg(n)));
    // The default depths (0.3-3 cm over the top) put tumours in both layers.
    qInfo("tumours centred in the fat: %d, in the gland: %d", layer_counts[0], layer_counts[1]);
    QVERIFY(layer_counts[0] > 10 && layer_counts[1] > 10);
    QVERIFY(shapes.count("sphere") && shapes.count("ellipsoid"));
    QVERIFY(grades.size() >= 3);  // the default ranges span easy to hard cases
  }

  void everyCaseParsesBackAndOneMeshes() {
    for (std::uint64_t seed = 100; seed < 140; ++seed) {
      const auto c = train::generate_case(seed);
      const std::string j = sim::scenario_to_json(c.scenario);
      const sim::Scenario back = sim::parse_scenario(j, "case.json");
      QCOMPARE(sim::scenario_to_json(back), j);  // round trip, byte for byte
      QCOMPARE(back.inclusions.size(), c.scenario.inclusions.size());
    }
    // One case with three tumours made into a model at coarse resolution: every tumour has
    // stiff elements, and the rest is its layer's tissue (fat, gland, or the harmonic
    // average of both where an element straddles their boundary).
    train::CaseRanges r;
    r.tumours_min = r.tumours_max = 3;
    r.diameter_min = 0.012;  // big enough for coarse elements to sit inside
    r.resolution = "coarse";
    const auto c = train::generate_case(7, r);
    QCOMPARE(c.scenario.inclusions.size(), std::size_t(3));
    const sim::Scenario s = sim::parse_scenario(sim::scenario_to_json(c.scenario), "case.json");
    const sim::Model m = sim::build_scenario_model(s, sim::patient_mesh(s));
    std::vector<int> stiff(s.inclusions.size(), 0);
    int tissue = 0;
    for (int e = 0; e < m.materials.size(); ++e) {
      const double E = m.materials.young[std::size_t(e)];
      if (E == m.tissue_young[std::size_t(e)]) {
        ++tissue;
        continue;
      }
      for (std::size_t i = 0; i < s.inclusions.size(); ++i)
        if (E == s.inclusions[i].young_modulus) ++stiff[i];
    }
    for (std::size_t i = 0; i < stiff.size(); ++i) QVERIFY2(stiff[i] > 0, qPrintable(QString("tumour %1").arg(i)));
    QVERIFY(tissue > m.materials.size() / 2);
    // The scorer sees three separate tumours (they do not touch), each under the skin.
    const train::SkinMap skin = train::build_skin_map(m);
    const auto truth = train::find_tumours(m.rest, m.tets, m.materials.young, m.tissue_young, skin, train::kPadRadius);
    QCOMPARE(truth.size(), std::size_t(3));
    for (const auto& t : truth) QVERIFY(t.depth > 0);
  }

  void badRangesNameTheField() {
    QVERIFY(ranges_error({{"tumours", {0, 4}}}).contains("r.json: ranges.tumours[1]: must be in [0, 3]"));
    QVERIFY(ranges_error({{"hardness", {2, 31}}}).contains("r.json: ranges.hardness: must be within 1.5..30"));
    QVERIFY(ranges_error({{"diameter", {0.02, 0.01}}}).contains("ranges.diameter: min 0.02 is above max 0.01"));
    QVERIFY(ranges_error({{"depth", "deep"}}).contains("ranges.depth: must be [min, max]"));
    QVERIFY(ranges_error({{"colour", "red"}}).contains("ranges.colour: unknown key"));
    QVERIFY(ranges_error({{"resolution", "ultra"}}).contains("ranges.resolution: unknown level \"ultra\""));
    QVERIFY(ranges_error({{"tumours", 2}, {"diameter", {0.01, 0.015}}}).isEmpty());
    // Ranges that leave no room: a clear message, every time the same.
    train::CaseRanges r;
    r.tumours_min = r.tumours_max = 3;
    r.diameter_min = r.diameter_max = 0.03;
    r.depth_min = r.depth_max = 0.04;
    r.base_radius_min = r.base_radius_max = 0.06;
    r.height_min = r.height_max = 0.045;
    QString e;
    try {
      train::generate_case(5, r, "tight.json");
    } catch (const sim::ScenarioError& ex) {
      e = QString::fromStdString(ex.what());
    }
    QVERIFY2(e.startsWith("tight.json: ranges: no room for tumour 1 of 3"), qPrintable(e));
  }

  void difficultyFollowsThePublishedFigures() {
    // Pugh: 2 cm superficial 99.6%, 2 cm deep firm 60%, deep hard 75%; silicone 0.3 cm 14%, 1 cm 87%.
    QVERIFY(std::abs(train::estimate_detection(0.02, 0.005, 2.0) - 0.996) < 1e-9);
    QVERIFY(std::abs(train::estimate_detection(0.02, 0.025, 5.6) - 0.6) < 0.01);
    QVERIFY(std::abs(train::estimate_detection(0.02, 0.03, 24) - 0.75) < 0.01);
    QVERIFY(std::abs(train::estimate_detection(0.003, 0.005, 5.6) - 0.14) < 1e-9);
    QVERIFY(std::abs(train::estimate_detection(0.01, 0.005, 5.6) - 0.87) < 1e-9);
    // Smaller, deeper, softer: harder.
    QVERIFY(train::estimate_detection(0.008, 0.01, 5) < train::estimate_detection(0.012, 0.01, 5));
    QVERIFY(train::estimate_detection(0.01, 0.02, 5) < train::estimate_detection(0.01, 0.01, 5));
    QVERIFY(train::estimate_detection(0.01, 0.02, 3) < train::estimate_detection(0.01, 0.02, 10));
    // The same estimate from the scenario alone (its depth is the drawn one rounded to 1 um).
    for (std::uint64_t seed = 0; seed < 30; ++seed) {
      const auto g = train::generate_case(seed);
      const auto d = train::scenario_difficulty(g.scenario);
      QVERIFY(d);
      QVERIFY2(std::abs(d->detection - g.detection) < 1e-4 && d->grade == g.difficulty, qPrintable(QString::number(seed)));
    }
    QCOMPARE(train::difficulty_grade(0.99), 1);
    QCOMPARE(train::difficulty_grade(0.7), 2);
    QCOMPARE(train::difficulty_grade(0.5), 3);
    QCOMPARE(train::difficulty_grade(0.3), 4);
    QCOMPARE(train::difficulty_grade(0.1), 5);
    // A case's grade is its hardest tumours': two tumours are harder than either alone.
    train::CaseRanges two;
    two.tumours_min = two.tumours_max = 2;
    const auto c = train::generate_case(3, two);
    QVERIFY(c.detection <= std::min(c.tumours[0].detection, c.tumours[1].detection) + 1e-12);
  }

  void curriculumErrorsNameFileFieldAndReason() {
    const std::string ok_a = R"({"patient": "paper-case"})", ok_b = R"({"patient": "breast-medium"})";
    struct Bad {
      std::string text;
      const char* message;
    };
    const std::vector<Bad> bad = {
        {R"({"cases": [)" + ok_a + "," + ok_b + R"(, {"patient": "x", "pass": {"min_sensitivity": 1.5}}]})",
         "cur.json: cases[2].pass.min_sensitivity: must be within 0..1, got 1.5"},
        {R"({"cases": []})", "cur.json: cases: must be a non-empty array of cases"},
        {R"({"name": "x"})", "cur.json: cases: is required"},
        {R"({"cases": [{"patient": "a", "generate": {"seed": 1}}]})", "cur.json: cases[0]: give exactly one of"},
        {R"({"cases": [{"generate": {"seed": -3}}]})", "cur.json: cases[0].generate.seed: must be a whole number >= 0"},
        {R"({"cases": [{"generate": {"seed": 1, "ranges": {"hardness": [2, 40]}}}]})",
         "cur.json: cases[0].generate.ranges.hardness: must be within 1.5..30"},
        {R"({"cases": [{"generate": {"seed": 4}}, {"generate": {"seed": 4}}]})",
         "cur.json: cases[1]: \"Generated case 4\" is already cases[0]"},
        {R"({"cases": [{"patient": "a", "pass": {"max_false_positives": -1}}]})",
         "cur.json: cases[0].pass.max_false_positives: must be in [0, 1000]"},
        {R"({"cases": [{"patient": "a", "pass": {"min_coverage": {"deep": 2}}}]})",
         "cur.json: cases[0].pass.min_coverage.deep: must be within 0..1, got 2"},
        {R"({"cases": [{"patient": "a", "pass": {"min_coverage": {"firm": 0.5}}}]})",
         "cur.json: cases[0].pass.min_coverage.firm: unknown key"},
        {R"({"cases": [{"patient": "a", "pass": {"deep_over_each_tumour": "yes"}}]})",
         "cur.json: cases[0].pass.deep_over_each_tumour: must be true or false"},
        {R"({"cases": [{"patient": "a", "pass": {"max_exam_time": 0}}]})", "cur.json: cases[0].pass.max_exam_time: must be > 0"},
        {R"({"cases": [{"patient": "a"}], "level": 3})", "cur.json: level: unknown key"},
        {R"({"cases": [{"patient": "a"})", "cur.json: (syntax): malformed JSON"},
    };
    for (const auto& b : bad) {
      const QString e = curriculum_error(b.text);
      QVERIFY2(e.startsWith(b.message), qPrintable("got: " + e + "\nexpected: " + b.message));
    }
    QVERIFY(curriculum_error(R"({"cases": [{"patient": "a"}]})").isEmpty());
    QString missing;
    try {
      train::load_curriculum("/nonexistent/cur.json");
    } catch (const sim::ScenarioError& e) {
      missing = e.what();
    }
    QVERIFY2(missing.startsWith("/nonexistent/cur.json: (file): cannot be read"), qPrintable(missing));
  }

  void casesInheritTheCurriculumsCriteria() {
    const auto c = train::parse_curriculum(R"({"name": "c", "pass": {"min_sensitivity": 1, "max_false_positives": 1,
        "min_coverage": {"light": 0.8}}, "cases": [{"patient": "a"},
        {"patient": "b", "pass": {"max_false_positives": 0, "min_coverage": {"deep": 0.5}}}]})",
                                           "c.json");
    QCOMPARE(*c.cases[0].pass.max_false_positives, 1);
    QVERIFY(!c.cases[0].pass.min_coverage[2]);
    QCOMPARE(*c.cases[1].pass.max_false_positives, 0);
    QCOMPARE(*c.cases[1].pass.min_sensitivity, 1.0);
    QCOMPARE(*c.cases[1].pass.min_coverage[0], 0.8);  // kept from the defaults
    QCOMPARE(*c.cases[1].pass.min_coverage[2], 0.5);
  }

  void theDefaultCurriculum() {
    const auto c = train::load_curriculum(PALPATION_SOURCE_DIR "/resources/curricula/cbe-basics.json");
    QVERIFY(c.cases.size() >= 5);
    const auto generated = train::check_generated(c);
    QVERIFY(!generated.empty());
    // Library cases are built-in patients (so every new library has them).
    const auto builtins = store::PatientLibrary::builtin_patients();
    std::set<std::string> builtin;
    for (const auto& p : builtins) builtin.insert(p.name);
    std::size_t g = 0;
    std::vector<int> tumours, grades;
    for (const auto& cc : c.cases) {
      if (cc.generated()) {
        tumours.push_back(int(generated[g].tumours.size()));
        grades.push_back(generated[g++].difficulty);
      } else {
        QVERIFY2(builtin.count(cc.patient), cc.patient.c_str());
        const auto p = std::find_if(builtins.begin(), builtins.end(),
                                    [&](const store::PatientRecord& r) { return r.name == cc.patient; });
        tumours.push_back(int(p->body["inclusions"].size()));
        const auto d = train::scenario_difficulty(sim::parse_scenario(store::patient_scenario(*p).dump(), p->name));
        QVERIFY(d);
        grades.push_back(d->grade);
      }
      QVERIFY(cc.pass.min_sensitivity && cc.pass.max_false_positives && cc.pass.max_exam_time && cc.pass.min_coverage[0]);
    }
    // From one easy lump to a breast without a tumour, with light coverage growing to
    // MammaCare's 96% after training.
    QCOMPARE(tumours.front(), 1);
    QCOMPARE(grades.front(), 1);
    for (std::size_t i = 1; i + 1 < grades.size(); ++i)  // never easier than the case before, up to the no-tumour one
      QVERIFY2(grades[i] >= grades[i - 1], qPrintable(QString("case %1: grade %2 after %3").arg(i + 1).arg(grades[i]).arg(grades[i - 1])));
    QVERIFY(grades[grades.size() - 2] >= 4);
    QCOMPARE(tumours.back(), 0);
    QCOMPARE(*c.cases.back().pass.max_false_positives, 0);
    QCOMPARE(*c.cases.back().pass.min_coverage[0], 0.96);
    QVERIFY(*c.cases.front().pass.min_coverage[0] < 0.96);
  }

  void evaluateAgainstTheCriteria() {
    train::PassCriteria p;
    p.min_sensitivity = 1.0;
    p.max_false_positives = 1;
    p.min_coverage = {0.9, 0.7, 0.5};
    p.deep_over_each_tumour = true;
    p.max_exam_time = 300;
    // Everything met.
    auto e = train::evaluate(p, score(2, 2, 2, 1, {0.95, 0.8, 0.6}, 250));
    QVERIFY(e.passed);
    QCOMPARE(e.criteria.size(), std::size_t(7));
    QVERIFY(e.failed().empty());
    // Each criterion fails on its own, and says why.
    struct Case {
      train::ExamScore s;
      const char* criterion;
      const char* detail;
    };
    const std::vector<Case> cases = {
        {score(2, 1, 2, 0, {0.95, 0.8, 0.6}, 250), "min_sensitivity", "sensitivity 0.50 < 1.00: 1 of 2 tumours found"},
        {score(2, 2, 2, 3, {0.95, 0.8, 0.6}, 250), "max_false_positives", "3 false positives > 1 allowed"},
        {score(2, 2, 2, 0, {0.62, 0.8, 0.6}, 250), "min_coverage.light", "light coverage 62% < 90% of the skin"},
        {score(2, 2, 2, 0, {0.95, 0.8, 0.3}, 250), "min_coverage.deep", "deep coverage 30% < 50% of the skin"},
        {score(2, 2, 1, 0, {0.95, 0.8, 0.6}, 250), "deep_over_each_tumour",
         "deep pressure reached over 1 of 2 tumours (not over tumour 2)"},
        {score(2, 2, 2, 0, {0.95, 0.8, 0.6}, 412), "max_exam_time", "exam time 412 s > 300 s"},
    };
    for (const auto& c : cases) {
      e = train::evaluate(p, c.s);
      QVERIFY(!e.passed);
      QCOMPARE(e.failed().size(), std::size_t(1));
      QCOMPARE(QString::fromStdString(e.failed().front()), QString(c.detail));
      for (const auto& r : e.criteria) QCOMPARE(r.passed, r.criterion != c.criterion);
    }
    // No tumour: sensitivity and deep pressure over tumours do not apply; a mark fails when
    // none is allowed.
    p.max_false_positives = 0;
    e = train::evaluate(p, score(0, 0, 0, 0, {0.95, 0.8, 0.6}, 250));
    QVERIFY(e.passed);
    e = train::evaluate(p, score(0, 0, 0, 1, {0.95, 0.8, 0.6}, 250));
    QVERIFY(!e.passed);
    QCOMPARE(QString::fromStdString(e.failed().front()), QString("1 false positive > 0 allowed"));
    // No criteria: passes.
    QVERIFY(train::evaluate({}, score(1, 0, 0, 5, {0, 0, 0}, 9999)).passed);
    QCOMPARE(train::to_json(e)["passed"].get<bool>(), false);
  }

  void examResultForTheLibrary() {
    train::PassCriteria p;
    p.min_sensitivity = 1.0;
    p.deep_over_each_tumour = true;
    const train::ExamScore s = score(4, 3, 1, 2, {0.9, 0.7, 0.25}, 240);
    const auto e = train::evaluate(p, s);
    const store::ExamResult r = train::exam_result(s, e, "Al", "Generated case 3", "cbe-basics", "2026-11-24T08:00:00Z", "rec/1");
    QCOMPARE(r.sensitivity.value_or(-1), 0.75);
    QCOMPARE(r.false_positives, 2);
    QCOMPARE(r.coverage_medium, 0.7);
    QCOMPARE(r.deep_reached.value_or(-1), 0.25);
    QCOMPARE(r.exam_time, 240.0);
    QVERIFY(!r.passed);
    QCOMPARE(r.score["evaluation"]["passed"].get<bool>(), false);
    QCOMPARE(QString::fromStdString(r.recording), QString("rec/1"));
    // No tumour: no sensitivity, no deep fraction; without an evaluation, not passed.
    const store::ExamResult n = train::exam_result(score(0, 0, 0, 0, {1, 1, 1}, 100), std::nullopt, "Al", "breast-medium", "");
    QVERIFY(!n.sensitivity && !n.deep_reached && !n.passed && !n.score.contains("evaluation"));
  }

  void nextCase() {
    const auto c = train::parse_curriculum(R"({"cases": [{"patient": "a"}, {"generate": {"seed": 9}}, {"patient": "b"}]})", "c.json");
    QCOMPARE(*train::next_case(c, {}), std::size_t(0));
    QCOMPARE(*train::next_case(c, {"a"}), std::size_t(1));
    QCOMPARE(*train::next_case(c, {"a", "Generated case 9"}), std::size_t(2));
    QCOMPARE(*train::next_case(c, {"b", "a"}), std::size_t(1));  // in the curriculum's order
    QVERIFY(!train::next_case(c, {"a", "b", "Generated case 9"}));
  }

  void cleanupTestCase() { test_db::drop_all(); }

  // The commands on SQLite and, with PALPATION_TEST_PG, on a PostgreSQL server.
  void commandLine_data() { test_db::add_rows(); }
  void commandLine() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    QTemporaryDir dir;
    const QString d = dir.path();
    // case generate: the same file twice, a scenario `palpation run` accepts.
    CliRun r = run_palpation({"case", "generate", "--seed", "42", "--out", d + "/a.json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.startsWith("Generated case 42: difficulty "), qPrintable(r.out));
    QVERIFY(!r.out.contains("tumour"));  // the answer only with --answer
    r = run_palpation({"case", "generate", "--seed", "42", "--out", d + "/b.json"});
    QCOMPARE(read((d + "/a.json").toStdString()), read((d + "/b.json").toStdString()));
    QCOMPARE(QString::fromStdString(read((d + "/a.json").toStdString())).trimmed().toStdString(),
             sim::scenario_to_json(train::generate_case(42).scenario));
    r = run_palpation({"case", "generate", "--seed", "-1", "--out", d + "/c.json"});
    QCOMPARE(r.code, 2);
    QVERIFY(!QFile::exists(d + "/c.json"));
    // curriculum check: the default one against a new library; a bad one exits 2 naming the field.
    const QString db = backend == "sqlite" ? d + "/lib.sqlite" : QString::fromStdString(test_db::new_library(backend, "cli"));
    QVERIFY(!db.isEmpty());
    r = run_palpation({"curriculum", "check", PALPATION_SOURCE_DIR "/resources/curricula/cbe-basics.json", "--db", db});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("valid") && r.out.contains("Generated case 1") && r.out.contains("breast-medium"), qPrintable(r.out));
    {
      std::ofstream(d.toStdString() + "/bad.json") << R"({"cases": [{"patient": "paper-case", "pass": {"min_sensitivity": 2}}]})";
      std::ofstream(d.toStdString() + "/unknown.json") << R"({"cases": [{"patient": "paper-case"}, {"patient": "nobody"}]})";
    }
    r = run_palpation({"curriculum", "check", d + "/bad.json", "--db", db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(d + "/bad.json: cases[0].pass.min_sensitivity: must be within 0..1, got 2"), qPrintable(r.err));
    r = run_palpation({"curriculum", "check", d + "/unknown.json", "--db", db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("cases[1].patient: no patient named \"nobody\""), qPrintable(r.err));
    // trainee add / list / progress.
    r = run_palpation({"trainee", "add", "Ada Lovelace", "--db", db});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = run_palpation({"trainee", "add", "Ada Lovelace", "--db", db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("trainee \"Ada Lovelace\" already exists"), qPrintable(r.err));
    {
      store::PatientLibrary lib({db.toStdString()});
      store::ExamResult x;
      x.trainee = "Ada Lovelace";
      x.case_name = "Generated case 1";
      x.curriculum = "cbe-basics";
      x.started = "2026-11-20T09:00:00Z";
      x.sensitivity = 1.0;
      x.coverage_light = 0.85;
      x.exam_time = 200;
      x.passed = true;
      x.score = {{"sensitivity", 1.0}};
      lib.record_result(x);
      x.case_name = "tumour-1.0cm-superficial-firm";
      x.started = "2026-11-21T09:00:00Z";
      x.passed = false;
      x.sensitivity = 0.0;
      lib.record_result(x);
    }
    r = run_palpation({"trainee", "progress", "Ada Lovelace", "--db", db, "--curriculum",
                   PALPATION_SOURCE_DIR "/resources/curricula/cbe-basics.json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("2026-11-20 09:00") && r.out.indexOf("Generated case 1") < r.out.indexOf("tumour-1.0cm") &&
                 r.out.contains("1 of 8 cases passed; next: 2. tumour-1.0cm-superficial-firm"),
             qPrintable(r.out));
    r = run_palpation({"trainee", "progress", "Ada Lovelace", "--db", db, "--json"});
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["results"].size(), std::size_t(2));
    QCOMPARE(j["results"][0]["case"].get<std::string>(), std::string("Generated case 1"));
    QCOMPARE(j["results"][1]["passed"].get<bool>(), false);
    r = run_palpation({"trainee", "list", "--db", db});
    QVERIFY2(r.code == 0 && r.out.contains("Ada Lovelace") && r.out.contains(": 1 trainee\n"), qPrintable(r.out + r.err));
    QVERIFY2(r.err.isEmpty(), qPrintable(r.err));  // nothing from Qt or the database driver either
    r = run_palpation({"trainee", "progress", "Nobody", "--db", db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("no trainee named \"Nobody\""), qPrintable(r.err));
  }

  // Without a desktop session (no XDG_RUNTIME_DIR: ssh, a service, CI) the command line's
  // stderr carries its own messages only, not Qt's warning about the runtime folder: a run
  // that draws its force plot (Qt's GUI part, which looks the folder up) and a trainee list.
  void stderrWithoutADesktopSession() {
    QTemporaryDir dir;
    const QString d = dir.path();
    {
      std::ofstream(d.toStdString() + "/box.json") << R"({
        "patient": {"phantom": "box", "size": [0.04, 0.04, 0.02], "resolution": 0.01},
        "tissue": {"young_modulus": 19000, "poisson_ratio": 0.45},
        "fingers": [{"radius": 0.008, "path": [[0, 0.0, 0.0, 0.029], [0.02, 0.0, 0.0, 0.027]]}],
        "duration": 0.02})";
    }
    QDir().mkpath(d + "/tmp");
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.remove("XDG_RUNTIME_DIR");
    env.remove("QT_QPA_PLATFORM");
    env.insert("TMPDIR", d + "/tmp");  // where Qt makes the folder it falls back to
    auto run = [&](const QStringList& args) { return run_palpation(args, env); };
    CliRun r = run({"run", d + "/box.json", "--out", d + "/out"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(QFile::exists(d + "/out/forces.png"));
    QVERIFY2(!r.err.contains("QStandardPaths") && !r.err.contains("XDG_RUNTIME_DIR"), qPrintable(r.err));
    r = run({"trainee", "list", "--db", d + "/lib.sqlite"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.isEmpty(), qPrintable(r.err));
    // The folder it used is the user's own and private, as Qt wants it.
    const QStringList made = QDir(d + "/tmp").entryList({"runtime-*"}, QDir::Dirs);
    QCOMPARE(made.size(), 1);
    QCOMPARE(QFile(d + "/tmp/" + made[0]).permissions() & (QFile::ReadGroup | QFile::ReadOther | QFile::WriteOther),
             QFileDevice::Permissions());
  }
};

QTEST_GUILESS_MAIN(TestCases)
#include "tst_cases.moc"
