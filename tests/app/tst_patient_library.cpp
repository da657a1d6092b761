// The patient library: created with the built-in patients, migrations from every earlier
// schema, a newer schema refused, a locked and a corrupt database give clear errors and
// lose nothing, trainees and their exam results. The cases that are not about SQLite's
// file run on SQLite and, when PALPATION_TEST_PG names a PostgreSQL server (tools/test.sh
// starts a private one), on a new database on that server too.
#include <QtTest>

#include <QSqlDatabase>
#include <QSqlQuery>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "store/patient_library.h"
#include "scenario.h"
#include "test_databases.h"

using namespace palpation;
using namespace palpation::app::store;
namespace fs = std::filesystem;

namespace {

std::string tmpdb(const char* name) {
  const fs::path d = fs::temp_directory_path() / ("palpation-tst-library-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path p = d / name;
  fs::remove(p);
  return p.string();
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

QString error_opening(const PatientLibrary::Options& o) {
  try {
    PatientLibrary lib(o);
  } catch (const LibraryError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

}  // namespace

class TestPatientLibrary : public QObject {
  Q_OBJECT
 private slots:
  void cleanupTestCase() {
    test_db::drop_all();
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("palpation-tst-library-" + std::to_string(::getpid())), ec);
  }

  void createdWithBuiltins_data() { test_db::add_rows(); }
  void createdWithBuiltins() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    const std::string p = backend == "sqlite" ? tmpdb("new/sub/lib.sqlite") : test_db::new_library(backend, "created");
    QVERIFY2(!p.empty(), "no database made on the test server");
    PatientLibrary lib({p});
    QCOMPARE(QString::fromStdString(lib.opened_as()), QString("created"));
    QCOMPARE(lib.schema_version(), PatientLibrary::kSchemaVersion);
    const auto v = lib.list();
    QCOMPARE(v.size(), PatientLibrary::builtin_patients().size());
    QVERIFY(lib.find("paper-case"));
    int shapes = 0, tumours = 0;
    double dmin = 1, dmax = 0, zmin = 1, zmax = 0, emin = 1e9, emax = 0;
    for (const auto& b : PatientLibrary::builtin_patients()) {
      // Every built-in patient is a valid scenario.
      const sim::Scenario s = sim::parse_scenario(patient_scenario(b).dump(), b.name);
      if (b.category == "breast") ++shapes;
      for (const auto& inc : s.inclusions) {
        ++tumours;
        dmin = std::min(dmin, 2 * inc.radii.x());
        dmax = std::max(dmax, 2 * inc.radii.x());
        zmin = std::min(zmin, inc.center.z());
        zmax = std::max(zmax, inc.center.z());
        emin = std::min(emin, inc.young_modulus);
        emax = std::max(emax, inc.young_modulus);
        // Inside the breast.
        QVERIFY2(inc.center.z() - inc.radii.z() > 0 && inc.center.z() + inc.radii.z() < s.patient.height, b.name.c_str());
      }
    }
    QVERIFY(shapes >= 4);
    QVERIFY(tumours >= 10);
    QCOMPARE(dmin, 0.003);
    QCOMPARE(dmax, 0.03);  // the paper's 3 cm; graded cases 0.3 to 2 cm
    QVERIFY(zmin < 0.015 && zmax > 0.05);  // deep near the chest wall to superficial
    QVERIFY(emin < 50000 && emax > 400000);  // soft to hard
    // Reopening: the same library, nothing added twice.
    PatientLibrary again({p});
    QCOMPARE(QString::fromStdString(again.opened_as()), QString("opened"));
    QCOMPARE(again.list().size(), v.size());
  }

  void addFindRemoveAndDuplicates_data() { test_db::add_rows(); }
  void addFindRemoveAndDuplicates() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    const std::string p = backend == "sqlite" ? tmpdb("crud.sqlite") : test_db::new_library(backend, "crud");
    QVERIFY2(!p.empty(), "no database made on the test server");
    PatientLibrary lib({p, 3000, false});
    QCOMPARE(lib.list().size(), std::size_t(0));
    PatientRecord r;
    r.name = "scan-1";
    r.category = "imported";
    r.body = {{"patient", {{"mesh", "scan-1.pmesh"}}}};
    r.mesh = std::string("\0\1\2binary\xff", 10);
    lib.add(r);
    const auto back = lib.find("scan-1");
    QVERIFY(back);
    QCOMPARE(back->mesh, r.mesh);
    QVERIFY_EXCEPTION_THROWN(lib.add(r), LibraryError);
    QCOMPARE(lib.list().size(), std::size_t(1));
    QVERIFY(lib.remove("scan-1"));
    QVERIFY(!lib.find("scan-1"));
  }

  void migratesFromEveryEarlierSchema_data() {
    QTest::addColumn<QString>("backend");
    QTest::addColumn<int>("version");
    for (const char* b : {"sqlite", "postgresql"})
      for (int v = 1; v < PatientLibrary::kSchemaVersion; ++v) QTest::newRow(qPrintable(QString("%1 from %2").arg(b).arg(v))) << QString(b) << v;
  }
  void migratesFromEveryEarlierSchema() {
    QFETCH(QString, backend);
    QFETCH(int, version);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    const std::string p = backend == "sqlite" ? tmpdb(qPrintable(QString("v%1.sqlite").arg(version)))
                                              : test_db::new_library(backend, "v" + std::to_string(version));
    QVERIFY2(!p.empty(), "no database made on the test server");
    PatientLibrary::create_old_schema_for_test(p, version);
    PatientLibrary lib({p});
    QCOMPARE(QString::fromStdString(lib.opened_as()), QString("migrated from %1").arg(version));
    QCOMPARE(lib.schema_version(), PatientLibrary::kSchemaVersion);
    const auto old = lib.find("old-patient");
    QVERIFY(old);  // kept
    QCOMPARE(old->body["patient"]["phantom"].get<std::string>(), std::string("box"));
    QCOMPARE(QString::fromStdString(old->category), version == 1 ? QString("custom") : QString("box"));
    QVERIFY(lib.find("paper-case"));  // the built-ins it lacked
    // The new schema works: an imported patient with a mesh.
    PatientRecord r;
    r.name = "after-migration";
    r.body = {{"patient", {{"mesh", "x.pmesh"}}}};
    r.mesh = "mesh";
    lib.add(r);
    QCOMPARE(lib.find("after-migration")->mesh, std::string("mesh"));
    // Trainees and results work in a migrated library.
    QVERIFY(lib.trainees().empty());
    lib.add_trainee("after-migration");
    QCOMPARE(lib.results("after-migration").size(), std::size_t(0));
  }

  // A library of the last schema without trainees, holding an imported patient's mesh:
  // opened by this program, it gains the trainee tables and keeps every patient and mesh
  // byte for byte.
  void migrationToTraineesKeepsPatientsAndMeshes() {
    const std::string p = tmpdb("v3-with-mesh.sqlite");
    PatientLibrary::create_old_schema_for_test(p, 3);
    const std::string mesh("\0\1\2mesh\xff", 8);
    {
      QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", "v3");
      db.setDatabaseName(QString::fromStdString(p));
      QVERIFY(db.open());
      QSqlQuery q(db);
      QVERIFY(q.exec("INSERT INTO patients (name, scenario, created, category, description, builtin, source) VALUES "
                     "('scan-v3', '{\"patient\": {\"mesh\": \"scan.pmesh\"}}', '2026-02-01T00:00:00Z', 'imported', 'a scan', 0, 'scan.stl')"));
      QSqlQuery m(db);
      m.prepare("INSERT INTO meshes (patient_id, format, data) SELECT id, 'pmesh', ? FROM patients WHERE name = 'scan-v3'");
      m.addBindValue(QByteArray(mesh.data(), qsizetype(mesh.size())));
      QVERIFY(m.exec());
      db.close();
    }
    QSqlDatabase::removeDatabase("v3");
    PatientLibrary lib({p});
    QCOMPARE(QString::fromStdString(lib.opened_as()), QString("migrated from 3"));
    QCOMPARE(lib.schema_version(), PatientLibrary::kSchemaVersion);
    const auto scan = lib.find("scan-v3");
    QVERIFY(scan);
    QCOMPARE(scan->mesh, mesh);
    QCOMPARE(QString::fromStdString(scan->source), QString("scan.stl"));
    QCOMPARE(QString::fromStdString(scan->created), QString("2026-02-01T00:00:00Z"));
    QVERIFY(lib.find("old-patient"));
    lib.add_trainee("first");
    QCOMPARE(lib.trainees().size(), std::size_t(1));
    // Opening it again changes nothing.
    PatientLibrary again({p});
    QCOMPARE(QString::fromStdString(again.opened_as()), QString("opened"));
    QCOMPARE(again.find("scan-v3")->mesh, mesh);
    QCOMPARE(again.trainees().size(), std::size_t(1));
  }

  void traineesAndResults_data() { test_db::add_rows(); }
  void traineesAndResults() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    const std::string p = backend == "sqlite" ? tmpdb("trainees.sqlite") : test_db::new_library(backend, "trainees");
    QVERIFY2(!p.empty(), "no database made on the test server");
    PatientLibrary lib({p, 3000, false});
    lib.add_trainee("Bea");
    lib.add_trainee("Al");
    QCOMPARE(lib.trainees().size(), std::size_t(2));
    QCOMPARE(QString::fromStdString(lib.trainees()[0].name), QString("Al"));  // by name
    QVERIFY(!lib.trainees()[0].created.empty());
    // Taken and bad names.
    auto add_error = [&](const std::string& n) {
      try {
        lib.add_trainee(n);
      } catch (const LibraryError& e) {
        return QString::fromStdString(e.what());
      }
      return QString();
    };
    QVERIFY(add_error("Al").contains("trainee \"Al\" already exists"));
    QVERIFY(add_error("").contains("must be 1 to 100 characters"));
    QVERIFY(add_error("tab\there").contains("control characters"));
    QVERIFY(add_error(" Al").contains("must not start or end with a space"));
    QCOMPARE(lib.trainees().size(), std::size_t(2));

    ExamResult r;
    r.trainee = "Al";
    r.case_name = "tumour-1.0cm-deep-firm";
    r.curriculum = "cbe-basics";
    r.duration = 310;
    r.sensitivity = 0.5;
    r.false_positives = 2;
    r.coverage_light = 0.9;
    r.coverage_medium = 0.7;
    r.coverage_deep = 0.4;
    r.deep_reached = 0.5;
    r.exam_time = 290;
    r.passed = false;
    r.score = {{"sensitivity", 0.5}, {"coverage", {{"light", 0.9}}}};
    r.recording = "/recordings/al-1";
    // Recorded out of time order: read back by start time.
    r.started = "2026-11-22T10:00:00Z";
    const auto later = lib.record_result(r);
    r.started = "2026-11-21T10:00:00Z";
    r.case_name = "paper-case";
    r.sensitivity = 1.0;
    r.false_positives = 0;
    r.passed = true;
    const auto earlier = lib.record_result(r);
    QVERIFY(later != earlier);
    // A case without tumours: no sensitivity, no deep-reached fraction (NULL, not 0).
    ExamResult none = r;
    none.case_name = "breast-medium";
    none.started = "2026-11-23T10:00:00Z";
    none.sensitivity.reset();
    none.deep_reached.reset();
    none.false_positives = 1;
    none.passed = false;
    lib.record_result(none);
    const auto v = lib.results("Al");
    QCOMPARE(v.size(), std::size_t(3));
    QCOMPARE(QString::fromStdString(v[0].case_name), QString("paper-case"));
    QCOMPARE(v[0].id, earlier);
    QCOMPARE(QString::fromStdString(v[1].case_name), QString("tumour-1.0cm-deep-firm"));
    QCOMPARE(v[1].sensitivity.value_or(-1), 0.5);
    QCOMPARE(v[1].false_positives, 2);
    QCOMPARE(v[1].coverage_medium, 0.7);
    QCOMPARE(v[1].deep_reached.value_or(-1), 0.5);
    QCOMPARE(v[1].exam_time, 290.0);
    QCOMPARE(v[1].duration, 310.0);
    QCOMPARE(v[1].passed, false);
    QCOMPARE(v[1].score, r.score);
    QCOMPARE(QString::fromStdString(v[1].recording), QString("/recordings/al-1"));
    QCOMPARE(QString::fromStdString(v[1].curriculum), QString("cbe-basics"));
    QVERIFY(!v[2].sensitivity && !v[2].deep_reached);
    QVERIFY(lib.results("Bea").empty());
    // An empty start time is now.
    ExamResult now = r;
    now.trainee = "Bea";
    now.started.clear();
    lib.record_result(now);
    QCOMPARE(lib.results("Bea").front().started.size(), std::size_t(20));

    // Unknown trainee: a LibraryError naming them, nothing written.
    auto result_error = [&](const ExamResult& x) {
      try {
        lib.record_result(x);
      } catch (const LibraryError& e) {
        return QString::fromStdString(e.what());
      }
      return QString();
    };
    ExamResult ghost = r;
    ghost.trainee = "Ghost";
    QString e = result_error(ghost);
    QVERIFY2(e.contains(test_db::shown(p)) && e.contains("no trainee named \"Ghost\""), qPrintable(e));
    e.clear();
    try {
      lib.results("Ghost");
    } catch (const LibraryError& ex) {
      e = QString::fromStdString(ex.what());
    }
    QVERIFY2(e.contains("no trainee named \"Ghost\""), qPrintable(e));
    // Bad values: the field and the reason; nothing written.
    ExamResult bad = r;
    bad.coverage_deep = 1.5;
    QVERIFY(result_error(bad).contains("exam result of \"Al\": coverage_deep: must be within 0..1, got 1.5"));
    bad = r;
    bad.started = "yesterday";
    QVERIFY(result_error(bad).contains("started: must be UTC"));
    bad = r;
    bad.exam_time = std::nan("");
    QVERIFY(result_error(bad).contains("exam_time: must be within"));
    bad = r;
    bad.score = nlohmann::json::array();
    QVERIFY(result_error(bad).contains("score: must be a JSON object"));
    QCOMPARE(lib.results("Al").size(), std::size_t(3));

    // The class: each trainee's latest and best.
    const auto cls = lib.class_summary();
    QCOMPARE(cls.size(), std::size_t(2));
    const TraineeSummary& al = cls[0];
    QCOMPARE(QString::fromStdString(al.trainee.name), QString("Al"));
    QCOMPARE(al.exams, 3);
    QCOMPARE(al.passed, 1);
    QCOMPARE(QString::fromStdString(al.latest->case_name), QString("breast-medium"));
    QCOMPARE(QString::fromStdString(al.best->case_name), QString("paper-case"));  // the one passed
    QCOMPARE(cls[1].exams, 1);
    // Best: passed first, then sensitivity, then fewer false positives.
    ExamResult a = r, b = r;
    a.passed = b.passed = false;
    a.sensitivity = 1.0;
    b.sensitivity = 0.5;
    QVERIFY(PatientLibrary::better_result(a, b) && !PatientLibrary::better_result(b, a));
    b.sensitivity = 1.0;
    b.false_positives = a.false_positives + 1;
    QVERIFY(PatientLibrary::better_result(a, b));
    b.passed = true;
    QVERIFY(PatientLibrary::better_result(b, a));

    // Removing a trainee removes their results only.
    QVERIFY(lib.remove_trainee("Bea"));
    QVERIFY(!lib.remove_trainee("Bea"));
    QCOMPARE(lib.results("Al").size(), std::size_t(3));
    QCOMPARE(lib.trainees().size(), std::size_t(1));
  }

