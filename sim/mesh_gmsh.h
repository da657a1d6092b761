// Gmsh, behind this one header (design.md: Gmsh for meshing only, behind one file).
// Implemented in mesh_gmsh.cpp when the build has Gmsh, else in mesh_gmsh_none.cpp,
// whose functions throw a clear error.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "mesh.h"
#include "phantom.h"
#include "scenario.h"

namespace palpation::sim {

/// True when this build links Gmsh.
bool gmsh_available();

/// Tetrahedralises the breast phantom with target edge length `edge` (m). The inclusions'
/// surfaces are embedded (elements conform to them, region tag i+1 for inclusion i) and
/// the mesh is refined inside and around them. Throws std::runtime_error.
TetMesh gmsh_breast(const BreastShape& shape, double edge, const std::vector<Inclusion>& inclusions,
                    const LogFn& log);

/// Tetrahedralises a closed, consistently oriented triangle surface with target edge
/// length `edge` (m), in a child process (self_child.h): a Gmsh crash or hang costs an error, and
/// `cancelled` (polled every 0.1 s; may be empty) or `timeout_s` stops it. Throws
/// std::runtime_error ("Gmsh: ..." / "cancelled ...").
TetMesh gmsh_tetrahedralize(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles,
                            double edge, double timeout_s, const std::function<bool()>& cancelled);

/// Reads a volume mesh file Gmsh understands (.msh v2/v4, .vtk, .mesh, ...): its linear
/// tetrahedra, physical/elementary volume tags as region. Throws std::runtime_error
/// naming the file and the reason.
TetMesh gmsh_read_volume(const std::string& path);

}  // namespace palpation::sim
