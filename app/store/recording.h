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

/// What a recording holds besides its ticks and steps: the header, events, end and how far
/// it is valid (read_recording, read_recording_compact).
struct RecordingInfo {
  std::string path;
  std::uint32_t version = 0;
  nlohmann::json header, footer;     // footer: null when there is no end chunk
  int fingers = 0;
  std::vector<nlohmann::json> events;
  int chunks = 0;
  bool complete = false;             // ends with an end chunk
  bool recovered = false;            // the end chunk says it was recovered
  std::string interrupted;           // non-empty: why the tail was dropped (no end chunk)
  std::uint64_t valid_bytes = 0;     // offset after the last valid chunk
  std::uint64_t file_bytes = 0;
};

struct Recording : RecordingInfo {
  std::vector<double> t;             // per tick
  std::vector<Eigen::Vector3d> x, f; // per tick x finger (index tick * fingers + finger)
  std::vector<RecordedStep> steps;   // workstation sessions (version 2 and later); empty otherwise
  std::size_t ticks() const { return t.size(); }
  std::size_t step_count() const { return steps.size(); }
  double duration() const { return t.empty() ? 0.0 : t.back(); }
  /// As CompactRecording's: f(tick, t, x, f) with `fingers` positions and forces.
  template <class F>
  void for_each_tick(F&& fn) const {
    for (std::size_t i = 0; i < t.size(); ++i)
      fn(i, t[i], &x[i * std::size_t(fingers)], &f[i * std::size_t(fingers)]);
  }
  /// f(step index, step).
  template <class F>
  void for_each_step(F&& fn) const {
    for (std::size_t i = 0; i < steps.size(); ++i) fn(i, steps[i]);
  }
};

/// A recording with its ticks and steps kept as they are coded in a version-3 file (each
/// chunk's records as one zstd frame of delta-coded byte-plane columns; the chunks of older
/// files are coded so when read), decoded a chunk (0.25 s) at a time when asked for. What a
/// review keeps: a five-finger workstation session's ticks as doubles take 248 bytes each
/// (446 MB for 30 minutes at 1 kHz) and its steps some 500 bytes each (180 to 800 MB),
/// coded about a sixth of that; only the times stay decoded (8 bytes a tick or step), for
/// lookups by time. Lossless: a decoded tick or step is bit for bit what read_recording
/// returns. Immutable after reading; the const members are safe from several threads.
class CompactRecording : public RecordingInfo {
 public:
  /// One chunk's ticks decoded: ticks first .. first + size - 1.
  struct Ticks {
    std::size_t first = 0;
    std::vector<double> t;
    std::vector<Eigen::Vector3d> x, f;  // tick x finger
  };
  struct Steps {
    std::size_t first = 0;
    std::vector<RecordedStep> steps;
  };

  std::size_t ticks() const { return tick_t_.size(); }
  std::size_t step_count() const { return step_t_.size(); }
  double duration() const { return tick_t_.empty() ? 0.0 : tick_t_.back(); }
  /// Recording time of every tick (step), in order.
  const std::vector<double>& tick_times() const { return tick_t_; }
  const std::vector<double>& step_times() const { return step_t_; }

  std::size_t tick_chunks() const { return tick_chunks_.size(); }
  std::size_t step_chunks() const { return step_chunks_.size(); }
  /// Decodes chunk c of the ticks (steps) into `out` (its buffers reused).
  void decode_ticks(std::size_t c, Ticks& out) const;
  void decode_steps(std::size_t c, Steps& out) const;
  /// The chunk that holds tick (step) i.
  std::size_t tick_chunk_of(std::size_t i) const;
  std::size_t step_chunk_of(std::size_t i) const;

  /// f(tick, t, x, f), every tick in order, x and f `fingers` each; a chunk decoded at a time.
  template <class F>
  void for_each_tick(F&& fn) const {
    Ticks b;
    for (std::size_t c = 0; c < tick_chunks(); ++c) {
      decode_ticks(c, b);
      for (std::size_t j = 0; j < b.t.size(); ++j)
        fn(b.first + j, b.t[j], &b.x[j * std::size_t(fingers)], &b.f[j * std::size_t(fingers)]);
    }
  }
  /// f(step index, step), every step in order.
  template <class F>
  void for_each_step(F&& fn) const {
    Steps b;
    for (std::size_t c = 0; c < step_chunks(); ++c) {
      decode_steps(c, b);
      for (std::size_t j = 0; j < b.steps.size(); ++j) fn(b.first + j, b.steps[j]);
    }
  }

  /// Everything decoded: what read_recording returns for the file.
  Recording decode() const;
  /// Bytes kept: the coded chunks, the times, the events' text, with an estimate of 16
  /// bytes of allocator overhead per allocation.
  std::size_t bytes() const;

  /// The reader's way in (read_recording_compact): appends a chunk's coded records.
  struct Sink {
    CompactRecording& rec;
    std::vector<double>& tick_t;
    std::vector<double>& step_t;
    void add(bool ticks, std::uint32_t count, std::string coded);
  };

 private:
  friend CompactRecording read_recording_compact(const std::string& path);
  struct Chunk {
    std::size_t first = 0;      // index of its first tick (step)
    std::uint32_t count = 0;    // records
    std::string coded;          // zstd frame of count x columns x 8 bytes (the version-3 coding)
  };
  std::vector<Chunk> tick_chunks_, step_chunks_;
  std::vector<double> tick_t_, step_t_;
};

/// The force scale the recorded session sent to its device (header "session"."force_scale",
/// app/live/force_mapping.h): the ticks' forces are this times the simulated ones. 1 for
/// recordings made before the scale, and for a missing or unusable value.
double recorded_force_scale(const RecordingInfo& r);

/// Reads and validates a recording. A torn tail (no end chunk; the last chunk cut short or
/// failing its checksum at the end of the file) is not an error: `interrupted` says what
/// was dropped. Anything else (bad magic, newer version, header checksum, a bad chunk
/// followed by more data, bad values) throws RecordingError("FILE: chunk N at offset O: reason").
Recording read_recording(const std::string& path);
/// As read_recording (the same checks and errors), the ticks and steps kept coded
/// (CompactRecording): for a long recording kept open, the review.
CompactRecording read_recording_compact(const std::string& path);

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
