#include "store/patient_library.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QStandardPaths>
#include <QUrl>
#include <QVariant>

#include "scenario.h"
#include "tissue_layers.h"

namespace palpation::app::store {

using nlohmann::json;

namespace {

std::atomic<int> g_connections{0};

std::string utc_now() {
  std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

QString q(const std::string& s) { return QString::fromStdString(s); }

// The schema's history: step 0 creates version 1, step k migrates version k to k + 1.
// Written once per version and never changed afterwards (databases out there hold them).
std::vector<std::vector<std::string>> schema_steps(bool pg) {
  const std::string pk = pg ? "SERIAL PRIMARY KEY" : "INTEGER PRIMARY KEY";
  const std::string blob = pg ? "BYTEA" : "BLOB";
  return {
      // version 1: patients as a JSON scenario fragment.
      {"CREATE TABLE meta (key VARCHAR(64) PRIMARY KEY, value TEXT NOT NULL)",
       "CREATE TABLE patients (id " + pk + ", name VARCHAR(200) UNIQUE NOT NULL, scenario TEXT NOT NULL, "
       "created VARCHAR(32) NOT NULL)",
       "INSERT INTO meta (key, value) VALUES ('schema_version', '1')"},
      // 1 -> 2: category, description, built-in flag.
      {"ALTER TABLE patients ADD COLUMN category VARCHAR(64) NOT NULL DEFAULT 'custom'",
       "ALTER TABLE patients ADD COLUMN description TEXT NOT NULL DEFAULT ''",
       "ALTER TABLE patients ADD COLUMN builtin INTEGER NOT NULL DEFAULT 0",
       "UPDATE meta SET value = '2' WHERE key = 'schema_version'"},
      // 2 -> 3: imported scans (source file, tetrahedral mesh).
      {"ALTER TABLE patients ADD COLUMN source TEXT NOT NULL DEFAULT ''",
       "CREATE TABLE meshes (patient_id INTEGER PRIMARY KEY, format VARCHAR(16) NOT NULL, data " + blob + " NOT NULL)",
       "UPDATE meta SET value = '3' WHERE key = 'schema_version'"},
      // 3 -> 4: trainees and their exam results (the figures as columns for the instructor's
      // queries, the whole score as JSON). Timestamps are UTC ISO 8601 text, which sorts.
      {"CREATE TABLE trainees (id " + pk + ", name VARCHAR(200) UNIQUE NOT NULL, created VARCHAR(32) NOT NULL)",
       "CREATE TABLE exam_results (id " + pk + ", trainee_id INTEGER NOT NULL REFERENCES trainees (id), "
       "case_name VARCHAR(200) NOT NULL, curriculum VARCHAR(200) NOT NULL DEFAULT '', started VARCHAR(32) NOT NULL, "
       "duration DOUBLE PRECISION NOT NULL, sensitivity DOUBLE PRECISION, false_positives INTEGER NOT NULL, "
       "coverage_light DOUBLE PRECISION NOT NULL, coverage_medium DOUBLE PRECISION NOT NULL, "
       "coverage_deep DOUBLE PRECISION NOT NULL, deep_reached DOUBLE PRECISION, exam_time DOUBLE PRECISION NOT NULL, "
       "passed INTEGER NOT NULL, score TEXT NOT NULL, recording TEXT NOT NULL DEFAULT '')",
       "CREATE INDEX exam_results_by_trainee ON exam_results (trainee_id, started)",
       "UPDATE meta SET value = '4' WHERE key = 'schema_version'"},
  };
}

// A QSqlError as a one-line reason, with the common SQLite cases made plain (libpq's
// messages come on several lines: joined).
std::string reason(const QSqlError& e) {
  const std::string t = e.text().simplified().toStdString();
  const std::string lower = e.text().toLower().toStdString();
  if (lower.find("locked") != std::string::npos || lower.find("busy") != std::string::npos)
    return "the library is locked by another program writing to it (" + t + "); try again when it has finished";
  if (lower.find("not a database") != std::string::npos || lower.find("malformed") != std::string::npos)
    return "not a patient library, or a corrupted one (" + t + "); the file was left as it is";
  return t.empty() ? std::string("unknown database error") : t;
}

// The built-in breasts' tissue layers (fat over glandular tissue: sim::breast_layers) as the
// scenario contract writes them.
json breast_layers_json() {
  sim::Scenario s;
  s.layers = sim::breast_layers();
  return json::parse(sim::scenario_to_json(s))["tissue"]["layers"];
}

json fragment(const json& patient, double e = 19000.0, json inclusions = json::array()) {
  return {{"patient", patient},
          {"tissue", {{"young_modulus", e}, {"poisson_ratio", 0.45}, {"density", 1000}, {"layers", breast_layers_json()}}},
          {"inclusions", inclusions}};
}

}  // namespace

// ---------------------------------------------------------------- built-in patients

std::string english_description(const BuiltinDescription& d) {
  using D = BuiltinDescription;
  char buf[200];
  switch (d.kind) {
    case D::Kind::Healthy: {
      const char* size = d.size == D::Size::Small      ? "small"
                         : d.size == D::Size::Medium   ? "medium"
                         : d.size == D::Size::Large    ? "large"
                         : d.size == D::Size::WideFlat ? "wide and flat"
                                                       : "narrow and projecting";
      std::string ml = std::to_string(d.volume_ml);
      if (d.volume_ml >= 1000) ml.insert(ml.size() - 3, ",");
      return std::string("Healthy breast, ") + size + " (" + ml + " mL)" + (d.paper_size ? ", the paper's size" : "") +
             ", no tumour";
    }
    case D::Kind::PaperCase: return "The paper's case: medium breast, tumour 3 cm diameter, 107 kPa, centre 2.0 cm below the skin";
    case D::Kind::Tumour: {
      const char* hard = d.hardness == D::Hardness::Soft ? "soft" : d.hardness == D::Hardness::Hard ? "hard" : "firm";
      std::snprintf(buf, sizeof buf, "Medium breast, %s tumour %.1f cm diameter (%.0f kPa), centre %.1f cm below the skin", hard,
                    d.diameter_cm, d.young_kpa, d.depth_cm);
      return buf;
    }
  }
  return {};
}

namespace {
// The built-in patients with their descriptions as data.
struct Builtin {
  PatientRecord record;
  BuiltinDescription description;
};
std::vector<Builtin> make_builtins();
}  // namespace

std::optional<BuiltinDescription> builtin_description(const std::string& name) {
  static const std::vector<Builtin> all = make_builtins();
  for (const auto& b : all)
    if (b.record.name == name) return b.description;
  return std::nullopt;
}

std::vector<PatientRecord> PatientLibrary::builtin_patients() {
  std::vector<PatientRecord> v;
  for (auto& b : make_builtins()) v.push_back(std::move(b.record));
  return v;
}

namespace {
std::vector<Builtin> make_builtins() {
  using D = BuiltinDescription;
  std::vector<Builtin> v;
  auto add = [&](std::string name, std::string cat, const D& desc, json body) {
    PatientRecord p;
    p.name = std::move(name);
    p.category = std::move(cat);
    p.description = english_description(desc);
    p.body = std::move(body);
    p.builtin = true;
    v.push_back({std::move(p), desc});
  };
  // Breast sizes and shapes: half-ellipsoid domes, volume 2/3 pi a^2 h (facts.md: about
  // 250 mL small to 1,250 mL large, 560-975 mL typical). Layered tissue (fragment):
  // fat at 19 kPa (the paper's value; Krouskop 1998 fat at 5% precompression 18-20 kPa)
  // and glandular tissue, where the tumours lie.
  struct Shape {
    const char* name;
    double a, h;
    D::Size size;
    int ml;
    bool paper;
  };
  const Shape shapes[] = {{"breast-small", 0.060, 0.045, D::Size::Small, 339, false},
                          {"breast-medium", 0.080, 0.065, D::Size::Medium, 871, true},
                          {"breast-large", 0.088, 0.077, D::Size::Large, 1249, false},
                          {"breast-flat", 0.085, 0.045, D::Size::WideFlat, 681, false},
                          {"breast-projecting", 0.065, 0.075, D::Size::NarrowProjecting, 664, false}};
  for (const auto& s : shapes) {
    json p = {{"phantom", "breast"}, {"resolution", "paper"}, {"base_radius", s.a}, {"height", s.h}};
    D d;
    d.kind = D::Kind::Healthy;
    d.size = s.size;
    d.volume_ml = s.ml;
    d.paper_size = s.paper;
    add(s.name, "breast", d, fragment(p));
  }
  // The paper's case: tumour radius 1.5 cm, E 107 kPa, on the axis at x = 0.125 m, its
  // centre 2 cm below the skin as in the paper-sweep scenario (sim/scenario_builtin.cpp;
  // 3 cm below, the sweep's tumour/no-tumour force ratio was only 1.02-1.04).
  const json medium = {{"phantom", "breast"}, {"resolution", "paper"}};
  D paper_case;
  paper_case.kind = D::Kind::PaperCase;
  add("paper-case", "tumour", paper_case,
      fragment(medium, 19000.0,
               json::array({{{"shape", "sphere"}, {"center", {0.125, 0.0, 0.045}}, {"radius", 0.015}, {"young_modulus", 107000}}})));
  // Graded cases on the medium breast (skin at z = 0.065 m on the axis, chest wall z = 0).
  // Hardness (Krouskop 1998, 5% / 20% precompression; Samani 2007 ratios to fat):
  //   soft 38 kPa (2x fat, fibroadenoma-like), firm 107 kPa (fibrous / IDC at 5%, the
  //   paper's), hard 460 kPa (IDC at 20% precompression).
  // Depth of the centre below the skin: superficial 0.5 cm + radius, mid 2.5 cm, deep: 1.2 cm
  // above the chest wall. Diameters 0.3 to 2 cm (0.3 cm: the expert detection limit).
  const double skin = 0.065;
  auto tumour = [&](double d_cm, const std::string& depth, const std::string& hard) {
    const double r = d_cm * 0.005;  // cm diameter -> m radius
    double z = skin - 0.025;
    if (depth == "superficial") z = skin - 0.005 - r;
    if (depth == "deep") z = 0.012;
    const double e = hard == "soft" ? 38000.0 : hard == "hard" ? 460000.0 : 107000.0;
    char name[64];
    std::snprintf(name, sizeof name, "tumour-%.1fcm-%s-%s", d_cm, depth.c_str(), hard.c_str());
    D desc;
    desc.kind = D::Kind::Tumour;
    desc.hardness = hard == "soft" ? D::Hardness::Soft : hard == "hard" ? D::Hardness::Hard : D::Hardness::Firm;
    desc.diameter_cm = d_cm;
    desc.young_kpa = e / 1000.0;
    desc.depth_cm = (skin - z) * 100.0;
    add(name, "tumour", desc,
        fragment(medium, 19000.0,
                 json::array({{{"shape", "sphere"}, {"center", {0.125, 0.0, z}}, {"radius", r}, {"young_modulus", e}}})));
  };
  for (double d : {0.3, 0.5, 1.0, 1.5, 2.0}) tumour(d, "mid", "firm");         // size
  for (const char* depth : {"superficial", "deep"}) tumour(1.0, depth, "firm");  // depth
  for (const char* h : {"soft", "hard"}) tumour(1.0, "mid", h);                  // hardness
  tumour(0.5, "deep", "soft");                                                   // the hardest to find
  tumour(2.0, "superficial", "hard");                                            // the easiest
  return v;
}
}  // namespace

json patient_scenario(const PatientRecord& p, const std::string& mesh_file) {
  json s = p.body;
  if (!mesh_file.empty()) s["patient"]["mesh"] = mesh_file;
  if (s.contains("fingers")) {  // the patient brings its own press (imported scans: over the top)
    if (!s.contains("duration")) s["duration"] = 2.0;
    return s;
  }
  // A default press: over the first inclusion, else over the breast's axis / the origin.
  double x = 0.0, top = 0.1;
  if (s["patient"].value("phantom", "") == "breast") {
    x = 0.125;
    top = s["patient"].value("height", 0.065);
  }
  if (!s["inclusions"].empty()) x = s["inclusions"][0]["center"][0].get<double>();
  const double r = 0.008;
  s["fingers"] = json::array({{{"radius", r}, {"path", {{0.0, x, 0.0, top + r + 0.005}, {1.0, x, 0.0, top + r - 0.01}, {2.0, x, 0.0, top + r + 0.005}}}}});
  s["duration"] = 2.0;
  return s;
}

// ---------------------------------------------------------------- the database

std::string PatientLibrary::default_location() {
  if (const char* e = std::getenv("PALPATION_DB"); e && *e) return e;
  if (QCoreApplication::applicationName().isEmpty()) QCoreApplication::setApplicationName("palpation");
  QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
  if (dir.isEmpty()) dir = QDir::homePath() + "/.local/share/palpation";
  return (dir + "/patients.sqlite").toStdString();
}

namespace {

// One transaction on a connection, ended once: rollback() after a commit or a rollback
// does nothing, and one still open when the guard goes (a throw) is rolled back, so a
// failed change leaves what was saved as it was. Begun by Qt (QSqlDatabase::transaction)
// or by a statement of the caller's (SQLite's BEGIN IMMEDIATE takes the write lock at
// once); it then ends by statements too, since Qt's driver did not see it begin.
class Transaction {
 public:
  explicit Transaction(QSqlDatabase db) : db_(std::move(db)) {}
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction() { rollback(); }
  /// False (error() says why) when it did not begin.
  bool begin(const QString& statement = {}) {
    by_statement_ = !statement.isEmpty();
    if (by_statement_) {
      QSqlQuery b(db_);
      open_ = b.exec(statement);
      if (!open_) error_ = b.lastError();
    } else {
      open_ = db_.transaction();
      if (!open_) error_ = db_.lastError();
    }
    return open_;
  }
  /// False (error() says why, and the transaction is rolled back) when it did not commit.
  bool commit() {
    QSqlQuery c(db_);
    const bool ok = by_statement_ ? c.exec("COMMIT") : db_.commit();
    if (ok) {
      open_ = false;
      return true;
    }
    error_ = by_statement_ ? c.lastError() : db_.lastError();
    rollback();
    return false;
  }
  void rollback() {
    if (!open_) return;
    open_ = false;
    if (by_statement_)
      QSqlQuery(db_).exec("ROLLBACK");
    else
      db_.rollback();
  }
  const QSqlError& error() const { return error_; }

