// Builds without Gmsh (the GPU machine): meshing is refused with a clear message; cached
// meshes still load (model_cache.cpp).
#include <stdexcept>

#include "mesh_gmsh.h"

namespace palpation::sim {

bool gmsh_available() { return false; }

TetMesh gmsh_breast(const BreastShape&, double, const std::vector<Inclusion>&, const LogFn&) {
  throw std::runtime_error("this build has no Gmsh");
}

TetMesh gmsh_tetrahedralize(const std::vector<Eigen::Vector3d>&, const std::vector<std::array<int, 3>>&, double, double,
                            const std::function<bool()>&) {
  throw std::runtime_error("this build has no Gmsh to tetrahedralise a scan");
}

TetMesh gmsh_read_volume(const std::string& path) {
  throw std::runtime_error(path + ": this build has no Gmsh to read it (use a .pmesh file)");
}

}  // namespace palpation::sim
