// Review of a recorded session for students (docs/recording.md): the recording,
// its re-simulation on a worker thread and the playback clock. The widgets (ui/review_window)
// only display what this holds. Qt-free.
//
// Re-simulation: a workstation recording (version 2) holds the simulation thread's steps
// (dt, fingertip inputs, forces out) and the parameter changes as data with the number of
// commands applied before each step; the worker builds the recorded patient, applies each
// change before the step that saw it, steps with the recorded dt and inputs, and compares
// the forces out with the recorded ones. Same backend, settings and thread count: the
// same floating-point operations, so the difference is zero up to rounding. A recording
// without steps (version 1, `palpation session`) is re-simulated from its 1 kHz device
// input at the scenario's dt (replay_scenario), and the difference is reported.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "review/frame_store.h"
#include "review/replay.h"
#include "store/recording.h"
#include "live/workstation.h"
#include "train/score_recording.h"

namespace palpation::app::review {

using live::PatientGeometry;
using live::RenderSnapshot;
using store::CompactRecording;
using store::Recording;

/// What the timeline shows besides the forces.
struct ReviewMarker {
  double t = 0;
  std::string kind;   // "instructor", "parameter", "mark", "session"
  std::string text;   // one line, English (as recorded, for events recorded without arguments)
  /// The event as data (kind and arguments): marks, and the events of recordings that
  /// keep their arguments; nothing for older ones (shown as `text`).
  std::optional<live::Event> event;
  bool has_position = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // marks: where, world m
};

class ReviewSession {
 public:
  /// Reads the recording (throws RecordingError naming file, chunk, offset, reason;
  /// nothing is written, an interrupted file is read as far as it is valid).
  explicit ReviewSession(const std::string& path);
  ~ReviewSession();
  ReviewSession(const ReviewSession&) = delete;
  ReviewSession& operator=(const ReviewSession&) = delete;

  /// The recording, its ticks and steps kept coded (store::CompactRecording, decoded a
  /// chunk at a time): what a 30-minute review keeps of it fits beside the frames in 1 GB.
  const CompactRecording& recording() const { return rec_; }
  double duration() const;
  const std::vector<ReviewMarker>& markers() const { return markers_; }
  /// Exact mode: the recording holds the simulation's steps.
  bool has_steps() const { return rec_.step_count() > 0; }
  /// The largest recorded force sent (N, finite ones), for the plot's scale.
  double max_recorded_force() const { return max_recorded_force_; }
  /// Device fingers of the recording: 5 (workstation) or the scenario's.
  int fingers() const { return rec_.fingers; }

  // Re-simulation (worker thread) -------------------------------------------------------
  /// Starts the worker (idempotent). `backend` non-empty overrides the recorded one.
  void start(const std::string& backend = {});
  void cancel();
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  /// Empty, or why the re-simulation stopped.
  std::string error() const;
  /// Recording time up to which the re-simulation has run.
  double resimulated_until() const { return done_t_.load(std::memory_order_acquire); }
  /// Steps (or 1 kHz ticks for a recording without steps) done and in all.
  std::size_t done() const { return done_.load(std::memory_order_acquire); }
  std::size_t total() const;
  std::string backend() const;

  /// Recorded vs re-simulated force per step and finger (exact mode) or per tick.
  struct Compare {
    double max_diff = 0;          // N, largest |f_resim - f_recorded|
    double at_t = 0;              // s
    int finger = 0;
    double max_force = 0;         // N, largest recorded, for scale
    std::size_t compared = 0;
    double max_sent_diff = 0;     // N, exact mode: the forces sent (1 kHz, haptic loop) vs the re-simulated step forces
  };
  Compare compare() const;

  /// The frame to show at time t (the newest at or before t that is computed), or null.
  /// Decoded from the compact store (review/frame_store.h: positions within 2.5 um of the
  /// re-simulated ones); the same frame asked again is the same object while it is among
  /// the last decoded.
  std::shared_ptr<const ReviewFrame> frame_at(double t) const;
  /// Frames kept so far, and frame i of them (decoded as frame_at does), or null.
  std::size_t frame_count() const { return frames_.size(); }
  std::shared_ptr<const ReviewFrame> frame(std::size_t i) const { return frames_.at(i); }

  /// What the review keeps in memory, in bytes (estimates from the containers' sizes).
  struct Memory {
    std::size_t frames = 0;        // the kept frames, coded (FrameStore::bytes)
    std::size_t frame_cache = 0;   // decoding state: a few decoded frames (FrameStore::cache_bytes)
    std::size_t resimulation = 0;  // the re-simulated forces per step (tick)
    std::size_t recording = 0;     // the recording as kept: ticks and steps coded, their times, events
    std::size_t geometry = 0;      // the patients' rest shapes, meshes and skin maps
    std::size_t total() const { return frames + frame_cache + resimulation + recording + geometry; }
  };
  Memory memory() const;
  /// Bytes the kept frames take (Memory::frames): divided by frame_count(), the bytes per frame.
  std::size_t frame_memory_bytes() const { return frames_.bytes(); }
  /// Test hook: also keep each frame's positions as re-simulated (float, uncoded), to
  /// compare decoded frames with. Before start().
  void keep_raw_frames_for_test(bool on) { keep_raw_ = on; }
  /// Frame i's positions as re-simulated (with keep_raw_frames_for_test), else empty.
  std::vector<float> raw_frame_for_test(std::size_t i) const;
  /// Re-simulated force of finger k at the step (tick) at or before t; false when not yet computed.
  bool resim_force_at(double t, int k, Eigen::Vector3d& f) const;
  /// Recorded force sent and fingertip position at the tick at or before t.
  std::size_t tick_index(double t) const;

