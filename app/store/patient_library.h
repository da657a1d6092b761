// The patient library (docs/patient-library.md): virtual patients in a database through
// QtSql. SQLite by default (a file in the user's data folder, created on first run with
// the built-in patients); the same code against a PostgreSQL server (QPSQL) for a
// classroom of stations sharing one library. The schema is versioned; older databases
// are migrated step by step, a newer one is refused.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace palpation::app::store {

/// A library failure: what() is one line naming the database and the reason.
class LibraryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The PostgreSQL server cannot be reached (stopped, restarting, the network gone): what()
/// names the server and says why. The library reconnects at its next use.
class ServerUnavailable : public LibraryError {
 public:
  using LibraryError::LibraryError;
};

struct PatientRecord {
  std::string name;          // unique
  std::string category;      // "breast" (built-in shapes), "tumour" (graded cases), "imported", ...
  std::string description;
  nlohmann::json body;       // scenario fragment: {"patient", "tissue", "inclusions"}
  bool builtin = false;
  std::string source;        // imported: the scan file it came from
  std::string mesh;          // imported: the tetrahedral mesh (.pmesh bytes), else empty
  std::string created;       // UTC, set by the library
};

/// What a built-in patient is, as data: its English description is composed from this
/// (english_description) and the GUI composes the description in the user's language from
/// the same (ui/event_text.h). Keyed by the built-in patient's name (builtin_description).
struct BuiltinDescription {
  enum class Kind { Healthy, PaperCase, Tumour };
  enum class Size { Small, Medium, Large, WideFlat, NarrowProjecting };
  enum class Hardness { Soft, Firm, Hard };
  Kind kind = Kind::Healthy;
  Size size = Size::Medium;          // Healthy
  int volume_ml = 0;                 // Healthy
  bool paper_size = false;           // Healthy: the paper's breast size
  Hardness hardness = Hardness::Firm;  // Tumour
  double diameter_cm = 0;            // Tumour
  double young_kpa = 0;              // Tumour
  double depth_cm = 0;               // Tumour: centre below the skin
};
/// The English description (PatientRecord::description of a built-in patient).
std::string english_description(const BuiltinDescription& d);
/// A built-in patient's description as data, by its name; nothing for other names.
std::optional<BuiltinDescription> builtin_description(const std::string& name);

/// A trainee (docs/training.md, "Trainees and progress").
struct TraineeRecord {
  std::string name;          // unique, 1 to 100 characters, no control characters
  std::string created;       // UTC, set by the library
};

/// One exam a trainee took: the figures an instructor compares, and the whole score.
struct ExamResult {
  std::int64_t id = 0;       // set by the library
  std::string trainee;
  std::string case_name;     // a library patient's name or "Generated case SEED"
  std::string curriculum;    // the curriculum's name, or empty for a free exam
  std::string started;       // UTC "YYYY-MM-DDTHH:MM:SSZ"; empty: now
  double duration = 0;       // s, the whole session
  std::optional<double> sensitivity;   // hits / tumours; none for a case without tumours
  int false_positives = 0;
  double coverage_light = 0, coverage_medium = 0, coverage_deep = 0;  // skin fractions 0..1
  std::optional<double> deep_reached;  // fraction of tumours pressed deep over; none without tumours
  double exam_time = 0;      // s, first contact to the end
  bool passed = false;       // against the curriculum's criteria (false for a free exam)
  nlohmann::json score;      // the full score (train::to_json(ExamScore)), an object
  std::string recording;     // the session recording's path, or empty
};

/// What PatientLibrary::store_result did with a result.
struct StoreOutcome {
  std::int64_t id = 0;       // the stored result's id; 0 when it was kept on this station
  std::string kept;          // the file on this station holding it while the server is away
  std::string message;       // when kept: one line naming the server, the reason and the file
};

/// The instructor's view of one trainee.
struct TraineeSummary {
  TraineeRecord trainee;
  int exams = 0, passed = 0;
  std::optional<ExamResult> latest;  // by start time
  /// The best: passed before failed, then the higher sensitivity (a case without tumours
  /// counts as 1), fewer false positives, more deep coverage, the later.
  std::optional<ExamResult> best;
};

class PatientLibrary {
 public:
  static constexpr int kSchemaVersion = 4;

  struct Options {
    /// SQLite file path, or "postgresql://user:password@host:port/dbname" (QPSQL).
    /// Empty: default_location().
    std::string db;
    int busy_timeout_ms = 3000;  // SQLite: how long to wait for another writer's lock
    bool seed = true;            // add the built-in patients to a new library
    /// PostgreSQL: where results are kept while the server cannot be reached (one file
    /// each). Empty: QStandardPaths::AppDataLocation/pending-results.
    std::string pending_dir = {};
    int connect_timeout_s = 10;  // PostgreSQL: how long to wait for the server to answer a connection
  };

  /// $PALPATION_DB, else QStandardPaths::AppDataLocation/patients.sqlite.
  static std::string default_location();

