#include "phantom.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "mesh_gmsh.h"
#include "model_cache.h"

namespace palpation::sim {

double BreastShape::surface_z(double x, double y) const {
  const double r2 = ((x - center_x) * (x - center_x) + y * y) / (base_radius * base_radius);
  return r2 >= 1.0 ? 0.0 : height * std::sqrt(1.0 - r2);
}

bool BreastShape::contains(const Eigen::Vector3d& p) const {
  return p.z() >= 0 && p.z() <= surface_z(p.x(), p.y());
}

namespace {

std::string breast_key(const BreastShape& b, double edge, const std::vector<Inclusion>& incs) {
  std::ostringstream k;
  k.precision(9);
  k << "breast/v2-delaunay c=" << b.center_x << " a=" << b.base_radius << " h=" << b.height << " edge=" << edge;
  for (const auto& i : incs)
    k << " inc(" << i.shape << ' ' << i.center.transpose() << ' ' << i.radii.transpose() << ')';
  // Only when set, so that every mesh without it keeps its key (and its cache file).
  if (b.skin_edge > 0) k << " skin=" << b.skin_edge;
  return k.str();
}

}  // namespace

TetMesh patient_mesh(const Scenario& s, const LogFn& log) {
  using clock = std::chrono::steady_clock;
  auto say = [&log](const std::string& m) {
    if (log) log(m);
  };
  if (!s.patient.mesh.empty()) {
    const std::string& path = s.patient.mesh;
    if (!std::filesystem::exists(path)) throw ScenarioError(s.source + ": patient.mesh: file not found: " + path);
    TetMesh m;
    std::string why;
    // Our own cache format first (works without Gmsh), then anything Gmsh reads.
    if (path.size() > 6 && path.substr(path.size() - 6) == ".pmesh") {
      if (!load_mesh_cache(path, "", m, &why, /*check_key=*/false))
        throw ScenarioError(s.source + ": patient.mesh: " + path + ": " + why);
      return m;
    }
    try {
      m = gmsh_read_volume(path);
    } catch (const std::exception& e) {
      throw ScenarioError(s.source + ": patient.mesh: " + e.what());
    }
    if (std::string v = m.validate(); !v.empty()) throw ScenarioError(s.source + ": patient.mesh: " + path + ": " + v);
    return m;
  }
  if (s.patient.phantom == "box") {
    const auto t0 = clock::now();
    TetMesh m = make_box_mesh(s.patient.size, s.patient.edge, s.patient.grading);
    const double ms = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
    std::ostringstream o;
    o << "meshing: box " << m.num_nodes() << " nodes, " << m.num_tets() << " tetrahedra in " << ms << " ms";
    say(o.str());
    return m;
  }
  // Breast phantom: cached Gmsh mesh.
  BreastShape shape;
  shape.base_radius = s.patient.base_radius;
  shape.height = s.patient.height;
  shape.skin_edge = s.patient.skin_edge;
  const std::string key = breast_key(shape, s.patient.edge, s.inclusions);
  std::ostringstream name;
  name << "breast-" << std::hex << key_hash(key) << ".pmesh";
  const std::string path = (std::filesystem::path(cache_dir()) / name.str()).string();
  TetMesh m;
  std::string why;
  if (load_mesh_cache(path, key, m, &why)) {
    say("meshing: breast from cache " + path + " (" + std::to_string(m.num_nodes()) + " nodes, " +
        std::to_string(m.num_tets()) + " tetrahedra)");
    return m;
  }
  if (why != "missing") say("meshing: cache " + path + " rejected (" + why + "), meshing again");
  if (!gmsh_available())
    throw MeshUnavailable(s.source + ": patient.phantom: the breast mesh is not in the cache (" + path +
                        ") and this build has no Gmsh: generate it on a machine with Gmsh and carry the "
                        "cache folder (PALPATION_CACHE_DIR)");
  const auto t0 = clock::now();
  try {
    m = gmsh_breast(shape, s.patient.edge, s.inclusions, log);
  } catch (const std::exception& e) {
    throw ScenarioError(s.source + ": patient: meshing the breast failed: " + e.what());
  }
  const double sec = std::chrono::duration<double>(clock::now() - t0).count();
  std::ostringstream o;
  o << "meshing: breast " << m.num_nodes() << " nodes, " << m.num_tets() << " tetrahedra in " << sec << " s";
  say(o.str());
  try {
    save_mesh_cache(path, m, key);
  } catch (const std::exception& e) {
    say(std::string("meshing: could not write the cache: ") + e.what());
  }
  return m;
}

}  // namespace palpation::sim
