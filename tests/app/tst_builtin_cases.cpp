// Every built-in patient with a tumour (app/store/patient_library.cpp): is the tumour
// felt? A fingertip (8 mm) pressed quasi-statically (sim/press_probe.h: dt 10 ms, 0.4 s
// ramp, 0.2 s hold) 18 mm into the skin (the paper sweep's deep push) along the skin's
// normal, on a 7.5 mm mesh of the patient (Gmsh, refined in and around the tumour as every
// resolution is). Reported per case (docs/patient-library.md, "Is the tumour felt?"):
//   C_body = F_over / F_over(no tumour) - 1  the tumour alone: same mesh, same site, the
//                                           tissue's modulus in the tumour's elements
//   C_site = F_over / F_beside - 1          what a trainee compares: the same press 2.5 cm
//                                           beside the tumour's axis
// Felt: C_body of at least 0.15, the Weber fraction for telling two compliances apart
// (Bergmann Tiest & Kappers 2009, facts.md; at the same depth the force ratio is the
// compliance ratio). C_site mixes in the mesh: the press beside lands on coarser elements,
// which push back harder (the same site without a tumour: 4.4 N on the 7.5 mm meshes of
// mid-depth cases, 2.3 N where a superficial tumour refined the mesh under the skin), by
// more than most tumours add; it is reported, and asserted only for the paper's case.
// Measured (2-core VM, 7.5 mm): see the qInfo lines and the table in the docs.
#include <QtTest>

#include <QSqlDatabase>
#include <QSqlQuery>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "convergence.h"
#include "live/patient_choice.h"
#include "press_probe.h"
#include "scenario.h"
#include "simulation.h"
#include "store/patient_library.h"

using namespace palpation;
namespace store = palpation::app::store;
namespace lv = palpation::app::live;

namespace {

constexpr double kRadius = 0.008;  // m, index fingertip
constexpr double kDepth = 0.018;   // m below the skin
constexpr double kBeside = 0.025;  // m from the tumour's axis
// Target edge of the mesh: coarse (11.9 mm, the workstation's default) gives C_body within
// 0.1 of this mesh's but its facets make C_site meaningless (paper case +0.03); the paper
// mesh (5.35 mm) gives C_body within 0.02 of this one's except the paper case (0.20
// against 0.37), and takes 50 s for all cases against 17 s here.
constexpr double kEdge = 0.0075;
// The force-discrimination threshold (see above).
constexpr double kFelt = 0.15;
// The cases whose tumour a deep press feels (C_body >= kFelt). The others are reported:
// on this model a press 18 mm deep does not feel them (C_body below 0.06: mid-depth and
// deep tumours up to 2 cm); the 1 cm superficial firm one is at the threshold's edge
// (0.11-0.13 on the three meshes) and asserted neither way.
bool expected_felt(const std::string& name) { return name == "paper-case" || name == "tumour-2.0cm-superficial-hard"; }
bool borderline(const std::string& name) { return name == "tumour-1.0cm-superficial-firm"; }

store::PatientRecord builtin(const std::string& name) {
  for (auto& p : store::PatientLibrary::builtin_patients())
    if (p.name == name) return p;
  return {};
}

struct Contrast {
  double over = 0, beside = 0, over_plain = 0;  // N
  double site() const { return over / beside - 1.0; }
  double body() const { return over / over_plain - 1.0; }
};

}  // namespace

class TestBuiltinCases : public QObject {
  Q_OBJECT

