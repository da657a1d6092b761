// The databases a library test runs against: a new SQLite file, and, when PALPATION_TEST_PG
// names a PostgreSQL server (tools/test.sh starts a private one), a new database on that
// server made for the test (the URL's user needs CREATEDB) and dropped at the end.
//
//   void thing_data() { test_db::add_rows(); }
//   void thing() {
//     QFETCH(QString, backend);
//     PALPATION_SKIP_WITHOUT_SERVER(backend);
//     const std::string where = test_db::new_library(backend, "thing");
//     ...
//   }
//   void cleanupTestCase() { test_db::drop_all(); }
#pragma once

#include <QtTest>

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QUrl>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace test_db {

inline QByteArray server() { return qgetenv("PALPATION_TEST_PG"); }

/// QTest data rows: column "backend", rows "sqlite" and "postgresql".
inline void add_rows() {
  QTest::addColumn<QString>("backend");
  QTest::newRow("sqlite") << QString("sqlite");
  QTest::newRow("postgresql") << QString("postgresql");
}

#define PALPATION_SKIP_WITHOUT_SERVER(backend)                                                                           \
  do {                                                                                                                 \
    if ((backend) == "postgresql" && test_db::server().isEmpty())                                                      \
      QSKIP("PALPATION_TEST_PG not set: no PostgreSQL server to test against (tools/test.sh starts one; "              \
            "docs/patient-library.md)");                                                                               \
    if ((backend) == "postgresql" && !QSqlDatabase::isDriverAvailable("QPSQL"))                                        \
      QSKIP("the QPSQL driver is not installed (libqt6sql6-psql)");                                                    \
  } while (0)

/// A connection of the test's own to `location` (an SQLite file or a PostgreSQL URL), open.
inline QSqlDatabase raw(const std::string& location, const QString& name) {
  const bool pg = location.rfind("postgresql://", 0) == 0;
  QSqlDatabase db = QSqlDatabase::addDatabase(pg ? "QPSQL" : "QSQLITE", name);
  if (pg) {
    const QUrl u(QString::fromStdString(location));
    db.setHostName(u.host());
    db.setPort(u.port(5432));
    db.setUserName(u.userName());
    db.setPassword(u.password());
    db.setDatabaseName(u.path().mid(1));
  } else {
    db.setDatabaseName(QString::fromStdString(location));
  }
  if (!db.open()) qWarning("%s: %s", qPrintable(name), qPrintable(db.lastError().text()));
  return db;
}

inline std::vector<std::string>& made() {
  static std::vector<std::string> v;
  return v;
}

/// Runs `sql` on the server's own database (PALPATION_TEST_PG); false and a warning when it fails.
inline bool on_server(const QString& sql) {
  bool ok = false;
  {
    QSqlDatabase db = raw(server().toStdString(), "test-db-admin");
    QSqlQuery q(db);
    ok = db.isOpen() && q.exec(sql);
    if (!ok) qWarning("%s: %s", qPrintable(sql), qPrintable(q.lastError().text()));
  }
  QSqlDatabase::removeDatabase("test-db-admin");
  return ok;
}

/// The URL of database `name` on the test server.
inline std::string server_database(const std::string& name) {
  QUrl u(QString::fromUtf8(server()));
  u.setPath("/" + QString::fromStdString(name));
  return u.toString().toStdString();
}

/// A new, empty library location: an SQLite file in a temporary folder of this process, or
/// a new database on the test server.
inline std::string new_library(const QString& backend, const std::string& name) {
  static std::atomic<int> n{0};
  if (backend == "postgresql") {
    const std::string db = "palptest_" + std::to_string(::getpid()) + "_" + std::to_string(++n);
    if (!on_server(QString::fromStdString("CREATE DATABASE " + db))) return {};
    made().push_back(db);
    return server_database(db);
  }
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("palpation-tst-db-" + std::to_string(::getpid())) /
                     (name + "-" + std::to_string(++n));
  fs::remove_all(d);
  fs::create_directories(d);
  return (d / "library.sqlite").string();
}

/// `location` as the library names it in messages (PostgreSQL: without the password).
inline QString shown(const std::string& location) {
  if (location.rfind("postgresql://", 0) != 0) return QString::fromStdString(location);
  QUrl u(QString::fromStdString(location));
  u.setPassword({});
  return u.toString();
}

/// Drops the databases made on the server, and this process's temporary folder.
inline void drop_all() {
  for (const auto& db : made()) on_server(QString::fromStdString("DROP DATABASE IF EXISTS " + db + " WITH (FORCE)"));
  made().clear();
  std::error_code ec;
  std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("palpation-tst-db-" + std::to_string(::getpid())), ec);
}

}  // namespace test_db
