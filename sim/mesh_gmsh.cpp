// Gmsh meshing of the breast phantom and import of volume mesh files. The only file of
// the project that includes gmsh.h (design.md section 2). Gmsh keeps global state, so
// every use holds one process-wide lock from gmsh::initialize to gmsh::finalize.
#include "mesh_gmsh.h"

#include <gmsh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace palpation::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// One Gmsh API session: the process-wide lock, initialize on entry, finalize on every
/// exit (also on exceptions). Gmsh cannot be initialised twice at the same time.
class GmshSession {
 public:
  GmshSession() : lock_(mutex()) {
    // No argv, no gmshrc/gmsh-options files: the same result on every machine.
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);  // no console output
    gmsh::option::setNumber("General.Verbosity", 2);  // keep errors and warnings in the logger
    gmsh::option::setNumber("General.AbortOnError", 3);  // errors throw (the API default is 2)
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
      // Nothing sensible to do while unwinding.
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The last error Gmsh logged (empty when none), for messages.
  static std::string last_error() {
    std::string e;
    try {
      gmsh::logger::getLastError(e);
    } catch (...) {
    }
    // Gmsh prefixes "Error   : "-style tags in some builds; keep the message only.
    while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
    return e;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
};

/// Text of an exception Gmsh threw: std::exception, a string, or anything else.
std::string reason_of(std::exception_ptr p) {
  std::string r;
  try {
    std::rethrow_exception(p);
  } catch (const std::exception& e) {
    r = e.what();
  } catch (const std::string& s) {
    r = s;
  } catch (const char* s) {
    r = s ? s : "";
  } catch (...) {
  }
  const std::string last = GmshSession::last_error();
  if (r.empty() || r == "std::exception") r = last;
  if (r.empty()) r = "unknown Gmsh error";
  return r;
}

/// Linear tetrahedra of the current model's volume entities, with the nodes they use
/// renumbered 0..n-1 in order of first use. `region_of` maps a volume entity tag to the
/// region tag of its elements; entities it maps to a negative value are skipped.
/// Quadratic tetrahedra (type 11) contribute their four corner nodes.
template <class RegionOf>
TetMesh extract_tets(RegionOf region_of) {
  TetMesh mesh;
  gmsh::vectorpair vols;
  gmsh::model::getEntities(vols, 3);
  std::unordered_map<std::size_t, int> index;  // Gmsh node tag -> compact index
  std::vector<std::size_t> used;               // compact index -> Gmsh node tag
  for (const auto& [dim, tag] : vols) {
    const int region = region_of(tag);
    if (region < 0) continue;
    for (const int type : {4, 11}) {
      std::vector<std::size_t> elems, enodes;
      gmsh::model::mesh::getElementsByType(type, elems, enodes, tag);
      const std::size_t per = type == 4 ? 4 : 10;
      if (elems.empty() || enodes.size() != elems.size() * per) continue;
      for (std::size_t e = 0; e < elems.size(); ++e) {
        std::array<int, 4> t{};
        for (int k = 0; k < 4; ++k) {
          const std::size_t gt = enodes[e * per + static_cast<std::size_t>(k)];
          auto [it, fresh] = index.try_emplace(gt, static_cast<int>(used.size()));
          if (fresh) used.push_back(gt);
          t[static_cast<std::size_t>(k)] = it->second;
        }
        mesh.tets.push_back(t);
        mesh.region.push_back(region);
      }
    }
  }
  if (mesh.tets.empty()) return mesh;

  // Coordinates of the used nodes only.
  mesh.nodes.assign(used.size(), Eigen::Vector3d::Zero());
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, /*includeBoundary=*/true,
                              /*returnParametricCoord=*/false);
  std::vector<char> seen(used.size(), 0);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    auto it = index.find(tags[i]);
    if (it == index.end()) continue;
    mesh.nodes[static_cast<std::size_t>(it->second)] =
        Eigen::Vector3d(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]);
    seen[static_cast<std::size_t>(it->second)] = 1;
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    if (!seen[i])
      throw std::runtime_error("tetrahedra refer to node " + std::to_string(used[i]) + ", which has no coordinates");
  return mesh;
}

