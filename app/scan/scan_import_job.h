// A scan import (app/scan/scan_import.h) on a worker thread, for the GUI's "Import scan..."
// dialog: progress and stage readable from any thread, cancel from any thread (the scan
// reader's and Gmsh's child processes are killed through the progress callback). Qt-free.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "scan/imported_patient.h"  // imported_patient_record: what the dialog saves
#include "store/patient_library.h"
#include "scan/scan_import.h"
#include "live/workstation.h"

namespace palpation::app::scan {

using live::PatientGeometry;
using store::PatientRecord;

class ScanImportJob {
 public:
  ScanImportJob() = default;
  ~ScanImportJob();
  ScanImportJob(const ScanImportJob&) = delete;
  ScanImportJob& operator=(const ScanImportJob&) = delete;

  /// Starts importing `path` (a job that is running is cancelled first).
  void start(const std::string& path, ImportOptions opt);
  void cancel();
  bool running() const { return running_.load(std::memory_order_acquire); }
  /// 0..1 and the stage in words ("reading", "meshing", ...).
  double progress() const { return progress_.load(std::memory_order_relaxed); }
  std::string stage() const;
  /// After the job ended: the result, or the error (ImportError names the file and the
  /// problem; "cancelled" after cancel()).
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  std::shared_ptr<const ImportResult> result() const;
  std::string error() const;
  bool cancelled() const { return cancelled_.load(); }

 private:
  std::thread worker_;
  std::atomic<bool> running_{false}, finished_{false}, cancel_{false}, cancelled_{false};
  std::atomic<double> progress_{0};
  mutable std::mutex mu_;
  std::string stage_, error_;
  std::shared_ptr<const ImportResult> result_;
};

/// What the 3-D view needs to preview an imported mesh (rest shape, bulk tissue).
std::shared_ptr<PatientGeometry> preview_geometry(const sim::TetMesh& mesh, std::uint64_t generation);

/// The scenario of a library patient for the workstation: an imported patient's mesh is
/// written once to `mesh_dir`/NAME-HASH.pmesh (created) and referenced from there.
/// Throws sim::ScenarioError / std::runtime_error.
sim::Scenario library_patient_scenario(const PatientRecord& p, const std::string& mesh_dir);

}  // namespace palpation::app::scan