 private:
  QSqlDatabase db_;
  bool open_ = false, by_statement_ = false;
  QSqlError error_;
};

// A PostgreSQL URL as messages show it: without the password.
std::string hide_password(const std::string& url) {
  QUrl u(q(url));
  u.setPassword({});
  return u.toString().toStdString();
}

// Sets up (does not open) a connection to `where`, SQLite file or PostgreSQL URL; returns
// the location as shown in messages (the password hidden).
std::string configure(QSqlDatabase& db, const std::string& where, bool pg, int busy_timeout_ms, int connect_timeout_s) {
  if (!pg) {
    db.setDatabaseName(q(where));
    db.setConnectOptions(q("QSQLITE_BUSY_TIMEOUT=" + std::to_string(busy_timeout_ms)));
    return where;
  }
  const QUrl u(q(where));
  db.setHostName(u.host());
  if (u.port() > 0) db.setPort(u.port());
  db.setUserName(u.userName());
  db.setPassword(u.password());
  db.setDatabaseName(u.path().mid(1));
  if (connect_timeout_s > 0) db.setConnectOptions(q("connect_timeout=" + std::to_string(connect_timeout_s)));
  return hide_password(where);
}

bool is_postgres_url(const std::string& s) { return s.rfind("postgresql://", 0) == 0 || s.rfind("postgres://", 0) == 0; }

// A unique-key violation: two stations adding the same name at once.
bool is_duplicate(const QSqlError& e) {
  const QString t = e.text().toLower();
  return t.contains("duplicate key") || t.contains("unique constraint");
}

// Every station opening a library takes this lock while it migrates and seeds it
// (pg_advisory_xact_lock: PostgreSQL's transaction-scoped lock on a number of the
// program's choosing), so that the first ones to connect at once do not both create it.
constexpr const char* kPgMigrationLock = "SELECT pg_advisory_xact_lock(7207150)";

// Counts the library's operations under way (PatientLibrary::with_server).
struct Nested {
  int& depth;
  explicit Nested(int& d) : depth(d) { ++depth; }
  ~Nested() { --depth; }
};

}  // namespace

PatientLibrary::PatientLibrary(const Options& opt) {
  where_ = opt.db.empty() ? default_location() : opt.db;
  conn_ = "palpation-library-" + std::to_string(++g_connections);
  pg_ = is_postgres_url(where_);
  const char* driver = pg_ ? "QPSQL" : "QSQLITE";
  if (!QSqlDatabase::isDriverAvailable(driver))
    throw LibraryError((pg_ ? hide_password(where_) : where_) + ": the Qt SQL driver " + driver + " is not installed (Debian: " +
                       (pg_ ? "libqt6sql6-psql" : "libqt6sql6-sqlite") + ")");
  {
    QSqlDatabase db = QSqlDatabase::addDatabase(driver, q(conn_));
    if (!pg_) {
      const QFileInfo fi(q(where_));
      if (fi.exists() && !fi.isFile()) throw LibraryError(where_ + ": not a file");
      if (!QDir().mkpath(fi.absolutePath()))
        throw LibraryError(where_ + ": cannot create the folder " + fi.absolutePath().toStdString());
    }
    where_ = configure(db, where_, pg_, opt.busy_timeout_ms, opt.connect_timeout_s);
    if (!db.open()) {
      const std::string why = reason(db.lastError());
      db = QSqlDatabase();
      QSqlDatabase::removeDatabase(q(conn_));
      if (pg_) throw ServerUnavailable(where_ + ": cannot reach the PostgreSQL server: " + why);
      throw LibraryError(where_ + ": cannot open the patient library: " + why);
    }
  }
  if (pg_) {
    pending_dir_ = opt.pending_dir;
    if (pending_dir_.empty()) {
      if (QCoreApplication::applicationName().isEmpty()) QCoreApplication::setApplicationName("palpation");
      QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
      if (dir.isEmpty()) dir = QDir::homePath() + "/.local/share/palpation";
      pending_dir_ = (dir + "/pending-results").toStdString();
    }
  }
  try {
    {
      Nested n(depth_);  // lookups while migrating are part of its transactions
      migrate(opt.seed);
    }
    // Results kept on this station while the server was away go now; a server that went
    // away again meanwhile leaves them kept.
    if (pg_ && !pending().empty()) {
      try {
        send_pending();
      } catch (const ServerUnavailable&) {
      }
    }
  } catch (...) {
    QSqlDatabase::database(q(conn_), false).close();
    QSqlDatabase::removeDatabase(q(conn_));
    throw;
  }
}

PatientLibrary::~PatientLibrary() {
  {
    QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
    if (db.isValid()) db.close();
  }
  QSqlDatabase::removeDatabase(q(conn_));
}

void PatientLibrary::exec(const std::string& sql, const char* what) const {
  QSqlQuery query(QSqlDatabase::database(q(conn_), false));
  if (!query.exec(q(sql))) throw LibraryError(where_ + ": " + what + ": " + reason(query.lastError()));
}

bool PatientLibrary::connection_alive() const {
  const QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  if (!db.isOpen()) return false;  // the driver closed it when it saw the connection gone
  QSqlQuery t(db);
  if (t.exec("SELECT 1")) return true;
  // A failed statement inside a transaction is no lost connection.
  return t.lastError().text().contains("transaction is aborted");
}

void PatientLibrary::reconnect() const {
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  db.close();
  if (!db.open()) {
    lost_ = true;
    throw ServerUnavailable(where_ + ": cannot reach the PostgreSQL server: " + reason(db.lastError()));
  }
  lost_ = false;
}

template <class F>
auto PatientLibrary::with_server(F&& op) const -> decltype(op()) {
  // Only the outermost operation runs again: an inner one (a lookup inside a change) on a
  // new connection would be outside the change's transaction.
  if (!pg_ || depth_ > 0) {
    Nested n(depth_);
    return op();
  }
  if (lost_ || !QSqlDatabase::database(q(conn_), false).isOpen()) reconnect();
  try {
    Nested n(depth_);
    return op();
  } catch (const ServerUnavailable&) {
    throw;
  } catch (const LibraryError&) {
    if (connection_alive()) throw;  // an ordinary failure: a taken name, a bad value
    // The server restarted or the network dropped: once more on a new connection. A change
    // cut off before its commit was rolled back by the server, so running it again is safe.
    lost_ = true;
    reconnect();
    Nested n(depth_);
    return op();
  }
}

int PatientLibrary::schema_version() const {
  return with_server([&] {
    QSqlQuery query(QSqlDatabase::database(q(conn_), false));
    if (!query.exec("SELECT value FROM meta WHERE key = 'schema_version'") || !query.next())
      throw LibraryError(where_ + ": reading the schema version: " + reason(query.lastError()));
    bool ok = false;
    const int v = query.value(0).toString().toInt(&ok);
    if (!ok || v < 1) throw LibraryError(where_ + ": schema version \"" + query.value(0).toString().toStdString() + "\" is not a number");
    return v;
  });
}

void PatientLibrary::migrate(bool seed) {
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  // Each step in one transaction that holds the library's write lock (SQLite: BEGIN
  // IMMEDIATE, waiting as long as the busy timeout; PostgreSQL: the migration lock) and
  // reads the version again: stations opening a new or older library at once migrate it
  // once, a failed step leaves the previous version intact.
  auto begin = [&](Transaction& tx, const std::string& doing) {
    if (!tx.begin(pg_ ? "BEGIN" : "BEGIN IMMEDIATE")) throw LibraryError(where_ + ": " + doing + ": " + reason(tx.error()));
    if (pg_) {
      QSqlQuery l(db);
      if (!l.exec(kPgMigrationLock)) {
        const std::string why = reason(l.lastError());
        tx.rollback();
        throw LibraryError(where_ + ": " + doing + ": " + why);
      }
    }
  };
  auto commit = [&](Transaction& tx, const std::string& doing) {
    if (!tx.commit()) throw LibraryError(where_ + ": " + doing + ": " + reason(tx.error()));
  };
  auto current_version = [&]() {
    QSqlQuery query(db);
    const QString probe = pg_ ? "SELECT count(*) FROM information_schema.tables WHERE table_name = 'meta' AND table_schema = current_schema()"
                              : "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'meta'";
    if (!query.exec(probe) || !query.next()) throw LibraryError(where_ + ": " + reason(query.lastError()));
    if (query.value(0).toInt() > 0) {
      QSqlQuery v(db);
      if (!v.exec("SELECT value FROM meta WHERE key = 'schema_version'") || !v.next())
        throw LibraryError(where_ + ": reading the schema version: " + reason(v.lastError()));
      bool ok = false;
      const int n = v.value(0).toString().toInt(&ok);
      if (!ok || n < 1) throw LibraryError(where_ + ": schema version \"" + v.value(0).toString().toStdString() + "\" is not a number");
      return n;
    }
    QSqlQuery other(db);
    const QString any = pg_ ? "SELECT count(*) FROM information_schema.tables WHERE table_schema = current_schema()"
                            : "SELECT count(*) FROM sqlite_master WHERE type = 'table'";
    if (other.exec(any) && other.next() && other.value(0).toInt() > 0)
      throw LibraryError(where_ + ": not a patient library (it holds other tables and no schema version); the file was left as it is");
    return 0;
  };
  const auto steps = schema_steps(pg_);
  int first = -1;
  for (;;) {
    Transaction tx(db);  // a throw below rolls the step back
    const auto rollback = [&tx] { tx.rollback(); };
    begin(tx, "opening");
    const int version = current_version();
    if (first < 0) first = version;
    if (version > kSchemaVersion) {
      throw LibraryError(where_ + ": the patient library has schema version " + std::to_string(version) +
                         ", newer than this program's (" + std::to_string(kSchemaVersion) +
                         "): use a newer palpation, or another library (--db / PALPATION_DB); nothing was changed");
    }
    if (version == kSchemaVersion) {
      // A new or migrated library gets the built-in patients it lacks, in the same locked
      // transaction (another station seeding at once waits, then finds them).
      // A built-in patient stored as an older program defined it (a corrected case: the
      // paper case's tumour moved to the paper sweep's depth) takes this program's
      // definition; one the user removed stays removed.
      if (seed) {
        for (const auto& p : builtin_patients()) {
          const auto have = find(p.name);
          if (!have) {
            if (first != kSchemaVersion) insert_patient(p, rollback);
          } else if (have->builtin && (have->body != p.body || have->description != p.description)) {
            QSqlQuery up(QSqlDatabase::database(q(conn_), false));
            up.prepare("UPDATE patients SET scenario = ?, description = ? WHERE name = ? AND builtin = 1");
            up.addBindValue(q(p.body.dump()));
            up.addBindValue(q(p.description));
            up.addBindValue(q(p.name));
            if (!up.exec()) {
              const std::string why = reason(up.lastError());
              tx.rollback();  // before `up` is freed: PostgreSQL frees no statement in an aborted transaction
              throw LibraryError(where_ + ": updating the built-in patient \"" + p.name + "\": " + why);
            }
          }
        }
      }
      commit(tx, "adding the built-in patients");
      break;
    }
    const std::string doing = "migrating to schema " + std::to_string(version + 1);
    for (const auto& sql : steps[std::size_t(version)]) exec(sql, doing.c_str());
    // The built-ins come with the last step: a station that sees the current version sees them.
    if (seed && version + 1 == kSchemaVersion)
      for (const auto& p : builtin_patients())
        if (!find(p.name)) insert_patient(p, rollback);
    commit(tx, doing);
  }
  opened_as_ = first == 0 ? "created" : first == kSchemaVersion ? "opened" : "migrated from " + std::to_string(first);
}

std::vector<PatientRecord> PatientLibrary::list() const {
  return with_server([&] {
  QSqlQuery query(QSqlDatabase::database(q(conn_), false));
  if (!query.exec("SELECT name, category, description, scenario, builtin, source, created FROM patients ORDER BY category, name"))
    throw LibraryError(where_ + ": listing patients: " + reason(query.lastError()));
  std::vector<PatientRecord> v;
  while (query.next()) {
    PatientRecord p;
    p.name = query.value(0).toString().toStdString();
    p.category = query.value(1).toString().toStdString();
    p.description = query.value(2).toString().toStdString();
    p.body = json::parse(query.value(3).toString().toStdString(), nullptr, false);
    p.builtin = query.value(4).toInt() != 0;
    p.source = query.value(5).toString().toStdString();
    p.created = query.value(6).toString().toStdString();
    v.push_back(std::move(p));
  }
  return v;
  });
}

std::optional<PatientRecord> PatientLibrary::find(const std::string& name) const {
  return with_server([&]() -> std::optional<PatientRecord> {
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  QSqlQuery query(db);
  query.prepare("SELECT id, name, category, description, scenario, builtin, source, created FROM patients WHERE name = ?");
  query.addBindValue(q(name));
  if (!query.exec()) throw LibraryError(where_ + ": reading patient \"" + name + "\": " + reason(query.lastError()));
  if (!query.next()) return std::nullopt;
  PatientRecord p;
  const int id = query.value(0).toInt();
  p.name = query.value(1).toString().toStdString();
  p.category = query.value(2).toString().toStdString();
  p.description = query.value(3).toString().toStdString();
  p.body = json::parse(query.value(4).toString().toStdString(), nullptr, false);
  if (p.body.is_discarded()) throw LibraryError(where_ + ": patient \"" + name + "\": scenario: not valid JSON");
  p.builtin = query.value(5).toInt() != 0;
  p.source = query.value(6).toString().toStdString();
  p.created = query.value(7).toString().toStdString();
  QSqlQuery m(db);
  m.prepare("SELECT data FROM meshes WHERE patient_id = ?");
  m.addBindValue(id);
  if (!m.exec()) throw LibraryError(where_ + ": reading the mesh of \"" + name + "\": " + reason(m.lastError()));
  if (m.next()) {
    const QByteArray b = m.value(0).toByteArray();
    p.mesh.assign(b.constData(), std::size_t(b.size()));
  }
  return p;
  });
}

void PatientLibrary::insert_patient(const PatientRecord& p, const std::function<void()>& abort) {
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  auto fail = [&](const QSqlError& e) {
    abort();
    if (is_duplicate(e))  // another station added the name at the same moment
      throw LibraryError(where_ + ": patient \"" + p.name + "\" already exists (choose another --name)");
    throw LibraryError(where_ + ": adding \"" + p.name + "\": " + reason(e) + " (nothing was added)");
  };
  QSqlQuery ins(db);
  ins.prepare("INSERT INTO patients (name, scenario, created, category, description, builtin, source) VALUES (?, ?, ?, ?, ?, ?, ?)");
  ins.addBindValue(q(p.name));
  ins.addBindValue(q(p.body.dump()));
  ins.addBindValue(q(utc_now()));
  ins.addBindValue(q(p.category.empty() ? "custom" : p.category));
  ins.addBindValue(q(p.description));
  ins.addBindValue(p.builtin ? 1 : 0);
  ins.addBindValue(q(p.source));
  if (!ins.exec()) fail(ins.lastError());
  if (!p.mesh.empty()) {
    QSqlQuery id(db);
    id.prepare("SELECT id FROM patients WHERE name = ?");
    id.addBindValue(q(p.name));
    if (!id.exec() || !id.next()) fail(id.lastError());
    QSqlQuery mesh(db);
    mesh.prepare("INSERT INTO meshes (patient_id, format, data) VALUES (?, ?, ?)");
    mesh.addBindValue(id.value(0).toInt());
    mesh.addBindValue(QString("pmesh"));
    mesh.addBindValue(QByteArray(p.mesh.data(), qsizetype(p.mesh.size())));
    if (!mesh.exec()) fail(mesh.lastError());
  }
}

void PatientLibrary::add(const PatientRecord& p) {
  if (p.name.empty() || p.name.size() > 200) throw LibraryError(where_ + ": patient name: must be 1 to 200 characters");
  if (!p.body.is_object() || !p.body.contains("patient"))
    throw LibraryError(where_ + ": patient \"" + p.name + "\": scenario: needs a \"patient\" object");
  with_server([&] {
    QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
    if (find(p.name)) throw LibraryError(where_ + ": patient \"" + p.name + "\" already exists (choose another --name)");
    Transaction tx(db);
    if (!tx.begin()) throw LibraryError(where_ + ": adding \"" + p.name + "\": " + reason(tx.error()));
    insert_patient(p, [&tx] { tx.rollback(); });
    if (!tx.commit()) {
      const QSqlError e = tx.error();
      if (is_duplicate(e)) throw LibraryError(where_ + ": patient \"" + p.name + "\" already exists (choose another --name)");
      throw LibraryError(where_ + ": adding \"" + p.name + "\": " + reason(e) + " (nothing was added)");
    }
  });
}

bool PatientLibrary::remove(const std::string& name) {
  return with_server([&] {
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  Transaction tx(db);
  if (!tx.begin()) throw LibraryError(where_ + ": removing \"" + name + "\": " + reason(tx.error()));
  QSqlQuery a(db), b(db);
  a.prepare("DELETE FROM meshes WHERE patient_id IN (SELECT id FROM patients WHERE name = ?)");
  a.addBindValue(q(name));
  b.prepare("DELETE FROM patients WHERE name = ?");
  b.addBindValue(q(name));
  if (!a.exec() || !b.exec()) {
    const std::string why = reason(a.lastError().isValid() ? a.lastError() : b.lastError());
    tx.rollback();
    throw LibraryError(where_ + ": removing \"" + name + "\": " + why);
  }
  const bool any = b.numRowsAffected() > 0;
  if (!tx.commit()) throw LibraryError(where_ + ": removing \"" + name + "\": " + reason(tx.error()));
  return any;
  });
}

// ---------------------------------------------------------------- trainees and results

namespace {

// A trainee's name: shown in tables and typed on command lines.
std::string trainee_name_problem(const std::string& n) {
  if (n.empty() || n.size() > 100) return "must be 1 to 100 characters";
  for (char c : n)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "must not hold control characters";
  if (n.front() == ' ' || n.back() == ' ') return "must not start or end with a space";
  return {};
}

// "YYYY-MM-DDTHH:MM:SSZ": fixed width, so that text order is time order.
bool is_utc_timestamp(const std::string& t) {
  static const char* const pattern = "dddd-dd-ddTdd:dd:ddZ";
  if (t.size() != std::strlen(pattern)) return false;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (pattern[i] == 'd' ? !(t[i] >= '0' && t[i] <= '9') : t[i] != pattern[i]) return false;
  return true;
}

QVariant nullable(const std::optional<double>& v) {
  return v ? QVariant(*v) : QVariant(QMetaType::fromType<double>());
}
std::optional<double> optional_double(const QVariant& v) {
  if (v.isNull()) return std::nullopt;
  return v.toDouble();
}

// The columns every result query reads, in read_result's order.
const char* const kResultColumns =
    "r.id, t.name, r.case_name, r.curriculum, r.started, r.duration, r.sensitivity, r.false_positives, "
    "r.coverage_light, r.coverage_medium, r.coverage_deep, r.deep_reached, r.exam_time, r.passed, r.score, r.recording";

ExamResult read_result(const QSqlQuery& q) {
  ExamResult r;
  r.id = q.value(0).toLongLong();
  r.trainee = q.value(1).toString().toStdString();
  r.case_name = q.value(2).toString().toStdString();
  r.curriculum = q.value(3).toString().toStdString();
  r.started = q.value(4).toString().toStdString();
  r.duration = q.value(5).toDouble();
  r.sensitivity = optional_double(q.value(6));
  r.false_positives = q.value(7).toInt();
  r.coverage_light = q.value(8).toDouble();
  r.coverage_medium = q.value(9).toDouble();
  r.coverage_deep = q.value(10).toDouble();
  r.deep_reached = optional_double(q.value(11));
  r.exam_time = q.value(12).toDouble();
  r.passed = q.value(13).toInt() != 0;
  // A damaged score text leaves the figures readable (they are columns of their own).
  r.score = json::parse(q.value(14).toString().toStdString(), nullptr, false);
  if (r.score.is_discarded()) r.score = nullptr;
  r.recording = q.value(15).toString().toStdString();
  return r;
}

}  // namespace

std::int64_t PatientLibrary::trainee_id(const std::string& name, const char* doing) const {
  QSqlQuery query(QSqlDatabase::database(q(conn_), false));
  query.prepare("SELECT id FROM trainees WHERE name = ?");
  query.addBindValue(q(name));
  if (!query.exec()) throw LibraryError(where_ + ": " + doing + " \"" + name + "\": " + reason(query.lastError()));
  if (!query.next())
    throw LibraryError(where_ + ": no trainee named \"" + name + "\" (see `palpation trainee list`; add one with `palpation trainee add`)");
  return query.value(0).toLongLong();
}

void PatientLibrary::add_trainee(const std::string& name) {
  if (const std::string why = trainee_name_problem(name); !why.empty())
    throw LibraryError(where_ + ": trainee name \"" + name + "\": " + why);
  return with_server([&] {
    if (find_trainee(name)) throw LibraryError(where_ + ": trainee \"" + name + "\" already exists");
    QSqlQuery ins(QSqlDatabase::database(q(conn_), false));
    ins.prepare("INSERT INTO trainees (name, created) VALUES (?, ?)");
    ins.addBindValue(q(name));
    ins.addBindValue(q(utc_now()));
    if (!ins.exec()) {
      if (is_duplicate(ins.lastError()))  // another station added them at the same moment
        throw LibraryError(where_ + ": trainee \"" + name + "\" already exists");
      throw LibraryError(where_ + ": adding trainee \"" + name + "\": " + reason(ins.lastError()) + " (nothing was added)");
    }
  });
}

std::vector<TraineeRecord> PatientLibrary::trainees() const {
  return with_server([&] {
    QSqlQuery query(QSqlDatabase::database(q(conn_), false));
    if (!query.exec("SELECT name, created FROM trainees ORDER BY name"))
      throw LibraryError(where_ + ": listing trainees: " + reason(query.lastError()));
    std::vector<TraineeRecord> v;
    while (query.next()) v.push_back({query.value(0).toString().toStdString(), query.value(1).toString().toStdString()});
    return v;
  });
}

std::optional<TraineeRecord> PatientLibrary::find_trainee(const std::string& name) const {
  return with_server([&]() -> std::optional<TraineeRecord> {
    QSqlQuery query(QSqlDatabase::database(q(conn_), false));
    query.prepare("SELECT name, created FROM trainees WHERE name = ?");
    query.addBindValue(q(name));
    if (!query.exec()) throw LibraryError(where_ + ": reading trainee \"" + name + "\": " + reason(query.lastError()));
    if (!query.next()) return std::nullopt;
    return TraineeRecord{query.value(0).toString().toStdString(), query.value(1).toString().toStdString()};
  });
}

bool PatientLibrary::remove_trainee(const std::string& name) {
  return with_server([&] {
    if (!find_trainee(name)) return false;
    QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
    Transaction tx(db);
    if (!tx.begin()) throw LibraryError(where_ + ": removing trainee \"" + name + "\": " + reason(tx.error()));
    QSqlQuery a(db), b(db);
    a.prepare("DELETE FROM exam_results WHERE trainee_id IN (SELECT id FROM trainees WHERE name = ?)");
    a.addBindValue(q(name));
    b.prepare("DELETE FROM trainees WHERE name = ?");
    b.addBindValue(q(name));
    if (!a.exec() || !b.exec() || !tx.commit()) {
      const QSqlError e = a.lastError().isValid() ? a.lastError() : b.lastError().isValid() ? b.lastError() : tx.error();
      tx.rollback();
      throw LibraryError(where_ + ": removing trainee \"" + name + "\": " + reason(e) + " (nothing was removed)");
    }
    return true;
  });
}

void PatientLibrary::check_result(const ExamResult& r) const {
  const std::string what = where_ + ": exam result of \"" + r.trainee + "\"";
  auto bad = [&](const std::string& field, const std::string& why) { throw LibraryError(what + ": " + field + ": " + why); };
  auto number = [&](const char* field, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream o;
      o << "must be within " << lo << ".." << hi << ", got " << v;
      bad(field, o.str());
    }
  };
  if (r.case_name.empty() || r.case_name.size() > 200) bad("case_name", "must be 1 to 200 characters");
  if (r.curriculum.size() > 200) bad("curriculum", "must be at most 200 characters");
  if (!r.started.empty() && !is_utc_timestamp(r.started)) bad("started", "must be UTC \"YYYY-MM-DDTHH:MM:SSZ\", got \"" + r.started + "\"");
  number("duration", r.duration, 0, 1e6);
  if (r.sensitivity) number("sensitivity", *r.sensitivity, 0, 1);
  if (r.false_positives < 0) bad("false_positives", "must be >= 0, got " + std::to_string(r.false_positives));
  number("coverage_light", r.coverage_light, 0, 1);
  number("coverage_medium", r.coverage_medium, 0, 1);
  number("coverage_deep", r.coverage_deep, 0, 1);
  if (r.deep_reached) number("deep_reached", *r.deep_reached, 0, 1);
  number("exam_time", r.exam_time, 0, 1e6);
  if (!r.score.is_object()) bad("score", "must be a JSON object (the exam's score)");
}

std::int64_t PatientLibrary::record_result(const ExamResult& r) {
  check_result(r);
  return with_server([&] { return insert_result(r, false); });
}

std::int64_t PatientLibrary::insert_result(const ExamResult& r, bool once) {
  const std::string what = where_ + ": exam result of \"" + r.trainee + "\"";
  const std::int64_t trainee = trainee_id(r.trainee, "recording a result of");
  const QString started = q(r.started.empty() ? utc_now() : r.started);
  QSqlDatabase db = QSqlDatabase::database(q(conn_), false);
  Transaction tx(db);
  if (!tx.begin()) throw LibraryError(what + ": " + reason(tx.error()));
  auto fail = [&](const QSqlError& e) {
    const std::string why = reason(e);
    tx.rollback();
    throw LibraryError(what + ": " + why + " (nothing was recorded)");
  };
  if (once) {
    // A kept result sent again (by a program that stopped before it deleted its file, or
    // by two at once): the same row is there already.
    QSqlQuery same(db);
    same.prepare("SELECT MIN(id) FROM exam_results WHERE trainee_id = ? AND started = ? AND case_name = ? AND curriculum = ? "
                 "AND recording = ? AND score = ?");
    same.addBindValue(QVariant::fromValue<qlonglong>(trainee));
    same.addBindValue(started);
    same.addBindValue(q(r.case_name));
    same.addBindValue(q(r.curriculum));
    same.addBindValue(q(r.recording));
    same.addBindValue(q(r.score.dump()));
    if (!same.exec() || !same.next()) fail(same.lastError());
    if (!same.value(0).isNull()) {
      const std::int64_t id = same.value(0).toLongLong();
      if (!tx.commit()) fail(tx.error());
      return id;
    }
  }
  QSqlQuery ins(db);
  ins.prepare("INSERT INTO exam_results (trainee_id, case_name, curriculum, started, duration, sensitivity, false_positives, "
              "coverage_light, coverage_medium, coverage_deep, deep_reached, exam_time, passed, score, recording) "
              "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  ins.addBindValue(QVariant::fromValue<qlonglong>(trainee));
  ins.addBindValue(q(r.case_name));
  ins.addBindValue(q(r.curriculum));
  ins.addBindValue(started);
  ins.addBindValue(r.duration);
  ins.addBindValue(nullable(r.sensitivity));
  ins.addBindValue(r.false_positives);
  ins.addBindValue(r.coverage_light);
  ins.addBindValue(r.coverage_medium);
  ins.addBindValue(r.coverage_deep);
  ins.addBindValue(nullable(r.deep_reached));
  ins.addBindValue(r.exam_time);
  ins.addBindValue(r.passed ? 1 : 0);
  ins.addBindValue(q(r.score.dump()));
  ins.addBindValue(q(r.recording));
  if (!ins.exec()) fail(ins.lastError());
  // The new row's id, portably: the largest id of this trainee inside the transaction.
  QSqlQuery id(db);
  id.prepare("SELECT MAX(id) FROM exam_results WHERE trainee_id = ?");
  id.addBindValue(QVariant::fromValue<qlonglong>(trainee));
  if (!id.exec() || !id.next()) fail(id.lastError());
  const std::int64_t rid = id.value(0).toLongLong();
  if (!tx.commit()) fail(tx.error());
  return rid;
}

// ---------------------------------------------------------------- results kept on this station

namespace {

json result_to_json(const ExamResult& r) {
  json j = {{"trainee", r.trainee}, {"case_name", r.case_name}, {"curriculum", r.curriculum}, {"started", r.started},
            {"duration", r.duration}, {"false_positives", r.false_positives}, {"coverage_light", r.coverage_light},
            {"coverage_medium", r.coverage_medium}, {"coverage_deep", r.coverage_deep}, {"exam_time", r.exam_time},
            {"passed", r.passed}, {"score", r.score}, {"recording", r.recording}};
  j["sensitivity"] = r.sensitivity ? json(*r.sensitivity) : json(nullptr);
  j["deep_reached"] = r.deep_reached ? json(*r.deep_reached) : json(nullptr);
  return j;
}

ExamResult result_from_json(const json& j) {
  ExamResult r;
  r.trainee = j.at("trainee").get<std::string>();
  r.case_name = j.at("case_name").get<std::string>();
  r.curriculum = j.at("curriculum").get<std::string>();
  r.started = j.at("started").get<std::string>();
  r.duration = j.at("duration").get<double>();
  if (!j.at("sensitivity").is_null()) r.sensitivity = j.at("sensitivity").get<double>();
  r.false_positives = j.at("false_positives").get<int>();
  r.coverage_light = j.at("coverage_light").get<double>();
  r.coverage_medium = j.at("coverage_medium").get<double>();
  r.coverage_deep = j.at("coverage_deep").get<double>();
  if (!j.at("deep_reached").is_null()) r.deep_reached = j.at("deep_reached").get<double>();
  r.exam_time = j.at("exam_time").get<double>();
  r.passed = j.at("passed").get<bool>();
  r.score = j.at("score");
  r.recording = j.at("recording").get<std::string>();
  return r;
}

constexpr const char* kPendingFormat = "palpation-pending-result";

}  // namespace

std::string PatientLibrary::keep(const ExamResult& r, bool add_missing_trainee) const {
  namespace fs = std::filesystem;
  const json doc = {{"format", kPendingFormat}, {"version", 1}, {"server", where_}, {"add_trainee", add_missing_trainee},
                    {"result", result_to_json(r)}};
  std::error_code ec;
  fs::create_directories(pending_dir_, ec);
  // Named by the time kept, so that they are sent in the order they were taken.
  static std::atomic<int> counter{0};
  char name[96];
  std::snprintf(name, sizeof name, "%s-%d-%d.json", utc_now().c_str(), int(::getpid()), ++counter);
  const std::string file = pending_dir_ + "/" + name;
  const std::string tmp = file + ".part";
  const std::string text = doc.dump(1) + "\n";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  bool ok = fd >= 0 && ::write(fd, text.data(), text.size()) == ssize_t(text.size()) && ::fsync(fd) == 0;
  if (fd >= 0) ok = (::close(fd) == 0) && ok;
  ok = ok && ::rename(tmp.c_str(), file.c_str()) == 0;
  if (!ok) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw LibraryError(where_ + ": the server cannot be reached, and the exam result of \"" + r.trainee +
                       "\" could not be kept on this station either (" + pending_dir_ + ": " + why + ")" +
                       (r.recording.empty() ? "" : "; the recording is " + r.recording));
  }
  return file;
}

std::vector<std::string> PatientLibrary::pending() const {
  namespace fs = std::filesystem;
  std::vector<std::string> v;
  if (!pg_) return v;
  std::error_code ec;
  for (fs::directory_iterator it(pending_dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() != ".json") continue;
    std::ifstream in(p);
    const json doc = json::parse(in, nullptr, false);
    if (doc.is_object() && doc.value("format", "") == kPendingFormat && doc.value("server", "") == where_) v.push_back(p.string());
  }
  std::sort(v.begin(), v.end());
  return v;
}

int PatientLibrary::send_pending() {
  int sent = 0;
  for (const std::string& file : pending()) {
    // Locked while it is sent: another program sending at the same time skips it; one that
    // opened it before it was removed finds its result there already (insert_result once).
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;  // sent by another program meanwhile
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd);
      continue;
    }
    struct Close {
      int fd;
      ~Close() { ::close(fd); }
    } closer{fd};
    std::ifstream in(file);
    const json doc = json::parse(in, nullptr, false);
    if (!doc.is_object() || !doc.contains("result")) continue;
    ExamResult r;
    try {
      r = result_from_json(doc["result"]);
    } catch (const json::exception&) {
      continue;  // a damaged file stays where it is, for a person to look at
    }
    try {
      with_server([&] {
        if (doc.value("add_trainee", false) && !find_trainee(r.trainee)) {
          try {
            add_trainee(r.trainee);
          } catch (const ServerUnavailable&) {
            throw;
          } catch (const LibraryError&) {
            if (!find_trainee(r.trainee)) throw;  // not another station adding them at once
          }
        }
        insert_result(r, true);
      });
    } catch (const ServerUnavailable&) {
      throw;
    } catch (const LibraryError& e) {
      // The server refuses it (its trainee removed meanwhile, say): set aside, with the
      // reason, for a person to look at; never sent again, never deleted.
      std::ofstream(file + ".refused.txt") << e.what() << "\n";
      ::rename(file.c_str(), (file + ".refused").c_str());
      continue;
    }
    ::unlink(file.c_str());
    ++sent;
  }
  return sent;
}

