#include "review/frame_store.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <zstd.h>

namespace palpation::app::review {

namespace {

// zstd's level: 1 codes a paper frame's 101 kB of byte planes in about 0.2 ms, small
// against the step it follows, and within a few per cent of level 3's size on these
// planes (mostly zero bytes).
constexpr int kZstdLevel = 1;
// The allocator's overhead per allocation, for bytes().
constexpr std::size_t kAllocOverhead = 16;

std::uint32_t zigzag(std::int32_t v) { return (std::uint32_t(v) << 1) ^ std::uint32_t(v >> 31); }
std::int32_t unzigzag(std::uint32_t u) { return std::int32_t(u >> 1) ^ -std::int32_t(u & 1); }

// The values' byte planes: all lowest bytes, then all second bytes, ...: small values leave
// the upper planes zero, which zstd codes in a few bytes.
void to_planes(const std::vector<std::int32_t>& r, std::vector<std::uint8_t>& out) {
  const std::size_t n = r.size();
  out.resize(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t u = zigzag(r[i]);
    out[i] = std::uint8_t(u);
    out[n + i] = std::uint8_t(u >> 8);
    out[2 * n + i] = std::uint8_t(u >> 16);
    out[3 * n + i] = std::uint8_t(u >> 24);
  }
}

// A difference frame's prediction of a quantized value from the previous frame's: the
// same integer on both sides (the scale is kept as the float it was coded with).
std::int32_t predict(float scale, std::int32_t previous) { return std::int32_t(std::lround(double(scale) * double(previous))); }

std::int32_t from_planes(const std::uint8_t* p, std::size_t n, std::size_t i) {
  return unzigzag(std::uint32_t(p[i]) | std::uint32_t(p[n + i]) << 8 | std::uint32_t(p[2 * n + i]) << 16 |
                  std::uint32_t(p[3 * n + i]) << 24);
}

}  // namespace

struct FrameStore::Compressor {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  std::vector<std::int32_t> q, r;
  std::vector<std::uint8_t> planes, out;
  ~Compressor() { ZSTD_freeCCtx(cctx); }
  // `in` zstd-coded into a vector of its own size.
  std::vector<std::uint8_t> compress(const void* in, std::size_t n) {
    out.resize(ZSTD_compressBound(n));
    const std::size_t z = ZSTD_compressCCtx(cctx, out.data(), out.size(), in, n, kZstdLevel);
    if (ZSTD_isError(z)) throw std::runtime_error(std::string("review frame: zstd: ") + ZSTD_getErrorName(z));
    return std::vector<std::uint8_t>(out.begin(), out.begin() + std::ptrdiff_t(z));
  }
};

struct FrameStore::Decompressor {
  ZSTD_DCtx* dctx = ZSTD_createDCtx();
  std::vector<std::uint8_t> planes;
  ~Decompressor() { ZSTD_freeDCtx(dctx); }
  void decompress(const std::vector<std::uint8_t>& in, std::size_t n) {
    planes.resize(n);
    const std::size_t z = ZSTD_decompressDCtx(dctx, planes.data(), n, in.data(), in.size());
    if (ZSTD_isError(z) || z != n) throw std::runtime_error("review frame: zstd: corrupt frame");
  }
};

FrameStore::FrameStore() : enc_(std::make_unique<Compressor>()), dec_(std::make_unique<Decompressor>()) {}
FrameStore::~FrameStore() = default;

void FrameStore::add(double t, const std::shared_ptr<const PatientGeometry>& g, const std::vector<double>& xyz,
                     const Fingers& fingers) {
  Coded c;
  c.t = t;
  c.fingers = fingers;
  {
    std::lock_guard<std::mutex> lk(mu_);
    const bool new_segment = segments_.empty() || segments_.back() != g;
    if (new_segment) {
      segments_.push_back(g);
      enc_q_valid_ = false;  // a patient swap starts with a keyframe
    }
    c.segment = std::uint32_t(segments_.size() - 1);
  }
  const std::size_t n = xyz.size();
  // Quantized displacements from rest; a position off the grid's range (or the rest shape's
  // size) keeps the frame unquantized.
  bool quantized = g && g->rest.size() * 3 == n;
  std::vector<std::int32_t>& q = enc_->q;
  q.resize(n);
  for (std::size_t i = 0; quantized && i < n; ++i) {
    const double d = xyz[i] - g->rest[i / 3][int(i % 3)];
    if (!(std::abs(d) <= kMaxDisplacement)) quantized = false;
    else q[i] = std::int32_t(std::lround(d / kQuantum));
  }
  if (!quantized) {
    std::vector<float> f(xyz.begin(), xyz.end());
    c.kind = Kind::Raw;
    c.data = enc_->compress(f.data(), f.size() * sizeof(float));
    enc_q_valid_ = false;
  } else {
    const bool key = !enc_q_valid_ || enc_q_.size() != n || since_key_ + 1 >= kKeyInterval;
    std::vector<std::int32_t>& r = enc_->r;
    r.resize(n);
    if (key) {
      for (std::size_t i = 0; i < n; ++i) r[i] = q[i];
    } else {
      // The previous frame scaled by least squares: a press deeper or shallower moves the
      // body roughly in proportion (a quarter fewer bytes than the plain difference on the
      // paper sweep). |q| <= 2e8 and |scale| <= 2: the residual fits an int32.
      double qq = 0, qp = 0;
      for (std::size_t i = 0; i < n; ++i) {
        qq += double(enc_q_[i]) * double(enc_q_[i]);
        qp += double(enc_q_[i]) * double(q[i]);
      }
      c.scale = qq > 0 ? float(std::clamp(qp / qq, -2.0, 2.0)) : 1.0f;
      for (std::size_t i = 0; i < n; ++i) r[i] = q[i] - predict(c.scale, enc_q_[i]);
    }
    to_planes(r, enc_->planes);
    c.kind = key ? Kind::Key : Kind::Delta;
    c.data = enc_->compress(enc_->planes.data(), enc_->planes.size());
    since_key_ = key ? 0 : since_key_ + 1;
    enc_q_.swap(q);
    enc_q_valid_ = true;
  }
  const std::size_t b = sizeof(Coded) + c.data.capacity() + (c.data.empty() ? 0 : kAllocOverhead);
  std::lock_guard<std::mutex> lk(mu_);
  frames_.push_back(std::move(c));
  bytes_ += b;
}

std::size_t FrameStore::size() const {
  std::lock_guard<std::mutex> lk(mu_);
  return frames_.size();
}

std::vector<std::shared_ptr<const PatientGeometry>> FrameStore::patients() const {
  std::lock_guard<std::mutex> lk(mu_);
  return segments_;
}

std::size_t FrameStore::bytes() const {
  std::lock_guard<std::mutex> lk(mu_);
  return bytes_;
}

std::size_t FrameStore::cache_bytes() const {
  std::lock_guard<std::mutex> dl(dec_mu_);
  std::size_t b = dec_q_.capacity() * sizeof(std::int32_t) + dec_->planes.capacity();
  for (const auto& [i, f] : cache_)
    if (f) b += sizeof(ReviewFrame) + f->snapshot.positions.capacity() * sizeof(float);
  return b;
}

std::shared_ptr<const ReviewFrame> FrameStore::at_time(double t) const {
  std::size_t i = 0;
  {
    std::lock_guard<std::mutex> lk(mu_);
    if (frames_.empty()) return nullptr;
    auto it = std::upper_bound(frames_.begin(), frames_.end(), t, [](double v, const Coded& c) { return v < c.t; });
    i = it == frames_.begin() ? 0 : std::size_t(it - frames_.begin()) - 1;
  }
  return at(i);
}

std::shared_ptr<const ReviewFrame> FrameStore::at(std::size_t i) const {
  std::lock_guard<std::mutex> dl(dec_mu_);
  for (const auto& [ci, f] : cache_)
    if (f && ci == i) return f;
  auto f = decode(i);
  if (f) {
    cache_[cache_next_] = {i, f};
    cache_next_ = (cache_next_ + 1) % kCachedFrames;
  }
  return f;
}

std::shared_ptr<const ReviewFrame> FrameStore::decode(std::size_t i) const {
  // The coded frames from the nearest keyframe (or the frame dec_q_ holds) up to i, and
  // their patient. Appended frames never move (a deque), so they are read after unlocking.
  std::vector<const Coded*> chain;
  std::shared_ptr<const PatientGeometry> g;
  {
    std::lock_guard<std::mutex> lk(mu_);
    if (i >= frames_.size()) return nullptr;
    // Back to the keyframe (a first frame and a frame after a patient swap or an
    // unquantized frame are keyframes), or to the frame after the one dec_q_ holds.
    std::size_t k = i;
    while (frames_[k].kind == Kind::Delta && k > 0 && !(dec_index_ != SIZE_MAX && dec_index_ + 1 == k)) --k;
    for (std::size_t j = k; j <= i; ++j) chain.push_back(&frames_[j]);
    g = segments_[frames_[i].segment];
  }
  auto fr = std::make_shared<ReviewFrame>();
  const Coded& last = *chain.back();
  fr->t = last.t;
  fr->geometry = g;
  RenderSnapshot& rs = fr->snapshot;
  rs.model_generation = g ? g->generation : 0;
  rs.sequence = i + 1;
  rs.sim_time = last.t;
  for (std::size_t d = 0; d < last.fingers.position.size(); ++d) {
    rs.finger_position[d] = last.fingers.position[d];
    rs.finger_force[d] = last.fingers.force[d];
    rs.finger_active[d] = last.fingers.active[d];
  }
  rs.finger_radius = last.fingers.radius;
  if (last.kind == Kind::Raw) {
    // Kept unquantized: the floats as they were.
    const unsigned long long z = ZSTD_getFrameContentSize(last.data.data(), last.data.size());
    if (z == ZSTD_CONTENTSIZE_ERROR || z == ZSTD_CONTENTSIZE_UNKNOWN || z % sizeof(float) != 0)
      throw std::runtime_error("review frame: zstd: corrupt frame");
    dec_->decompress(last.data, std::size_t(z));
    rs.positions.resize(std::size_t(z) / sizeof(float));
    std::memcpy(rs.positions.data(), dec_->planes.data(), std::size_t(z));
    dec_index_ = SIZE_MAX;
    return fr;
  }
  const std::size_t n = g->rest.size() * 3;
  const std::size_t first = i + 1 - chain.size();
  // A chain that starts with a difference continues from dec_q_ (frame first - 1).
  if (chain.front()->kind == Kind::Delta && (dec_index_ + 1 != first || dec_q_.size() != n))
    throw std::logic_error("review frame: no keyframe");
  dec_index_ = SIZE_MAX;  // until the chain is decoded
  dec_q_.resize(n);
  for (const Coded* c : chain) {
    dec_->decompress(c->data, 4 * n);
    const std::uint8_t* p = dec_->planes.data();
    if (c->kind == Kind::Key)
      for (std::size_t j = 0; j < n; ++j) dec_q_[j] = from_planes(p, n, j);
    else
      for (std::size_t j = 0; j < n; ++j) dec_q_[j] = predict(c->scale, dec_q_[j]) + from_planes(p, n, j);
  }
  dec_index_ = i;
  rs.positions.resize(n);
  for (std::size_t j = 0; j < n; ++j) rs.positions[j] = float(g->rest[j / 3][int(j % 3)] + double(dec_q_[j]) * kQuantum);
  return fr;
}

}  // namespace palpation::app::review
