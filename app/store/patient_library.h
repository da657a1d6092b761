// The patient library (docs/patient-library.md): virtual patients in a database through
// QtSql. SQLite by default (a file in the user's data folder, created on first run with
// the built-in patients); the same code against a PostgreSQL server (QPSQL) for a
// classroom of stations sharing one library. The schema is versioned; older databases
// are migrated step by step, a newer one is refused.
#pragma once

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

class PatientLibrary {
 public:
  static constexpr int kSchemaVersion = 3;

  struct Options {
    /// SQLite file path, or "postgresql://user:password@host:port/dbname" (QPSQL).
    /// Empty: default_location().
    std::string db;
    int busy_timeout_ms = 3000;  // SQLite: how long to wait for another writer's lock
    bool seed = true;            // add the built-in patients to a new library
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

  /// The built-in patients (several breast sizes and shapes; graded tumour cases; the
  /// paper's case).
  static std::vector<PatientRecord> builtin_patients();

  /// Tests: creates the tables of an earlier schema version (1 .. kSchemaVersion) in an
  /// empty SQLite file, as that version of the program did, with one patient in it.
  static void create_old_schema_for_test(const std::string& sqlite_path, int version);

 private:
  void exec(const std::string& sql, const char* what) const;
  void migrate();
  std::string conn_, where_, opened_as_;
  bool pg_ = false;
};

/// A full scenario (the patient's body + a default finger path over its centre, or over
/// its first inclusion) that `palpation run` accepts; `mesh_file` replaces the imported
/// patient's mesh path.
nlohmann::json patient_scenario(const PatientRecord& p, const std::string& mesh_file = {});

}  // namespace palpation::app::store
