// Importing a scanned breast (the paper's route: scan -> surface mesh -> tetrahedral
// mesh): STL, OBJ and PLY through assimp (behind scan_read_assimp.cpp alone), checked to
// be one closed manifold surface, safely repaired, its chest-wall base plane found
// (largest planar region, or given), aligned so that the base is z = 0 with the body
// above, tetrahedralised by Gmsh in a child process. Qt-free.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh.h"

namespace palpation::app::scan {

/// A bad scan: what() names the file and says exactly what is wrong.
class ImportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// True when this build reads STL/OBJ/PLY (assimp).
bool scan_reader_available();
/// Reads all triangles of the file (no repair). Throws ImportError (empty file, garbage
/// bytes, unsupported format, no triangles; and a file that makes the reader exceed its
/// memory or CPU-time limit, crash or hang: assimp runs in a child process with limits,
/// app/scan/scan_read_child.h). `cancelled` (may be empty) is polled while the child reads:
/// true stops it and throws std::runtime_error("cancelled"). Throws std::runtime_error
/// when the child process cannot be started.
SurfaceMesh read_surface(const std::string& path, const std::function<bool()>& cancelled = {});

/// What checking and repairing found.
struct SurfaceReport {
  int merged_vertices = 0;      // duplicates merged (STL stores each corner separately)
  int degenerate_dropped = 0;   // zero-area triangles
  int duplicate_dropped = 0;    // the same triangle twice
  int flipped = 0;              // triangles turned to the orientation of their neighbours
  bool inverted = false;        // the whole surface was inside out (turned)
  int open_edges = 0;           // edges with one triangle: holes
  int nonmanifold_edges = 0;    // edges with more than two triangles
  int components = 0;           // separate pieces
  int triangles = 0, vertices = 0;
  double volume = 0;            // m^3 (in file units^3 before scaling)
  bool ok() const { return open_edges == 0 && nonmanifold_edges == 0 && components == 1 && volume > 0; }
  /// One line: what is wrong (empty when ok()).
  std::string problems() const;
  /// One line: what was repaired.
  std::string repairs() const;
};

/// Repairs what is safe to repair (merge duplicate vertices, drop degenerate and duplicate
/// triangles, orient consistently and outward) and checks closed + manifold + one piece.
SurfaceReport repair_surface(SurfaceMesh& s);

struct BasePlane {
  Eigen::Vector3d normal = -Eigen::Vector3d::UnitZ();  // unit, pointing out of the body (into the chest)
  double offset = 0;                                   // plane: normal . x = offset
  double area = 0;                                     // of the surface lying on it
  double footprint = 0;  // m^2, the body's outline projected along the normal onto the plane (import_scan fills it)
  bool automatic = true;
  /// The base's share of the body's footprint: about 1 for a scan cut flat at the chest
  /// wall, a few per cent for a closed body touching the plane at one flat patch.
  double footprint_fraction() const { return footprint > 0 ? area / footprint : 0.0; }
  /// Degrees between the normal and the scan's own -z (how far the base is tilted in the file).
  double tilt_deg() const;
};

/// A base must cover at least this share of the body's footprint to be a chest wall
/// (import_scan refuses less). The scans of tests/data (domes cut flat at the base) have
/// 1.00; the largest flat patch of a closed 20 cm sphere (32 x 16 facets) 0.012, of an
/// octahedron subdivided three times onto a 20 cm sphere 0.015 (tst_scan_import). A breast
/// scanned lying on its back and cut at the chest wall has its base under it, most of its
/// outline; a pendulous one, scanned upright, can overhang its base: with an outline
/// reaching twice the base's radius all round, the base is a quarter of it. Below that the
/// body hangs from a patch, not from a chest wall.
inline constexpr double kMinBaseFootprintFraction = 0.25;

/// The area (m^2) of the surface's outline projected along `normal` onto a plane
/// perpendicular to it (rasterised on a 512 x 512 grid over its extent: within 1 % for a
/// disc).
double projected_footprint(const SurfaceMesh& s, const Eigen::Vector3d& normal);

/// The largest planar region of the surface (triangles within 5 degrees and 0.5% of the
/// size of one plane, connected): the cut of the scan at the chest wall.
BasePlane find_base_plane(const SurfaceMesh& s);

struct ImportOptions {
  double edge = 0.00515;                   // m, target tetrahedron edge
  double scale = 1.0;                      // file units -> m
  std::optional<BasePlane> base;           // manual override (normal, offset in metres after scaling)
  double timeout_s = 600;                  // Gmsh
  /// Progress (0..1) and stage; return false to cancel. Called from the calling thread.
  std::function<bool(double, const std::string&)> progress;
};

struct ImportResult {
  SurfaceReport report;
  BasePlane base;
  sim::TetMesh mesh;      // base on z = 0, body above
  double seconds = 0;     // total
  double mesh_seconds = 0;
};

/// The whole import. Throws ImportError (bad scan, naming the file) or std::runtime_error
/// (meshing failed, cancelled: "cancelled").
ImportResult import_scan(const std::string& path, const ImportOptions& opt);

/// Writes a closed half-ellipsoid dome (base radius a, height h, base on z = 0) as ASCII
/// STL, OBJ or PLY by the file's extension; `drop_base` leaves the base open, `extra`
/// adds a triangle on a rim edge (non-manifold), `rotate_x_90` tips it on its side. For
/// tests and examples.
void write_test_dome(const std::string& path, double a, double h, bool drop_base = false, bool extra = false,
                     bool rotate_x_90 = false);

}  // namespace palpation::app::scan