/// Normalised ellipsoidal radius of an inclusion, sqrt(sum ((x - c)/r)^2), as a Gmsh
/// MathEval expression: 1 on its surface, 2 one radius outside it.
std::string normalized_radius_expr(const Inclusion& inc) {
  std::ostringstream f;
  f.precision(17);
  f << "Sqrt(";
  const char* axis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (k) f << " + ";
    f << "((" << axis[k] << " - (" << inc.center[k] << ")) / " << inc.radii[k] << ")^2";
  }
  f << ")";
  return f.str();
}

}  // namespace

bool gmsh_available() { return true; }

TetMesh gmsh_breast(const BreastShape& shape, double edge, const std::vector<Inclusion>& inclusions,
                    const LogFn& log) {
  if (!(edge > 0) || !std::isfinite(edge)) throw std::runtime_error("edge length must be positive");
  if (!(shape.base_radius > 0) || !(shape.height > 0)) throw std::runtime_error("breast shape must have positive size");
  const double a = shape.base_radius, h = shape.height, cx = shape.center_x;  // m
  const auto t0 = std::chrono::steady_clock::now();

  GmshSession session;
  TetMesh mesh;
  int algorithm = 10;
  try {
    gmsh::model::add("breast");
    namespace occ = gmsh::model::occ;

    // Dome: upper half ball (polar angle 0..pi/2, flat disc on z = 0) of radius a about
    // (cx, 0, 0), stretched along z by h / a into the half ellipsoid.
    const int dome = occ::addSphere(cx, 0, 0, a, -1, 0.0, kPi / 2);
    occ::dilate({{3, dome}}, cx, 0, 0, 1.0, 1.0, h / a);

    // Inclusions whose bounding box reaches into the dome's bounding box. Spheres stay
    // exact spheres; ellipsoids are unit spheres stretched per axis.
    std::vector<int> inc_index;  // tool entity k -> inclusion index
    gmsh::vectorpair tools;
    for (std::size_t i = 0; i < inclusions.size(); ++i) {
      const Inclusion& inc = inclusions[i];
      const Eigen::Vector3d& c = inc.center;
      const Eigen::Vector3d& r = inc.radii;
      if (!c.allFinite() || !r.allFinite() || (r.array() <= 0).any()) continue;
      if (c.z() + r.z() <= 0 || c.z() - r.z() >= h || c.x() + r.x() <= cx - a || c.x() - r.x() >= cx + a ||
          c.y() + r.y() <= -a || c.y() - r.y() >= a)
        continue;
      const int s = occ::addSphere(c.x(), c.y(), c.z(), r.x());
      if (r.y() != r.x() || r.z() != r.x()) occ::dilate({{3, s}}, c.x(), c.y(), c.z(), 1.0, r.y() / r.x(), r.z() / r.x());
      tools.push_back({3, s});
      inc_index.push_back(static_cast<int>(i));
    }

    // Volume tag -> region. Fragmenting makes the inclusion surfaces interior faces of
    // one conforming mesh; pieces of inclusions outside the dome are removed.
    std::unordered_map<int, int> region_of;
    if (tools.empty()) {
      occ::synchronize();
      region_of[dome] = 0;
    } else {
      gmsh::vectorpair out;
      std::vector<gmsh::vectorpair> map;
      occ::fragment({{3, dome}}, tools, out, map);
      if (map.size() != 1 + tools.size()) throw std::runtime_error("OpenCASCADE fragment returned an unexpected map");
      for (const auto& [dim, tag] : map[0])
        if (dim == 3) region_of[tag] = 0;
      // The first inclusion that contains a piece names it (as apply_inclusions does).
      for (std::size_t k = tools.size(); k-- > 0;)
        for (const auto& [dim, tag] : map[k + 1])
          if (dim == 3 && region_of.count(tag)) region_of[tag] = inc_index[k] + 1;
      gmsh::vectorpair outside;
      for (const auto& [dim, tag] : out)
        if (dim == 3 && !region_of.count(tag)) outside.push_back({dim, tag});
      if (!outside.empty()) occ::remove(outside, /*recursive=*/true);
      occ::synchronize();
    }
    if (region_of.empty()) throw std::runtime_error("the dome vanished in the boolean operations");

    // Mesh size: `edge` everywhere, refined to 0.6 edge inside each inclusion and up to
    // one radius around it (normalised radius s <= 2), graded back to `edge` by s = 3.
    // Small inclusions get at least two elements across their smallest radius.
    gmsh::option::setNumber("Mesh.MeshSizeMax", edge);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    std::vector<double> thresholds;
    for (std::size_t k = 0; k < tools.size(); ++k) {
      const Inclusion& inc = inclusions[static_cast<std::size_t>(inc_index[k])];
      const double fine = std::max(std::min(0.6 * edge, 0.5 * inc.radii.minCoeff()), 0.05 * edge);
      const int f = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(f, "F", normalized_radius_expr(inc));
      const int t = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(t, "IField", f);
      gmsh::model::mesh::field::setNumber(t, "LcMin", fine);
      gmsh::model::mesh::field::setNumber(t, "LcMax", edge);
      gmsh::model::mesh::field::setNumber(t, "DistMin", 2.0);
      gmsh::model::mesh::field::setNumber(t, "DistMax", 3.0);
      thresholds.push_back(t);
    }
    if (!thresholds.empty()) {
      const int m = gmsh::model::mesh::field::add("Min");
      gmsh::model::mesh::field::setNumbers(m, "FieldsList", thresholds);
      gmsh::model::mesh::field::setAsBackgroundMesh(m);
    }

    gmsh::option::setNumber("General.NumThreads", 2);
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::mesh::generate(2);
    // HXT (parallel Delaunay) first; the classic Delaunay mesher if HXT fails.
    try {
      gmsh::option::setNumber("Mesh.Algorithm3D", 10);
      gmsh::model::mesh::generate(3);
    } catch (...) {
      algorithm = 1;
      gmsh::model::mesh::clear();
      gmsh::option::setNumber("Mesh.Algorithm3D", 1);
      gmsh::model::mesh::generate(3);
    }

    mesh = extract_tets([&region_of](int tag) {
      auto it = region_of.find(tag);
      return it == region_of.end() ? -1 : it->second;
    });
  } catch (...) {
    throw std::runtime_error("Gmsh: " + reason_of(std::current_exception()));
  }
  if (mesh.tets.empty()) throw std::runtime_error("Gmsh produced no tetrahedra");

  // The chest wall is exactly z = 0 (fix_base selects z <= zmin + 1e-6).
  for (auto& p : mesh.nodes)
    if (std::abs(p.z()) < 1e-9) p.z() = 0.0;
  mesh.orient();

  if (log) {
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ostringstream o;
    o.precision(3);
    o << "gmsh: breast edge " << edge * 1000 << " mm, " << inclusions.size() << " inclusion(s): "
      << mesh.num_nodes() << " nodes, " << mesh.num_tets() << " tetrahedra in " << sec << " s ("
      << (algorithm == 10 ? "HXT" : "Delaunay") << ")";
    log(o.str());
  }
  return mesh;
}

TetMesh gmsh_read_volume(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw std::runtime_error(path + ": no such file");
  if (!std::ifstream(path, std::ios::binary)) throw std::runtime_error(path + ": cannot be read");

  GmshSession session;
  TetMesh mesh;
  try {
    gmsh::model::add("import");
    gmsh::merge(path);
    gmsh::vectorpair vols;
    gmsh::model::getEntities(vols, 3);
    std::unordered_map<int, int> order;  // volume entity tag -> 0-based index
    for (std::size_t i = 0; i < vols.size(); ++i) order[vols[i].second] = static_cast<int>(i);
    mesh = extract_tets([&order](int tag) { return order.at(tag); });
  } catch (...) {
    throw std::runtime_error(path + ": " + reason_of(std::current_exception()));
  }
  if (mesh.tets.empty()) throw std::runtime_error(path + ": contains no tetrahedra");
  mesh.orient();
  return mesh;
}

}  // namespace palpation::sim
