// The workstation's session recorder (docs/recording.md): every GUI session
// records the patient and all settings (header), the device input and the forces sent at
// 1 kHz (ticks), the simulation thread's steps (dt, fingertip inputs, forces out: the
// review re-simulates from these exactly), instructor events, parameter changes as data
// (tumour edits, tissue and solver changes, patient swaps) and trainee marks.
//
// Listens to app::live::Workstation's telemetry on the thread that calls Workstation::poll()
// (the GUI thread); the file is written by RecordingWriter (whole chunks at least every
// 0.25 s, fdatasync at least every second). Qt-free.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "store/recording.h"
#include "live/workstation.h"

namespace palpation::app::review {

namespace dv = palpation::device;

using live::TickSample;
using live::Workstation;
using store::RecordingWriter;

class WorkstationRecorder {
 public:
  static constexpr int kFingers = dv::kMaxFingers;  // device fingers 0..4 (thumb..little)

  /// Creates `path` and writes the header: the workstation's patient scenario, device
  /// configuration, session (device, backend request, real-time dt, program) and
  /// `settings` (the GUI's: language, mode, ...). Registers its listeners on `ws` (which
  /// must outlive this recorder or stop polling first). Throws RecordingError.
  WorkstationRecorder(Workstation& ws, const std::string& path, nlohmann::json settings = nlohmann::json::object());
  ~WorkstationRecorder();

  /// A trainee's mark: "I feel a lump here" at `position` (world, m), as sure as
  /// `confidence` (0..1; recorded as "confidence", which recordings made before it lack:
  /// read those as 1). Returns the mark's number (1, 2, ...).
  int add_mark(const Eigen::Vector3d& position, const std::string& note = {}, double confidence = 1.0);
  /// Any other event worth keeping (mode changes, view settings): kind "instructor".
  void add_event(const std::string& kind, nlohmann::json data);
  /// Syncs to disk when the last sync is over a second old (call every ~second).
  void flush();
  /// Ends the recording (end chunk). Idempotent.
  void close();

  const std::string& path() const { return writer_->path(); }
  bool failed() const { return writer_->failed(); }
  const std::string& error() const { return writer_->error(); }
  std::uint64_t ticks() const { return writer_->ticks(); }
  std::uint64_t steps() const { return writer_->steps(); }
  int marks() const { return marks_; }

 private:
  void on_tick(const TickSample& s);
  void emit_tick();

  Workstation& ws_;
  std::unique_ptr<RecordingWriter> writer_;
  sim::Scenario scenario_;  // the patient now (params commands are recorded against it)
  std::array<Eigen::Vector3d, kFingers> x_{}, f_{};
  double tick_t_ = -1, last_t_ = 0;
  bool pending_ = false;
  int marks_ = 0;
  double force_scale_ = 0;  // the last force scale recorded (a "session" event when it changes)
  int lock_fd_ = -1;  // flock held while recording: recovery leaves a live file alone
  std::shared_ptr<bool> alive_;
};

/// Recovers the interrupted recordings (*.palrec without an end chunk, not being written
/// by a running program) in `dir`: their torn tails cut, an end chunk marked "recovered"
/// appended (recover_recording). Returns one line per file recovered; a file that cannot
/// be recovered is left as it is and reported.
std::vector<std::string> recover_interrupted_recordings(const std::string& dir);

/// The scenario as the recording keeps it: finger paths cut to their first two keyframes
/// (the device input is what matters), `fingers` fingers of the first one's radius.
nlohmann::json recorded_scenario_json(const sim::Scenario& s, int fingers);

}  // namespace palpation::app::review
