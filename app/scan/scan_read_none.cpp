// Builds without assimp: scans cannot be read (a clear message).
#include "scan/scan_import.h"

namespace palpation::app::scan {

bool scan_reader_available() { return false; }

SurfaceMesh read_surface(const std::string& path, const std::function<bool()>&) {
  throw ImportError(path + ": this build has no assimp to read STL/OBJ/PLY scans (Debian: libassimp-dev)");
}

}  // namespace palpation::app::scan
