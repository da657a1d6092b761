// libFuzzer target: the scan importer's reading and checking (app/scan/scan_import.h):
// assimp's STL/OBJ/PLY readers behind read_surface (app/scan/scan_read_assimp.cpp), then
// repair_surface and find_base_plane, i.e. everything import_scan does before Gmsh
// tetrahedralises in a child process (not run here: it needs Gmsh and a fork per input).
// The first input byte picks the file extension (0: .stl, 1: .obj, 2: .ply), the rest is
// the file. Contract (abort otherwise): read_surface returns finite vertices and
// triangles whose indices are in range, or throws ImportError with one line naming the
// file; repair keeps indices in range and its report consistent; a closed surface's base
// plane has a unit normal and a finite offset. Any other exception, a crash or a
// sanitizer report is a finding. assimp itself is Debian's uninstrumented build: its
// crashes are caught, its internal memory errors only when they crash. Since finding 7
// (docs/fuzzing.md) assimp runs in read_surface's child process (this executable,
// re-executed: app/scan/scan_read_child.h): the file checks run here under the fuzzer's eyes,
// assimp and the conversion of its scene run in the child, whose coverage and memory
// libFuzzer does not see; its crash, hang or excess is an ImportError here.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scan/scan_import.h"

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
void check_indices(const palpation::app::scan::SurfaceMesh& s) {
  const int n = int(s.vertices.size());
  for (const auto& v : s.vertices) check(v.allFinite());
  for (const auto& t : s.triangles)
    for (int i : t) check(i >= 0 && i < n);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace palpation::app::scan;
  if (size < 1) return 0;
  static const char* const kExt[3] = {".stl", ".obj", ".ply"};
  const std::string path = "/tmp/palpation-fuzz-scan-" + std::to_string(::getpid()) + kExt[data[0] % 3];
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  if (size > 1) std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  try {
    SurfaceMesh s = read_surface(path);
    check(!s.triangles.empty());
    check_indices(s);
    const SurfaceReport r = repair_surface(s);
    check_indices(s);
    check(r.triangles == int(s.triangles.size()) && r.vertices >= 0 && r.open_edges >= 0 && r.nonmanifold_edges >= 0);
    check(r.problems().find('\n') == std::string::npos && r.repairs().find('\n') == std::string::npos);
    if (r.ok()) {
      const BasePlane b = find_base_plane(s);
      check(std::isfinite(b.offset) && std::isfinite(b.area) && b.area >= 0);
      check(std::abs(b.normal.norm() - 1.0) < 1e-6);
    }
  } catch (const ImportError& e) {
    const std::string w = e.what();
    check(w.find('\n') == std::string::npos && w.rfind(path, 0) == 0);
  }
  std::remove(path.c_str());
  return 0;
}
