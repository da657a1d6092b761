// The patient library: created with the built-in patients, migrations from every earlier
// schema, a newer schema refused, a locked and a corrupt database give clear errors and
// lose nothing, PostgreSQL when a server is given (PALPATION_TEST_PG).
#include <QtTest>

#include <QSqlDatabase>
#include <QSqlQuery>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "store/patient_library.h"
#include "scenario.h"

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
  void createdWithBuiltins() {
    const std::string p = tmpdb("new/sub/lib.sqlite");
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

  void addFindRemoveAndDuplicates() {
    const std::string p = tmpdb("crud.sqlite");
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
    QTest::addColumn<int>("version");
    for (int v = 1; v < PatientLibrary::kSchemaVersion; ++v) QTest::newRow(qPrintable(QString("from %1").arg(v))) << v;
  }
  void migratesFromEveryEarlierSchema() {
    QFETCH(int, version);
    const std::string p = tmpdb(qPrintable(QString("v%1.sqlite").arg(version)));
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
  }

  void newerSchemaIsRefused() {
    const std::string p = tmpdb("newer.sqlite");
    { PatientLibrary lib({p}); }
    {
      QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", "bump");
      db.setDatabaseName(QString::fromStdString(p));
      QVERIFY(db.open());
      QSqlQuery q(db);
      QVERIFY(q.exec("UPDATE meta SET value = '99' WHERE key = 'schema_version'"));
      db.close();
    }
    QSqlDatabase::removeDatabase("bump");
    const std::string before = bytes_of(p);
    const QString e = error_opening({p});
    QVERIFY2(e.contains(QString::fromStdString(p)) && e.contains("schema version 99, newer than this program's (3)"), qPrintable(e));
    QCOMPARE(bytes_of(p), before);
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
      // Opening a second library while locked: the same clear message.
      const QString e2 = error_opening({p, 200, true});
      QVERIFY2(e2.isEmpty() || e2.contains("locked"), qPrintable(e2));
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
    {
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
    }
  }
};

QTEST_GUILESS_MAIN(TestPatientLibrary)
#include "tst_patient_library.moc"