  /// Time series for plots: recorded forces sent (1 kHz, decimated to `step` s) and the
  /// re-simulated ones (computed part). (t, |f|) pairs.
  std::vector<std::pair<double, double>> recorded_series(int finger, double step) const;
  std::vector<std::pair<double, double>> resim_series(int finger, double step) const;

  /// CSV of the whole session: t,finger,x,y,z,fx,fy,fz (recorded, 1 kHz) and the
  /// re-simulated force (fx_resim..; empty where not computed). Throws std::runtime_error.
  void export_csv(const std::string& path) const;

  // The exam's score (docs/training.md, "Scoring an exam") ------------------------------
  /// The recording scored as `palpation score` scores it (train::score_recording: the patient
  /// rebuilt from the recording's scenario, the fingertips from its steps or ticks, the marks
  /// from its mark events). Computed once: by the worker before it re-simulates, or by the
  /// first call. Null when the scorer refuses the recording (cut short, no scenario, marks
  /// outside the body); score_error() then says why.
  const train::ScoredExam* score() const;
  std::string score_error() const;
  /// Whether score() has been computed (it then returns at once): the GUI asks before it asks
  /// for the score, so that it never waits on the worker's scoring.
  bool score_ready() const { return score_ready_.load(std::memory_order_acquire); }
  /// The highest pressure level reached up to recording time `t` on each face of the
  /// patient's surface, in PatientGeometry::surface's order (`surface_faces` faces; the chest
  /// wall's and any face off the skin 0), from score(): the coverage overlay at the playback
  /// time. A threshold per face on the times the score keeps (ScoredExam::face_reached),
  /// nothing scored again; from the exam's end on (and without `t`) the whole exam's levels.
  /// Empty when there is no score.
  std::vector<unsigned char> surface_levels(std::size_t surface_faces, double t = train::kNever) const;
  /// The skin fractions reached at least at each level (light, medium, deep) up to time `t`;
  /// nothing when there is no score.
  std::optional<std::array<double, train::kLevels>> coverage_at(double t) const;

  // Playback clock (the GUI advances it) ---------------------------------------------------
  double time() const { return time_; }
  void seek(double t);
  bool playing() const { return playing_; }
  void set_playing(bool on);
  double speed() const { return speed_; }
  /// 0.25 to 4.
  void set_speed(double s);
  /// Advances by `wall_dt` seconds of wall time x speed; stops at the end.
  void advance(double wall_dt);

  double frame_period = 1.0 / 30.0;  // s between kept frames

 private:
  void run_steps(const std::string& backend);
  void run_ticks(const std::string& backend);
  void keep_frame(double t, sim::Simulation& s, const std::shared_ptr<const PatientGeometry>& g,
                  const std::vector<sim::FingerInput>& in, const std::vector<Eigen::Vector3d>& f);

  CompactRecording rec_;
  double max_recorded_force_ = 0;
  // The score: computed once under score_mu_, never changed after (score() hands out a pointer).
  mutable std::mutex score_mu_;
  mutable bool scored_ = false;
  mutable std::unique_ptr<const train::ScoredExam> score_;
  mutable std::string score_error_;
  mutable std::atomic<bool> score_ready_{false};
  std::vector<ReviewMarker> markers_;
  std::vector<RecordedCommand> commands_;  // the recording's, in queue order (replay.h)
  // Per step (or tick) x fingers; times: the recording's. Float: 12 bytes a finger step
  // instead of 24 (a GPU session's 900 steps a second: 97 MB for 30 minutes, not 194),
  // and 7 significant digits are more than the plot and the CSV's 1e-9 N noise need; the
  // comparison with the recorded forces is made in double before it is stored.
  std::vector<Eigen::Vector3f> resim_f_;
  /// Recording time of step (tick) i.
  double resim_t(std::size_t i) const { return has_steps() ? rec_.step_times()[i] : rec_.tick_times()[i]; }
  // The kept frames, coded (thread-safe: the worker appends, frame_at decodes).
  FrameStore frames_;
  bool keep_raw_ = false;
  std::vector<std::vector<float>> raw_frames_;  // keep_raw_frames_for_test, under mu_
  mutable std::mutex mu_;                  // error_, backend_, compare_, raw_frames_
  std::string error_, backend_;
  Compare compare_;
  std::thread worker_;
  std::atomic<bool> cancel_{false}, finished_{false};
  std::atomic<std::size_t> done_{0};
  std::atomic<double> done_t_{0};
  double time_ = 0, speed_ = 1;
  bool playing_ = false;
};

}  // namespace palpation::app::review
