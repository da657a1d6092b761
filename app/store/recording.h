// Session recordings (docs/recording.md): a versioned, checksummed, crash-safe file.
//
//   "PALREC\r\n"  u32 version  u32 header_len  header (JSON: patient scenario + all settings)  u32 crc32(header)
//   chunks: u32 'CHNK'  u32 type  u32 seq  u32 len  payload[len]  u32 crc32(type, seq, len, payload)
//     type 1 ticks : u32 count, then count x (f64 t, fingers x (f64 x[3], f64 f[3]))   device input + force sent
//     type 2 event : JSON {"t", "kind": "instructor" | "parameter" | "mark" | "session", ...}
//     type 3 end   : JSON footer (clean close, or {"recovered": true, ...} after recovery)
//     type 4 steps : (version 2) u32 count, then count x (f64 t, f64 h, f64 commands_applied,
//                    fingers x (f64 active, f64 radius, f64 x[3], f64 v[3], f64 f[3]))
//                    the simulation thread's steps: dt, the fingertip inputs and the forces
//                    out, so that a review re-simulates a real-time session exactly
//     type 5 ticks, type 6 steps (version 3): the records of a type 1 / type 4 chunk,
//                    compressed losslessly: u32 count, u32 columns, u32 coding (1), then one
//                    zstd frame of count x columns x 8 bytes: per column (a record's f64
//                    fields in order), each value's bits minus the previous value's in that
//                    column (wrapping, zigzag), stored as 8 byte planes. Each chunk is
//                    self-contained (no state across chunks), so a torn tail loses only
//                    its last chunk. Version 3 files may hold type 1 and 4 chunks too.
//
// Little-endian. The writer appends whole chunks with write(2) at least every 0.25 s of
// recording time and fdatasync()s at least every second, so a crashed process loses at
// most the last second. A file without an end chunk was interrupted: the reader returns
// what is valid; recover_recording() cuts the torn tail and appends an end chunk marked
// "recovered". Qt-free (the GPU machine replays recordings too).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

struct ZSTD_CCtx_s;

namespace palpation::app::store {

/// Version 2 added the steps chunk (type 4); version 3 stores ticks and steps compressed
/// (types 5 and 6, about a sixth of the size). Versions 1 and 2 read unchanged.
inline constexpr std::uint32_t kRecordingVersion = 3;
inline constexpr int kRecordingMaxFingers = 5;

/// A bad recording: what() names the file, the chunk/offset and the reason.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One simulation step of a real-time session (the workstation's simulation thread):
/// what Backend::step was given and what it returned. World frame, SI.
struct RecordedStep {
  double t = 0;                        // s since the session started (wall clock, as the ticks)
  double h = 0;                        // s, the step's dt
  std::uint64_t commands_applied = 0;  // queued commands applied before this step
  struct Finger {
    bool active = false;
    double radius = 0;                 // m
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();  // input, m, m/s
    Eigen::Vector3d f = Eigen::Vector3d::Zero();  // output force on the finger, N
  };
  std::vector<Finger> fingers;         // `fingers` of the recording
};

class RecordingWriter {
 public:
  /// Creates (truncates) `path` and writes the header. `header` must hold "scenario"
  /// (scenario_to_json as an object); "format", "version", "fingers", "created" are added.
  /// Throws RecordingError when the file cannot be created or the header not written.
  /// `version`: the format written: 3, or an older one for tests and comparisons (2:
  /// uncompressed; 1: no steps either, add_step() does nothing).
  RecordingWriter(const std::string& path, nlohmann::json header, int fingers,
                  std::uint32_t version = kRecordingVersion);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// One haptic tick: fingertip positions and forces sent, world frame, `fingers` each.
  /// Never throws: after a write error (disk full) the writer stops and failed() is set;
  /// what was written before stays readable.
  void add_tick(double t, const Eigen::Vector3d* x, const Eigen::Vector3d* f);
  /// One simulation step (fingers() entries). Buffered, written with the ticks.
  void add_step(const RecordedStep& s);
  /// An event (instructor event, parameter change, trainee mark); written at once.
  void add_event(double t, const std::string& kind, nlohmann::json data = nlohmann::json::object());
  /// Writes buffered ticks as a chunk; fdatasync when the last sync is over 1 s old (or `sync`).
  void flush(bool sync = false);
  /// Flushes and writes the end chunk (`footer` plus counts). Idempotent.
  void close(nlohmann::json footer = nlohmann::json::object());

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t ticks() const { return ticks_; }
  std::uint64_t steps() const { return steps_; }
  int fingers() const { return fingers_; }
  std::uint32_t version() const { return version_; }
  const std::string& path() const { return path_; }

