// The review's re-simulated frames, kept compactly (docs/recording.md, "Review memory").
//
// A frame as the 3-D view shows it is every node's position (8,445 nodes on the paper mesh:
// 101 kB as float), every 1/30 s of recording time: 180 MB a minute, 5.5 GB for a 30-minute
// review. The store keeps instead each node's displacement from the patient's rest shape,
// quantized to kQuantum (5 um; a screen pixel over the 20 cm breast is some 200 um, so the
// view cannot show the difference), as the residual from a prediction by the previous frame
// (that frame times one least-squares factor: a press deeper or shallower moves the body
// roughly in proportion), byte planes of the zigzag-coded residuals, zstd-coded. Every
// kKeyInterval-th frame, and the first after a patient swap, is a keyframe (the quantized
// displacements themselves), so that a frame is decoded from at most kKeyInterval coded
// frames. Decoding runs on demand (frame_at) and keeps the last decoded frames: playback
// decodes one residual per frame, a scrub at most kKeyInterval (about 1 ms on the paper mesh).
//
// Measured on the paper sweep at the paper mesh (a 2 cm press every 0.4 s: the whole body
// moves between two frames, a worst case) the frames take some 10 kB each: 0.6 GB for 30
// minutes (1 um steps: 22 kB, too much with the recording itself for 1 GB).
//
// Bound: each coordinate of a decoded frame is within kQuantum / 2 (2.5 um) of the
// re-simulated one, before both are rounded to float for the view; the quantized values are
// coded without loss, so the error does not grow along a chain of residuals. A frame with a
// position that is not finite or more than kMaxDisplacement from rest (a diverged body,
// before the guard resets it) is kept as float, zstd-coded, unquantized.
//
// The worker appends (add), the GUI thread reads (at, at_time); both are thread-safe. Qt-free.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "live/workstation.h"

namespace palpation::app::review {

using live::PatientGeometry;
using live::RenderSnapshot;

/// One re-simulated frame for the 3-D view (kept at most every `frame_period` s).
struct ReviewFrame {
  double t = 0;                                   // s, recording time
  std::shared_ptr<const PatientGeometry> geometry;
  RenderSnapshot snapshot;
};

class FrameStore {
 public:
  static constexpr double kQuantum = 5e-6;             // m, the displacements' step
  static constexpr double kMaxDisplacement = 1000.0;   // m, beyond: kept unquantized
  static constexpr std::size_t kKeyInterval = 30;      // frames from one keyframe to the next
  static constexpr std::size_t kCachedFrames = 2;      // decoded frames kept

  /// The fingertips of a frame (RenderSnapshot's finger fields).
  struct Fingers {
    std::array<Eigen::Vector3d, ::palpation::device::kMaxFingers> position{};
    std::array<Eigen::Vector3d, ::palpation::device::kMaxFingers> force{};
    std::array<bool, ::palpation::device::kMaxFingers> active{};
    double radius = 0.008;
  };

  FrameStore();
  ~FrameStore();
  FrameStore(const FrameStore&) = delete;
  FrameStore& operator=(const FrameStore&) = delete;

  /// Appends a frame at recording time `t` (not before the last one): `xyz` the nodes'
  /// positions (nnode x 3, m, as Backend::positions gives them) of the patient `g`.
  /// One writer at a time.
  void add(double t, const std::shared_ptr<const PatientGeometry>& g, const std::vector<double>& xyz,
           const Fingers& fingers);

  std::size_t size() const;
  /// The patients of the frames, in order (one more after each patient swap).
  std::vector<std::shared_ptr<const PatientGeometry>> patients() const;
  /// Frame i decoded (snapshot.sequence = i + 1), or null when there is none.
  std::shared_ptr<const ReviewFrame> at(std::size_t i) const;
  /// The newest frame at or before t (the first when t is before it), or null when empty.
  std::shared_ptr<const ReviewFrame> at_time(double t) const;

  /// Bytes the kept frames take: their records (time, fingertips) and coded positions,
  /// with the allocator's overhead per allocation estimated at 16 bytes. Grows with the
  /// frames; the patients' geometry (shared with the view) is not counted.
  std::size_t bytes() const;
  /// Bytes of the decoding state: the decoded frames kept and the decoder's buffers (a few
  /// frames' worth, independent of the recording's length; the writer's buffers, as many
  /// again while the worker runs, are not counted).
  std::size_t cache_bytes() const;

 private:
  enum class Kind : std::uint8_t { Key, Delta, Raw };
  struct Coded {
    double t = 0;
    std::uint32_t segment = 0;  // index into segments_
    Kind kind = Kind::Key;
    float scale = 1;            // Delta: the previous frame's factor in the prediction
    Fingers fingers;
    std::vector<std::uint8_t> data;
  };
  std::shared_ptr<const ReviewFrame> decode(std::size_t i) const;

  mutable std::mutex mu_;  // frames_, segments_, bytes_
  std::deque<Coded> frames_;  // elements never move once appended (the decoder reads them unlocked)
  std::vector<std::shared_ptr<const PatientGeometry>> segments_;
  std::size_t bytes_ = 0;

  // The writer's state (add only).
  struct Compressor;
  std::unique_ptr<Compressor> enc_;
  std::vector<std::int32_t> enc_q_;  // the last frame's quantized displacements
  bool enc_q_valid_ = false;
  std::size_t since_key_ = 0;

  // The reader's state, under dec_mu_ (taken before mu_ where both are held).
  mutable std::mutex dec_mu_;
  struct Decompressor;
  std::unique_ptr<Decompressor> dec_;
  mutable std::size_t dec_index_ = SIZE_MAX;     // frame whose quantized displacements dec_q_ holds
  mutable std::vector<std::int32_t> dec_q_;
  mutable std::array<std::pair<std::size_t, std::shared_ptr<const ReviewFrame>>, kCachedFrames> cache_{};
  mutable std::size_t cache_next_ = 0;
};

}  // namespace palpation::app::review