StoreOutcome PatientLibrary::store_result(const ExamResult& r, bool add_missing_trainee) {
  check_result(r);
  ExamResult x = r;
  if (x.started.empty()) x.started = utc_now();  // the exam's time, also when it is sent later
  StoreOutcome out;
  try {
    if (pg_ && !pending().empty()) send_pending();  // the older results first
    with_server([&] {
      if (add_missing_trainee && !find_trainee(x.trainee)) {
        try {
          add_trainee(x.trainee);
        } catch (const ServerUnavailable&) {
          throw;
        } catch (const LibraryError&) {
          if (!find_trainee(x.trainee)) throw;  // not another station adding them at once
        }
      }
      out.id = insert_result(x, false);
    });
  } catch (const ServerUnavailable& e) {
    out.id = 0;
    out.kept = keep(x, add_missing_trainee);
    out.message = std::string(e.what()) + "; the exam result of \"" + x.trainee + "\" is kept on this station (" + out.kept +
                  ") and sent when the server is back" + (x.recording.empty() ? "" : "; the recording is " + x.recording);
  }
  return out;
}

std::vector<ExamResult> PatientLibrary::results(const std::string& trainee) const {
  return with_server([&] {
    const std::int64_t tid = trainee_id(trainee, "reading the results of");
    QSqlQuery query(QSqlDatabase::database(q(conn_), false));
    query.prepare(QString("SELECT ") + kResultColumns +
                  " FROM exam_results r JOIN trainees t ON t.id = r.trainee_id WHERE r.trainee_id = ? ORDER BY r.started, r.id");
    query.addBindValue(QVariant::fromValue<qlonglong>(tid));
    if (!query.exec()) throw LibraryError(where_ + ": reading the results of \"" + trainee + "\": " + reason(query.lastError()));
    std::vector<ExamResult> v;
    while (query.next()) v.push_back(read_result(query));
    return v;
  });
}

