#include "scan/scan_import_job.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "model_cache.h"
#include "scenario.h"

namespace palpation::app::scan {

using live::PatientGeometry;
using store::PatientRecord;
using store::patient_scenario;

ScanImportJob::~ScanImportJob() { cancel(); }

void ScanImportJob::start(const std::string& path, ImportOptions opt) {
  cancel();
  cancel_.store(false);
  cancelled_.store(false);
  finished_.store(false);
  progress_.store(0);
  {
    std::lock_guard<std::mutex> lk(mu_);
    stage_ = "reading";
    error_.clear();
    result_.reset();
  }
  running_.store(true, std::memory_order_release);
  worker_ = std::thread([this, path, opt = std::move(opt)]() mutable {
    opt.progress = [this](double p, const std::string& stage) {
      progress_.store(p, std::memory_order_relaxed);
      {
        std::lock_guard<std::mutex> lk(mu_);
        stage_ = stage;
      }
      return !cancel_.load(std::memory_order_relaxed);
    };
    try {
      auto r = std::make_shared<ImportResult>(import_scan(path, opt));
      std::lock_guard<std::mutex> lk(mu_);
      result_ = std::move(r);
      stage_ = "done";
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lk(mu_);
      error_ = cancel_.load() ? std::string("cancelled") : std::string(e.what());
      if (cancel_.load()) cancelled_.store(true);
    }
    finished_.store(true, std::memory_order_release);
    running_.store(false, std::memory_order_release);
  });
}

void ScanImportJob::cancel() {
  cancel_.store(true);
  if (worker_.joinable()) worker_.join();
}

std::string ScanImportJob::stage() const {
  std::lock_guard<std::mutex> lk(mu_);
  return stage_;
}

std::shared_ptr<const ImportResult> ScanImportJob::result() const {
  std::lock_guard<std::mutex> lk(mu_);
  return result_;
}

std::string ScanImportJob::error() const {
  std::lock_guard<std::mutex> lk(mu_);
  return error_;
}

}  // namespace palpation::app::scan

namespace palpation::app::scan {

std::shared_ptr<PatientGeometry> preview_geometry(const sim::TetMesh& mesh, std::uint64_t generation) {
  auto g = std::make_shared<PatientGeometry>();
  g->generation = generation;
  g->rest = mesh.nodes;
  g->tets = mesh.tets;
  g->surface = mesh.boundary_faces();
  g->young.assign(mesh.tets.size(), g->tissue_young);
  g->centroid.resize(mesh.tets.size());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) c += mesh.nodes[std::size_t(mesh.tets[e][a])];
    g->centroid[e] = c / 4.0;
  }
  g->backend = "preview";
  return g;
}

sim::Scenario library_patient_scenario(const PatientRecord& p, const std::string& mesh_dir) {
  namespace fs = std::filesystem;
  std::string mesh_file;
  if (!p.mesh.empty()) {
    fs::create_directories(mesh_dir);
    char h[32];
    std::uint64_t v = 1469598103934665603ull;
    for (unsigned char c : p.mesh) v = (v ^ c) * 1099511628211ull;
    std::snprintf(h, sizeof h, "%016llx", static_cast<unsigned long long>(v));
    std::string safe;
    for (char c : p.name) safe += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
    mesh_file = (fs::path(mesh_dir) / (safe + "-" + std::string(h).substr(0, 12) + ".pmesh")).string();
    if (!fs::exists(mesh_file)) {
      const std::string tmp = mesh_file + ".tmp";
      {
        std::ofstream m(tmp, std::ios::binary);
        m.write(p.mesh.data(), std::streamsize(p.mesh.size()));
        if (!m) throw std::runtime_error(tmp + ": write failed");
      }
      fs::rename(tmp, mesh_file);
    }
  }
  sim::Scenario s = sim::parse_scenario(patient_scenario(p, mesh_file).dump(), "patient library: " + p.name);
  s.source = p.name;
  return s;
}

}  // namespace palpation::app::scan