  void newerSchemaIsRefused_data() { test_db::add_rows(); }
  void newerSchemaIsRefused() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    const std::string p = backend == "sqlite" ? tmpdb("newer.sqlite") : test_db::new_library(backend, "newer");
    QVERIFY2(!p.empty(), "no database made on the test server");
    std::size_t patients = 0;
    {
      PatientLibrary lib({p});
      patients = lib.list().size();
    }
    {
      QSqlDatabase db = test_db::raw(p, "bump");
      QVERIFY(db.isOpen());
      QSqlQuery q(db);
      QVERIFY(q.exec("UPDATE meta SET value = '99' WHERE key = 'schema_version'"));
    }
    QSqlDatabase::removeDatabase("bump");
    const std::string before = backend == "sqlite" ? bytes_of(p) : std::string();
    const QString e = error_opening({p});
    QVERIFY2(e.contains(test_db::shown(p)) && e.contains(QString("schema version 99, newer than this program's (%1)").arg(PatientLibrary::kSchemaVersion)), qPrintable(e));
    if (backend == "sqlite") {
      QCOMPARE(bytes_of(p), before);
    } else {
      // Nothing changed: the version and the patients as they were.
      {
        QSqlDatabase db = test_db::raw(p, "check");
        QSqlQuery v(db), n(db);
        QVERIFY(v.exec("SELECT value FROM meta WHERE key = 'schema_version'") && v.next());
        QCOMPARE(v.value(0).toString(), QString("99"));
        QVERIFY(n.exec("SELECT count(*) FROM patients") && n.next());
        QCOMPARE(std::size_t(n.value(0).toInt()), patients);
      }
      QSqlDatabase::removeDatabase("check");
    }
  }

  void lockedDatabaseGivesAClearErrorAndLosesNothing() {
    const std::string p = tmpdb("locked.sqlite");
    PatientLibrary lib({p, 200, true});
    const std::size_t n = lib.list().size();
    {
      // Another program holds the write lock.
      QSqlDatabase other = QSqlDatabase::addDatabase("QSQLITE", "other-writer");
      other.setDatabaseName(QString::fromStdString(p));
      QVERIFY(other.open());
      QSqlQuery q(other);
      QVERIFY(q.exec("BEGIN EXCLUSIVE"));
      PatientRecord r;
      r.name = "while-locked";
      r.body = {{"patient", {{"phantom", "box"}}}};
      QString e;
      try {
        lib.add(r);
      } catch (const LibraryError& ex) {
        e = QString::fromStdString(ex.what());
      }
      QVERIFY2(e.contains(QString::fromStdString(p)) && e.contains("locked by another program"), qPrintable(e));
      // Opening a second library while locked: the same clear message (opening reads the
      // schema, which the exclusive lock forbids).
      const QString e2 = error_opening({p, 200, true});
      QVERIFY2(e2.contains(QString::fromStdString(p)) && e2.contains("locked by another program"), qPrintable(e2));
      QVERIFY(q.exec("ROLLBACK"));
      other.close();
    }
    QSqlDatabase::removeDatabase("other-writer");
    // Nothing lost, and writing works again.
    QCOMPARE(lib.list().size(), n);
    QVERIFY(!lib.find("while-locked"));
    PatientRecord r;
    r.name = "after-lock";
    r.body = {{"patient", {{"phantom", "box"}}}};
    lib.add(r);
    QCOMPARE(lib.list().size(), n + 1);
  }

  void corruptDatabaseGivesAClearErrorAndIsLeftAlone() {
    const std::string p = tmpdb("corrupt.sqlite");
    {
      std::ofstream f(p, std::ios::binary);
      for (int i = 0; i < 512; ++i) f << "garbage!";
    }
    const std::string before = bytes_of(p);
    QString e = error_opening({p});
    QVERIFY2(e.contains(QString::fromStdString(p)) && e.contains("not a patient library"), qPrintable(e));
    QCOMPARE(bytes_of(p), before);
    // A real library whose pages were damaged in the middle.
    const std::string q = tmpdb("damaged.sqlite");
    { PatientLibrary lib({q}); }
    std::string b = bytes_of(q);
    for (std::size_t i = 0; i < b.size(); ++i)
      if (i >= 100 && i % 7 == 0) b[i] = char(0xA5);
    { std::ofstream(q, std::ios::binary | std::ios::trunc) << b; }
    e.clear();
    try {
      PatientLibrary lib({q});
      lib.list();
      for (const auto& x : lib.list()) lib.find(x.name);
    } catch (const LibraryError& ex) {
      e = QString::fromStdString(ex.what());
    }
    QVERIFY2(e.contains(QString::fromStdString(q)) && (e.contains("corrupted") || e.contains("not a patient library")), qPrintable(e));
    QCOMPARE(bytes_of(q), b);
    // Another library next to it is unaffected.
    PatientLibrary fine({tmpdb("fine.sqlite")});
    QVERIFY(fine.find("paper-case"));
  }

  void defaultLocation() {
    qputenv("PALPATION_DB", "/tmp/somewhere/lib.sqlite");
    QCOMPARE(QString::fromStdString(PatientLibrary::default_location()), QString("/tmp/somewhere/lib.sqlite"));
    qunsetenv("PALPATION_DB");
    QVERIFY(QString::fromStdString(PatientLibrary::default_location()).endsWith("/patients.sqlite"));
  }

  // The same code against a PostgreSQL server: PALPATION_TEST_PG=postgresql://user:pass@host:port/db
  void postgres() {
    const QByteArray url = qgetenv("PALPATION_TEST_PG");
    if (url.isEmpty()) QSKIP("PALPATION_TEST_PG not set: no PostgreSQL server to test against (docs/patient-library.md)");
    if (!QSqlDatabase::isDriverAvailable("QPSQL")) QSKIP("the QPSQL driver is not installed (libqt6sql6-psql)");
    // A server named but unreachable (or failing mid-test) is a failure with its message,
    // not an exception out of the test function (QtTest rethrows it: the suite aborts).
    try {
      PatientLibrary lib({url.toStdString()});
      QVERIFY(lib.is_postgres());
      QCOMPARE(lib.schema_version(), PatientLibrary::kSchemaVersion);
      lib.remove("pg-test");
      PatientRecord r;
      r.name = "pg-test";
      r.body = {{"patient", {{"mesh", "x.pmesh"}}}};
      r.mesh = std::string("\0\1\2", 3);
      lib.add(r);
      QCOMPARE(lib.find("pg-test")->mesh, r.mesh);
      QVERIFY(lib.find("paper-case"));
      QVERIFY(lib.remove("pg-test"));
      // Trainees and results: NULLs, doubles and order by time on PostgreSQL too.
      lib.remove_trainee("pg-trainee");
      lib.add_trainee("pg-trainee");
      ExamResult x;
      x.trainee = "pg-trainee";
      x.case_name = "paper-case";
      x.started = "2026-11-22T10:00:00Z";
      x.coverage_deep = 0.123456789;
      x.score = {{"x", 1}};
      lib.record_result(x);
      x.started = "2026-11-21T10:00:00Z";
      x.sensitivity = 0.5;
      lib.record_result(x);
      const auto v = lib.results("pg-trainee");
      QCOMPARE(v.size(), std::size_t(2));
      QCOMPARE(v[0].sensitivity.value_or(-1), 0.5);
      QVERIFY(!v[1].sensitivity);
      QCOMPARE(v[1].coverage_deep, 0.123456789);
      QVERIFY(!lib.class_summary().empty());
      QVERIFY(lib.remove_trainee("pg-trainee"));
    } catch (const std::exception& e) {
      QFAIL(qPrintable(QString("PALPATION_TEST_PG: ") + e.what()));
    }
  }
};

QTEST_GUILESS_MAIN(TestPatientLibrary)
#include "tst_patient_library.moc"