 private slots:
  // The paper case is defined as the paper sweep has it (centre 2 cm under the skin, z =
  // 0.045 m), and a library that stored it as an older program defined it (z = 0.035 m)
  // takes the corrected definition when it is opened.
  void paperCaseMatchesTheScenario() {
    const sim::Scenario sweep = sim::builtin_scenario("paper-sweep");
    store::PatientRecord paper;
    for (auto& p : store::PatientLibrary::builtin_patients())
      if (p.name == "paper-case") paper = p;
    const sim::Scenario s = sim::parse_scenario(store::patient_scenario(paper).dump(), paper.name);
    QCOMPARE(int(s.inclusions.size()), 1);
    QVERIFY((s.inclusions[0].center - sweep.inclusions.at(0).center).norm() < 1e-12);
    QCOMPARE(s.inclusions[0].radii.x(), sweep.inclusions[0].radii.x());
    QCOMPARE(s.inclusions[0].young_modulus, sweep.inclusions[0].young_modulus);

    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("palpation-tst-builtin-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string db = (dir / "old.sqlite").string();
    fs::remove(db);
    store::PatientLibrary::Options o;
    o.db = db;
    { store::PatientLibrary lib(o); }
    {
      QSqlDatabase d = QSqlDatabase::addDatabase("QSQLITE", "tamper");
      d.setDatabaseName(QString::fromStdString(db));
      QVERIFY(d.open());
      nlohmann::json old = paper.body;
      old["inclusions"][0]["center"] = {0.125, 0.0, 0.035};
      QSqlQuery q(d);
      q.prepare("UPDATE patients SET scenario = ?, description = ? WHERE name = 'paper-case'");
      q.addBindValue(QString::fromStdString(old.dump()));
      q.addBindValue(QString("The paper's case: medium breast, tumour 3 cm diameter, 107 kPa, 1.5 cm below the skin"));
      QVERIFY(q.exec());
      QVERIFY(q.numRowsAffected() == 1);
      q.finish();
      d.close();
    }
    QSqlDatabase::removeDatabase("tamper");
    store::PatientLibrary lib(o);
    const auto got = lib.find("paper-case");
    QVERIFY(got.has_value());
    QCOMPARE(got->body["inclusions"][0]["center"][2].get<double>(), 0.045);
    QCOMPARE(QString::fromStdString(got->description), QString::fromStdString(paper.description));
    fs::remove_all(dir);
  }

  // Every graded tumour, 0.3 to 2 cm, is resolved on the coarsest breast (the
  // workstation's default): at least three elements across and its volume within 10 %
  // (sim/convergence.h). Inside a tumour the mesher asks for min(0.6 edge, half its
  // radius), so the coarse level is the worst of the four. Measured: 3.3-3.5 across, 91-92 %
  // of the volume, about 200 elements per tumour whatever its size.
  void gradedTumoursAreResolved_data() { tumourIsFelt_data(); }
  void gradedTumoursAreResolved() {
    QFETCH(QString, name);
    const store::PatientRecord rec = builtin(name.toStdString());
    sim::Scenario s = sim::parse_scenario(store::patient_scenario(rec).dump(), rec.name);
    s.patient.resolution = "coarse";
    s.patient.edge = *sim::resolution_edge("breast", "coarse");
    sim::Model m;
    try {
      m = sim::build_scenario_model(s, sim::patient_mesh(s));
    } catch (const sim::MeshUnavailable& e) {
      QSKIP(e.what());
    }
    for (const auto& inc : s.inclusions) {
      const sim::TumourResolution r = sim::tumour_resolution(m, inc);
      qInfo("%-29s r %4.1f mm: %3d elements, %.2f across, volume %.3f", rec.name.c_str(), inc.radii.minCoeff() * 1e3,
            r.elements, r.across, r.volume_ratio);
      QVERIFY2(r.resolved, qPrintable(QString("%1 across, volume ratio %2").arg(r.across).arg(r.volume_ratio)));
    }
  }

  void tumourIsFelt_data() {
    QTest::addColumn<QString>("name");
    int n = 0;
    for (const auto& p : store::PatientLibrary::builtin_patients())
      if (p.body.contains("inclusions") && !p.body["inclusions"].empty()) {
        QTest::newRow(p.name.c_str()) << QString::fromStdString(p.name);
        ++n;
      }
    QVERIFY(n >= 12);
  }

  void tumourIsFelt() {
    QFETCH(QString, name);
    const store::PatientRecord rec = builtin(name.toStdString());
    sim::Scenario s = sim::parse_scenario(store::patient_scenario(rec).dump(), rec.name);
    s.patient.edge = kEdge;
    s.backend = "cpu";
    s.fingers.clear();
    QCOMPARE(int(s.inclusions.size()), 1);
    const sim::Inclusion inc = s.inclusions[0];
    sim::Simulation body(s);
    const sim::Model& m = body.model();
    int tumour_elements = 0;
    for (int e = 0; e < m.num_tets(); ++e)
      tumour_elements += sim::is_tumour_modulus(m.materials.young[std::size_t(e)], m.tissue_young[std::size_t(e)]);
    QVERIFY2(tumour_elements > 0, "the mesh has tumour elements");
    // Without the tumour: every element its own tissue (its layer's).
    sim::Materials plain = m.materials;
    for (int e = 0; e < m.num_tets(); ++e) plain.set(e, m.tissue_young[std::size_t(e)], m.materials.poisson[std::size_t(e)]);

    const auto over = sim::skin_site_above(m, inc.center, kRadius);
    const auto beside = sim::skin_site_above(m, inc.center - Eigen::Vector3d(kBeside, 0, 0), kRadius);
    QVERIFY(over && beside);
    Contrast c;
    c.over = sim::press_probe(s, m, m.materials, *over, kRadius, kDepth).force;
    c.beside = sim::press_probe(s, m, m.materials, *beside, kRadius, kDepth).force;
    c.over_plain = sim::press_probe(s, m, plain, *over, kRadius, kDepth).force;
    const bool felt = c.body() >= kFelt;
    qInfo("%-29s centre z %.3f m, r %4.1f mm, E %3.0f kPa, %4d tumour elements of %5d: over %.2f N, beside %.2f N, over "
          "without it %.2f N; C_body %+.3f, C_site %+.3f: %s",
          rec.name.c_str(), inc.center.z(), inc.radii.x() * 1e3, inc.young_modulus / 1e3, tumour_elements, m.num_tets(),
          c.over, c.beside, c.over_plain, c.body(), c.site(), felt ? "felt" : "NOT felt");
    QVERIFY(std::isfinite(c.site()) && std::isfinite(c.body()));
    QVERIFY(c.over_plain > 1.0 && c.beside > 1.0);  // the presses reached the tissue
    // A tumour stiffer than the tissue never makes the press softer (the CG tolerance, 1e-3,
    // moves a force by far less than 0.5 %).
    QVERIFY2(c.body() > -0.005, qPrintable(QString::number(c.body())));
    if (expected_felt(rec.name)) {
      QVERIFY2(felt, qPrintable(QString("C_body %1 below %2").arg(c.body()).arg(kFelt)));
      // The paper's tumour (3 cm, 2 cm under the skin) is felt against the tissue beside it
      // too, above the mesh noise between the sites (the 0.3 cm case, C_body 0.000, gives
      // C_site -0.06 to -0.09). In the layered breast the press beside it is on stiffer
      // glandular tissue: C_site 0.141, 0.303 and >= 0.15 on three fresh Gmsh meshings of
      // one commit (the parallel mesher's mesh differs run to run): the bound is the
      // noise, 0.1.
      if (rec.name == "paper-case") QVERIFY2(c.site() >= 0.1, qPrintable(QString::number(c.site())));
    } else if (!borderline(rec.name)) {
      // Not felt now: a model change that makes it felt fails here, so the docs and this
      // list are brought up to date with it.
      QVERIFY2(!felt, qPrintable(QString("C_body %1: now felt; update expected_felt and docs/patient-library.md").arg(c.body())));
    }
  }
};

QTEST_GUILESS_MAIN(TestBuiltinCases)
#include "tst_builtin_cases.moc"
