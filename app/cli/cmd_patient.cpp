// palpation patient list | show NAME | export NAME FILE | import FILE --name NAME | remove NAME
// The patient library (docs/patient-library.md); --db or $PALPATION_DB choose the database.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <QCoreApplication>

#include "cli/cli.h"
#include "scan/imported_patient.h"
#include "model_cache.h"
#include "store/patient_library.h"
#include "scan/scan_import.h"

namespace palpation::app::cli {

using scan::BasePlane;
using scan::ImportError;
using scan::ImportOptions;
using scan::ImportResult;
using scan::import_scan;
using scan::imported_patient_record;
using store::LibraryError;
using store::PatientLibrary;
using store::PatientRecord;
using store::patient_scenario;

namespace {

// QtSql loads its drivers as plugins: a QCoreApplication must exist.
struct QtCore {
  int argc = 1;
  char name[10] = "palpation";
  char* argv[2] = {name, nullptr};
  std::unique_ptr<QCoreApplication> app;
  QtCore() {
    if (!QCoreApplication::instance()) app = std::make_unique<QCoreApplication>(argc, argv);
  }
};

// Library errors are bad input (a locked, corrupt or newer database, an unknown name).
template <class F>
int guarded(F f) {
  try {
    return f();
  } catch (const LibraryError& e) {
    throw sim::ScenarioError(e.what());
  } catch (const ImportError& e) {
    throw sim::ScenarioError(e.what());
  }
}

}  // namespace

CommandAction add_patient_command(CLI::App& app) {
  auto* sub = app.add_subcommand("patient", "The patient library: list, show, export, import a scan, remove");
  sub->require_subcommand(1);
  struct Opts {
    std::string db, name, file, resolution = "paper", base_plane;
    double scale = 1.0;
    bool quiet = false, json_out = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("--db", o->db, "Database: SQLite file or postgresql://user:pass@host:port/db "
                                 "(default: $PALPATION_DB, else the user's data folder)");
  auto* list = sub->add_subcommand("list", "List the patients");
  list->add_flag("--json", o->json_out, "As JSON");
  auto* show = sub->add_subcommand("show", "Print a patient as a scenario (JSON)");
  show->add_option("name", o->name, "Patient name")->required();
  auto* exp = sub->add_subcommand("export", "Write a patient as a scenario FILE (.json) that `palpation run` accepts "
                                            "(imported scans: the mesh beside it as FILE.pmesh)");
  exp->add_option("name", o->name, "Patient name")->required();
  exp->add_option("file", o->file, "Scenario file to write")->required();
  auto* imp = sub->add_subcommand("import", "Import a scanned breast (STL, OBJ, PLY) as a patient");
  imp->add_option("file", o->file, "Surface mesh")->required();
  imp->add_option("--name", o->name, "Patient name")->required();
  imp->add_option("--resolution", o->resolution, "Tetrahedron edge length in m, or coarse, paper, fine, xfine");
  imp->add_option("--scale", o->scale, "File units to metres (0.001 for millimetres)");
  imp->add_option("--base-plane", o->base_plane, "Chest-wall plane nx,ny,nz,d (n.x = d in metres, n out of the body); "
                                                 "default: found automatically (the largest flat region)");
  imp->add_flag("--quiet", o->quiet, "No progress on stderr");
  auto* rm = sub->add_subcommand("remove", "Remove a patient");
  rm->add_option("name", o->name, "Patient name")->required();
  for (auto* c : {list, show, exp, imp, rm})
    c->add_option("--db", o->db, "Database: SQLite file or postgresql://user:pass@host:port/db");

  return [o, list, show, exp, imp, rm]() -> int {
    QtCore qt;
    return guarded([&]() -> int {
      PatientLibrary::Options lo;
      lo.db = o->db;
      if (imp->parsed()) {
        // Check the scan before touching the library.
        ImportOptions io;
        if (auto e = sim::resolution_edge("breast", o->resolution)) {
          io.edge = *e;
        } else {
          try {
            std::size_t used = 0;
            io.edge = std::stod(o->resolution, &used);
            if (used != o->resolution.size()) throw std::invalid_argument("trailing");
          } catch (const std::exception&) {
            throw sim::ScenarioError("--resolution: \"" + o->resolution + "\" is neither a level (coarse, paper, fine, xfine) nor a length in m");
          }
        }
        io.scale = o->scale;
        if (!o->base_plane.empty()) {
          double v[4];
          if (std::sscanf(o->base_plane.c_str(), "%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3]) != 4 ||
              !(std::hypot(v[0], v[1], v[2]) > 0))
            throw sim::ScenarioError("--base-plane: expected nx,ny,nz,d with a non-zero normal, got \"" + o->base_plane + "\"");
          BasePlane b;
          const double len = std::hypot(v[0], v[1], v[2]);
          b.normal = Eigen::Vector3d(v[0], v[1], v[2]) / len;
          b.offset = v[3] / len;
          b.automatic = false;
          io.base = b;
        }
        if (!o->quiet)
          io.progress = [last = -1](double f, const std::string& stage) mutable {
            const int pct = int(f * 100);
            if (pct / 10 != last / 10) std::fprintf(stderr, "import: %3d%%  %s\n", pct, stage.c_str());
            last = pct;
            return true;
          };
        {
          PatientLibrary lib(lo);  // fails early: locked, corrupt, newer, name taken
          if (lib.find(o->name)) throw LibraryError(lib.location() + ": patient \"" + o->name + "\" already exists (choose another --name)");
        }
        ImportResult r = import_scan(o->file, io);
        const PatientRecord p = imported_patient_record(r, o->name, o->file, io.edge);
        PatientLibrary lib(lo);
        lib.add(p);
        std::printf("imported %s as \"%s\": %s; %s; base plane n = (%.3f, %.3f, %.3f) %s, %.1f cm^2 (%.0f %% of the body's "
                    "outline, tilted %.0f degrees); %d nodes, %d tetrahedra; %.2f s (meshing %.2f s) -> %s\n",
                    o->file.c_str(), o->name.c_str(), r.report.repairs().c_str(), "closed and manifold", r.base.normal.x(),
                    r.base.normal.y(), r.base.normal.z(), r.base.automatic ? "found" : "given", r.base.area * 1e4,
                    100.0 * r.base.footprint_fraction(), r.base.tilt_deg(), r.mesh.num_nodes(), r.mesh.num_tets(), r.seconds,
                    r.mesh_seconds, lib.location().c_str());
        return kExitOk;
      }
      PatientLibrary lib(lo);
      if (list->parsed()) {
        const auto v = lib.list();
        if (o->json_out) {
          nlohmann::json a = nlohmann::json::array();
          for (const auto& p : v)
            a.push_back({{"name", p.name}, {"category", p.category}, {"description", p.description}, {"builtin", p.builtin}, {"created", p.created}});
          std::printf("%s\n", a.dump(2).c_str());
        } else {
          std::printf("# %s (schema %d, %zu patients)\n", lib.location().c_str(), lib.schema_version(), v.size());
          for (const auto& p : v) std::printf("%-32s %-9s %s\n", p.name.c_str(), p.category.c_str(), p.description.c_str());
        }
        return kExitOk;
      }
      const auto p = lib.find(o->name);
      if (!p) throw LibraryError(lib.location() + ": no patient named \"" + o->name + "\" (see `palpation patient list`)");
      if (show->parsed()) {
        std::printf("%s\n", patient_scenario(*p).dump(2).c_str());
        return kExitOk;
      }
      if (rm->parsed()) {
        lib.remove(o->name);
        std::printf("removed \"%s\" from %s\n", o->name.c_str(), lib.location().c_str());
        return kExitOk;
      }
      if (exp->parsed()) {
        // Staged: a temporary file renamed into place, so nothing is written half.
        namespace fs = std::filesystem;
        std::string mesh_name;
        if (!p->mesh.empty()) {
          mesh_name = fs::path(o->file).filename().string() + ".pmesh";
          const std::string mp = o->file + ".pmesh";
          {
            std::ofstream m(mp + ".tmp", std::ios::binary);
            m.write(p->mesh.data(), std::streamsize(p->mesh.size()));
            if (!m) throw std::runtime_error(mp + ": write failed");
          }
          fs::rename(mp + ".tmp", mp);
        }
        {
          std::ofstream f(o->file + ".tmp");
          f << patient_scenario(*p, mesh_name).dump(2) << "\n";
          if (!f) throw std::runtime_error(o->file + ": cannot be written");
        }
        fs::rename(o->file + ".tmp", o->file);
        std::printf("exported \"%s\" -> %s%s\n", o->name.c_str(), o->file.c_str(), mesh_name.empty() ? "" : (" (+ " + o->file + ".pmesh)").c_str());
        return kExitOk;
      }
      return kExitBadInput;
    });
  };
}

}  // namespace palpation::app::cli
