#include "scan/imported_patient.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "model_cache.h"

namespace palpation::app::scan {

using store::PatientRecord;

PatientRecord imported_patient_record(const ImportResult& r, const std::string& name, const std::string& scan_file, double edge) {
  namespace fs = std::filesystem;
  // The mesh as .pmesh bytes, through a temporary file of its own (process and call).
  static std::atomic<unsigned> serial{0};
  const std::string tmp = (fs::temp_directory_path() / ("palpation-import-" + std::to_string(::getpid()) + "-" +
                                                        std::to_string(serial.fetch_add(1)) + ".pmesh"))
                              .string();
  PatientRecord p;
  try {
    sim::save_mesh_cache(tmp, r.mesh, "import " + scan_file);
    std::ifstream in(tmp, std::ios::binary);
    p.mesh.assign(std::istreambuf_iterator<char>(in), {});
    if (!in.good() && !in.eof()) throw std::runtime_error(tmp + ": cannot read");
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::remove(tmp, ec);
  if (p.mesh.empty()) throw std::runtime_error(tmp + ": the mesh could not be written");
  p.name = name;
  p.category = "imported";
  p.source = fs::absolute(scan_file).string();
  char desc[300];
  std::snprintf(desc, sizeof desc, "Imported scan %s: %d nodes, %d tetrahedra, edge %.4g m; base plane %s (%.1f cm^2)",
                fs::path(scan_file).filename().string().c_str(), r.mesh.num_nodes(), r.mesh.num_tets(), edge,
                r.base.automatic ? "found" : "given", r.base.area * 1e4);
  p.description = desc;
  p.body = {{"patient", {{"mesh", name + ".pmesh"}}},
            {"tissue", {{"young_modulus", 19000}, {"poisson_ratio", 0.45}, {"density", 1000}}},
            {"inclusions", nlohmann::json::array()}};
  // The default press of `patient export`: straight down over the highest point.
  Eigen::Vector3d top = r.mesh.nodes.empty() ? Eigen::Vector3d::Zero() : r.mesh.nodes.front();
  for (const auto& n : r.mesh.nodes)
    if (n.z() > top.z()) top = n;
  const double rad = 0.008, z0 = top.z() + rad + 0.005, z1 = top.z() + rad - 0.01;
  p.body["fingers"] = nlohmann::json::array(
      {{{"radius", rad}, {"path", {{0.0, top.x(), top.y(), z0}, {1.0, top.x(), top.y(), z1}, {2.0, top.x(), top.y(), z0}}}}});
  p.body["duration"] = 2.0;
  return p;
}

}  // namespace palpation::app::scan