  /// Opens (creating a new SQLite file and its folder), migrates an older schema, adds
  /// the built-in patients to a new library. Throws LibraryError: locked, not a database,
  /// newer schema, no driver.
  explicit PatientLibrary(const Options& opt);
  ~PatientLibrary();
  PatientLibrary(const PatientLibrary&) = delete;
  PatientLibrary& operator=(const PatientLibrary&) = delete;

  const std::string& location() const { return where_; }
  int schema_version() const;
  bool is_postgres() const { return pg_; }
  /// What opening did: "created", "migrated from N", "opened".
  const std::string& opened_as() const { return opened_as_; }

  std::vector<PatientRecord> list() const;  // without mesh bytes
  std::optional<PatientRecord> find(const std::string& name) const;
  /// Adds a patient; throws LibraryError for a duplicate name or a failed write (nothing
  /// half written: one transaction).
  void add(const PatientRecord& p);
  bool remove(const std::string& name);

  // Trainees and their exam results.
  /// Adds a trainee; throws LibraryError for a bad or taken name.
  void add_trainee(const std::string& name);
  std::vector<TraineeRecord> trainees() const;  // by name
  std::optional<TraineeRecord> find_trainee(const std::string& name) const;
  /// Removes a trainee and their results (one transaction); false when there was none.
  bool remove_trainee(const std::string& name);
  /// Stores a result and returns its id. Throws LibraryError naming the trainee when there
  /// is no such trainee, naming the field for a bad value; nothing is written then.
  std::int64_t record_result(const ExamResult& r);
  /// A trainee's results, oldest first (by start time, then as recorded). Throws
  /// LibraryError for an unknown trainee.
  std::vector<ExamResult> results(const std::string& trainee) const;
  /// Every trainee's exams, passes, latest and best result, by name.
  std::vector<TraineeSummary> class_summary() const;
  /// A station's exam result at the exam's end: adds the trainee when missing (and
  /// `add_missing_trainee`), stores the result. When a PostgreSQL server cannot be reached
  /// (stopped, restarting, the network gone) the result is kept on this station
  /// (Options::pending_dir) and the outcome says so; results kept earlier are sent first,
  /// here and when the library is opened, once the server is back. Throws LibraryError for
  /// anything else (a bad value, an unknown trainee), nothing written or kept then.
  StoreOutcome store_result(const ExamResult& r, bool add_missing_trainee = true);
  /// Sends the results kept on this station for this server (oldest first; each once, even
  /// when two programs send at the same time); returns how many. Throws ServerUnavailable
  /// when the server cannot be reached (those not sent stay kept). SQLite: 0.
  int send_pending();
  /// The results kept on this station for this server, not yet sent (their files).
  std::vector<std::string> pending() const;
  const std::string& pending_dir() const { return pending_dir_; }

  /// The better of two results by TraineeSummary::best's order.
  static bool better_result(const ExamResult& a, const ExamResult& b);

  /// The built-in patients (several breast sizes and shapes; graded tumour cases; the
  /// paper's case).
  static std::vector<PatientRecord> builtin_patients();

  /// Tests: creates the tables of an earlier schema version (1 .. kSchemaVersion) in an
  /// empty SQLite file, as that version of the program did, with one patient in it (and,
  /// from version 4, one trainee "old-trainee" with one result).
  /// `location` may also be a PostgreSQL URL naming an empty database.
  static void create_old_schema_for_test(const std::string& location, int version);

 private:
  void exec(const std::string& sql, const char* what) const;
  void migrate(bool seed);
  /// Runs one operation; on PostgreSQL, when it failed because the connection was lost (the
  /// server restarted, the network dropped), reconnects and runs it once more. Throws
  /// ServerUnavailable when the server cannot be reached.
  template <class F>
  auto with_server(F&& op) const -> decltype(op());
  void reconnect() const;
  bool connection_alive() const;
  /// One patient's rows, inside the caller's transaction. On failure it calls `abort` (the
  /// caller's rollback) before its statements are freed: PostgreSQL refuses to free a
  /// prepared statement inside an aborted transaction, and Qt warns of it.
  void insert_patient(const PatientRecord& p, const std::function<void()>& abort);
  /// Checks a result's values; LibraryError naming the field.
  void check_result(const ExamResult& r) const;
  /// Inserts a result in one transaction; with `once`, not when the same result (trainee,
  /// start, case, curriculum, recording, score) is there already (returns its id).
  std::int64_t insert_result(const ExamResult& r, bool once);
  /// Writes a result to pending_dir_; returns the file.
  std::string keep(const ExamResult& r, bool add_missing_trainee) const;
  std::string pending_dir_;
  mutable bool lost_ = false;
  mutable int depth_ = 0;  // operations under way (with_server)
  /// The trainee's row id; LibraryError naming the trainee when there is none.
  std::int64_t trainee_id(const std::string& name, const char* doing) const;
  std::string conn_, where_, opened_as_;
  bool pg_ = false;
};

/// A full scenario (the patient's body + a default finger path over its centre, or over
/// its first inclusion) that `palpation run` accepts; `mesh_file` replaces the imported
/// patient's mesh path.
nlohmann::json patient_scenario(const PatientRecord& p, const std::string& mesh_file = {});

}  // namespace palpation::app::store