bool PatientLibrary::better_result(const ExamResult& a, const ExamResult& b) {
  if (a.passed != b.passed) return a.passed;
  const double sa = a.sensitivity.value_or(1.0), sb = b.sensitivity.value_or(1.0);
  if (sa != sb) return sa > sb;
  if (a.false_positives != b.false_positives) return a.false_positives < b.false_positives;
  if (a.coverage_deep != b.coverage_deep) return a.coverage_deep > b.coverage_deep;
  if (a.started != b.started) return a.started > b.started;
  return a.id > b.id;
}

std::vector<TraineeSummary> PatientLibrary::class_summary() const {
  return with_server([&] {
    std::vector<TraineeSummary> v;
    for (auto& t : trainees()) v.push_back({std::move(t), 0, 0, std::nullopt, std::nullopt});
    QSqlQuery query(QSqlDatabase::database(q(conn_), false));
    if (!query.exec(QString("SELECT ") + kResultColumns +
                    " FROM exam_results r JOIN trainees t ON t.id = r.trainee_id ORDER BY t.name, r.started, r.id"))
      throw LibraryError(where_ + ": reading the class's results: " + reason(query.lastError()));
    std::map<std::string, std::size_t> index;
    for (std::size_t k = 0; k < v.size(); ++k) index[v[k].trainee.name] = k;
    while (query.next()) {
      ExamResult r = read_result(query);
      const auto it = index.find(r.trainee);
      if (it == index.end()) continue;  // a trainee added since the list was read
      TraineeSummary& s = v[it->second];
      ++s.exams;
      if (r.passed) ++s.passed;
      if (!s.best || better_result(r, *s.best)) s.best = r;
      s.latest = std::move(r);
    }
    return v;
  });
}

