// assimp, behind this one file: reads the triangles of an STL, OBJ or PLY scan. The
// cheap checks of the file run in the calling process; assimp itself runs only in the
// scan reader's child process (app/scan/scan_read_child.cpp: memory and CPU-time limits), so
// that whatever a malformed file makes assimp do costs an error message, not the session.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <new>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scan/scan_import.h"
#include "scan/scan_read_child.h"

namespace palpation::app::scan {

bool scan_reader_available() { return true; }

SurfaceMesh read_surface(const std::string& path, const std::function<bool()>& cancelled) {
  reader::check_file(path);
  return reader::read_in_child(path, reader::limits_for(path), cancelled);
}

namespace reader {

void check_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ImportError(path + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw ImportError(path + ": not a regular file");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    throw ImportError(path + ": unsupported scan format \"" + ext + "\" (STL, OBJ or PLY)");
  if (fs::file_size(path, ec) == 0) throw ImportError(path + ": empty file (0 bytes)");
  {
    // Text formats must start with their keyword; anything else is garbage bytes.
    std::ifstream in(path, std::ios::binary);
    char head[5] = {};
    in.read(head, 5);
    const std::string h(head, std::size_t(in.gcount()));
    if (ext == ".ply" && h.rfind("ply", 0) != 0) throw ImportError(path + ": not a PLY file (no \"ply\" header): garbage bytes?");
    if (ext == ".ply") {
      // The header must be text ending in an "end_header" line within its first 64 kB.
      // assimp 5.2's PLY reader loops without end on a header with a NUL byte in it
      // (fuzz_scan_import, docs/fuzzing.md): it never gets to see such a file.
      in.seekg(0);
      std::string header(65536, '\0');
      in.read(header.data(), std::streamsize(header.size()));
      header.resize(std::size_t(in.gcount()));
      const std::size_t end = header.find("\nend_header");
      const std::size_t eol = end == std::string::npos ? end : header.find_first_of("\r\n", end + 11);
      if (end == std::string::npos || eol == std::string::npos || header.find_first_not_of(" \t", end + 11) != eol)
        throw ImportError(path + ": not a PLY file (no \"end_header\" line in the first 64 kB): truncated or garbage bytes?");
      for (std::size_t i = 0; i < end; ++i) {
        const unsigned char c = static_cast<unsigned char>(header[i]);
        if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || c > 0x7e)
          throw ImportError(path + ": not a PLY file (byte " + std::to_string(i) + " of the header is not text): garbage bytes?");
      }
    }
  }
}

SurfaceMesh read_here(const std::string& path) {
  Assimp::Importer imp;
  // Normals dropped so that STL corners merge (each STL facet carries its own normal).
  imp.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TEXCOORDS | aiComponent_COLORS);
  // ValidateDataStructure first: assimp 5.2's PLY reader passes out-of-range face indices on to
  // the other steps, which then read out of bounds (fuzz_scan_import crash, docs/fuzzing.md).
  // No aiProcess_Triangulate: its ai_assert aborts the process on some malformed PLY
  // faces (fuzz_scan_import); polygons are fanned into triangles below instead.
  const aiScene* sc = imp.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_DropNormals |
                                             aiProcess_RemoveComponent | aiProcess_JoinIdenticalVertices |
                                             aiProcess_PreTransformVertices);
  if (!sc) {
    std::string why = imp.GetErrorString();
    // assimp's importers catch a failed allocation's std::bad_alloc and return its text as
    // the error: out of memory, not a verdict on the file (the child reports its limit).
    if (why.find("bad_alloc") != std::string::npos) throw std::bad_alloc();
    for (char& c : why)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    if (why.size() > 200) why = why.substr(0, 200) + "...";
    if (why.find("No output meshes") != std::string::npos || why.find("no meshes") != std::string::npos ||
        why.find("contains no faces") != std::string::npos)
      throw ImportError(path + ": empty: no triangles in the file (" + why + ")");
    throw ImportError(path + ": not a mesh file assimp reads (" + why + "): empty, truncated or garbage bytes?");
  }
  SurfaceMesh s;
  for (unsigned m = 0; m < sc->mNumMeshes; ++m) {
    const aiMesh* mesh = sc->mMeshes[m];
    const int base = int(s.vertices.size());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      const Eigen::Vector3d v(p.x, p.y, p.z);
      if (!v.allFinite()) throw ImportError(path + ": vertex " + std::to_string(i) + " is not finite (garbage bytes?)");
      s.vertices.push_back(v);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices) throw ImportError(path + ": face " + std::to_string(f) + " refers to a missing vertex");
      // A polygon as a fan of triangles (scans are triangles; OBJ may hold quads).
      for (unsigned k = 1; k + 1 < face.mNumIndices; ++k)
        s.triangles.push_back({base + int(face.mIndices[0]), base + int(face.mIndices[k]), base + int(face.mIndices[k + 1])});
    }
  }
  if (s.triangles.empty()) throw ImportError(path + ": empty: no triangles in the file");
  return s;
}

}  // namespace reader

}  // namespace palpation::app::scan