  /// Test hook: fail every write after `bytes` bytes in total (0: off), as a full disk would.
  void set_byte_limit_for_test(std::uint64_t bytes) { limit_ = bytes; }

 private:
  bool write_all(const void* data, std::size_t n);
  void write_chunk(std::uint32_t type, std::string_view payload);
  /// Writes a buffered type 1 / type 4 payload (u32 count, records), compressed in version 3.
  void write_records(std::uint32_t type, const std::string& payload, std::uint32_t count, std::uint32_t columns);
  std::string path_, error_;
  int fd_ = -1, fingers_ = 0;
  std::uint32_t version_ = kRecordingVersion;
  ZSTD_CCtx_s* zctx_ = nullptr;  // reused across chunks; every chunk is its own zstd frame
  std::string columns_, packed_;  // version 3 scratch: the columns, the chunk's payload
  std::uint32_t seq_ = 0;
  std::uint64_t bytes_ = 0, ticks_ = 0, limit_ = 0;
  std::string buf_;             // pending tick records
  std::uint32_t buffered_ = 0;  // ticks in buf_
  std::string step_buf_;        // pending step records
  std::uint32_t step_buffered_ = 0;
  std::uint64_t steps_ = 0;
  double buf_t0_ = 0, last_t_ = 0;
  std::int64_t last_sync_ns_ = 0;
  bool closed_ = false;
};

struct Recording {
  std::string path;
  std::uint32_t version = 0;
  nlohmann::json header, footer;     // footer: null when there is no end chunk
  int fingers = 0;
  std::vector<double> t;             // per tick
  std::vector<Eigen::Vector3d> x, f; // per tick x finger (index tick * fingers + finger)
  std::vector<nlohmann::json> events;
  std::vector<RecordedStep> steps;   // workstation sessions (version 2 and later); empty otherwise
  int chunks = 0;
  bool complete = false;             // ends with an end chunk
  bool recovered = false;            // the end chunk says it was recovered
  std::string interrupted;           // non-empty: why the tail was dropped (no end chunk)
  std::uint64_t valid_bytes = 0;     // offset after the last valid chunk
  std::uint64_t file_bytes = 0;
  std::size_t ticks() const { return t.size(); }
  double duration() const { return t.empty() ? 0.0 : t.back(); }
};

/// The force scale the recorded session sent to its device (header "session"."force_scale",
/// app/live/force_mapping.h): the ticks' forces are this times the simulated ones. 1 for
/// recordings made before the scale, and for a missing or unusable value.
double recorded_force_scale(const Recording& r);

/// Reads and validates a recording. A torn tail (no end chunk; the last chunk cut short or
/// failing its checksum at the end of the file) is not an error: `interrupted` says what
/// was dropped. Anything else (bad magic, newer version, header checksum, a bad chunk
/// followed by more data, bad values) throws RecordingError("FILE: chunk N at offset O: reason").
Recording read_recording(const std::string& path);

struct RecoverResult {
  bool was_complete = false;     // nothing to do
  std::size_t ticks = 0;
  double duration = 0;           // s kept
  std::uint64_t dropped_bytes = 0;
  std::string reason;            // what was cut
};
/// Makes an interrupted recording complete: cuts the torn tail, appends an end chunk
/// {"recovered": true, ...}. Throws RecordingError for a file that is not recoverable.
RecoverResult recover_recording(const std::string& path);

}  // namespace palpation::app::store