void PatientLibrary::create_old_schema_for_test(const std::string& location, int version) {
  const QString conn = q("palpation-old-schema-" + std::to_string(++g_connections));
  const bool pg = is_postgres_url(location);
  {
    QSqlDatabase db = QSqlDatabase::addDatabase(pg ? "QPSQL" : "QSQLITE", conn);
    const std::string path = configure(db, location, pg, 3000, 10);
    if (!db.open()) throw LibraryError(path + ": " + reason(db.lastError()));
    const auto steps = schema_steps(pg);
    for (int v = 0; v < version; ++v)
      for (const auto& sql : steps[std::size_t(v)]) {
        QSqlQuery query(db);
        if (!query.exec(q(sql))) throw LibraryError(path + ": " + reason(query.lastError()));
      }
    QSqlQuery ins(db);
    const std::string body = fragment({{"phantom", "box"}, {"size", {0.1, 0.1, 0.05}}}).dump();
    if (version == 1)
      ins.prepare("INSERT INTO patients (name, scenario, created) VALUES ('old-patient', ?, '2026-01-01T00:00:00Z')");
    else
      ins.prepare("INSERT INTO patients (name, scenario, created, category, description) VALUES ('old-patient', ?, "
                  "'2026-01-01T00:00:00Z', 'box', 'made by schema version " + QString::number(version) + "')");
    ins.addBindValue(q(body));
    if (!ins.exec()) throw LibraryError(path + ": " + reason(ins.lastError()));
    if (version >= 4) {
      QSqlQuery t(db), r(db);
      if (!t.exec("INSERT INTO trainees (name, created) VALUES ('old-trainee', '2026-01-01T00:00:00Z')"))
        throw LibraryError(path + ": " + reason(t.lastError()));
      if (!r.exec("INSERT INTO exam_results (trainee_id, case_name, curriculum, started, duration, sensitivity, "
                  "false_positives, coverage_light, coverage_medium, coverage_deep, deep_reached, exam_time, passed, score) "
                  "SELECT id, 'paper-case', '', '2026-01-01T00:10:00Z', 200, 1, 0, 0.9, 0.8, 0.5, 1, 180, 1, '{}' "
                  "FROM trainees WHERE name = 'old-trainee'"))
        throw LibraryError(path + ": " + reason(r.lastError()));
    }
  }
  QSqlDatabase::removeDatabase(conn);  // closes it, after its queries are gone
}

}  // namespace palpation::app::store
