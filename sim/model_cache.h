// Binary model cache: meshes saved once (Gmsh takes seconds) and loaded by every later
// run, also by the Qt-free, Gmsh-free build on the GPU machine.
//
// File layout (little endian), version 1:
//   char[8]  magic "PALPMSH\0"
//   u32      format version (kCacheVersion)
//   u32      reserved (0)
//   u64      key hash (FNV-1a of the generation key: phantom, edge, inclusions, version)
//   u64      nnode, ntet
//   f64[nnode*3] nodes, i32[ntet*4] tets, i32[ntet] region
//   u64      FNV-1a checksum of everything above
#pragma once

#include <cstdint>
#include <string>

#include "mesh.h"

namespace palpation::sim {

inline constexpr std::uint32_t kCacheVersion = 1;

/// FNV-1a 64 of a string (the generation key).
std::uint64_t key_hash(const std::string& key);

/// Writes atomically (temporary file + rename). Throws std::runtime_error on I/O errors.
void save_mesh_cache(const std::string& path, const TetMesh& mesh, const std::string& key);

/// Loads a cached mesh. Returns false with `why` set ("stale: key differs", "corrupt:
/// checksum mismatch", "version 0 != 1", ...) when the file must not be used.
/// With `check_key` false any key is accepted (a mesh file exported on its own).
bool load_mesh_cache(const std::string& path, const std::string& key, TetMesh& mesh, std::string* why,
                     bool check_key = true);

/// Cache folder: $PALPATION_CACHE_DIR, else $XDG_CACHE_HOME/palpation, else
/// ~/.cache/palpation, else ./.palpation-cache. Created on demand.
std::string cache_dir();

}  // namespace palpation::sim
