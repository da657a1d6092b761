#include "store/recording.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <algorithm>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <memory>
#include <unistd.h>
#include <zstd.h>

#include "crc32.h"

namespace palpation::app::store {

using nlohmann::json;

namespace {

constexpr char kMagic[8] = {'P', 'A', 'L', 'R', 'E', 'C', '\r', '\n'};
constexpr std::uint32_t kChunkTag = 0x4B4E4843u;  // "CHNK"
constexpr std::uint32_t kTicks = 1, kEvent = 2, kEnd = 3, kSteps = 4, kTicksZ = 5, kStepsZ = 6;
constexpr std::uint32_t kMaxChunk = 64u << 20;
constexpr std::uint32_t kMaxHeader = 16u << 20;
constexpr std::uint32_t kTicksPerChunk = 250;  // 0.25 s at 1 kHz

void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(char((v >> (8 * i)) & 0xFF));
}
void put_f64(std::string& s, double d) {
  std::uint64_t v;
  std::memcpy(&v, &d, 8);
  for (int i = 0; i < 8; ++i) s.push_back(char((v >> (8 * i)) & 0xFF));
}
std::uint32_t get_u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
double get_f64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  double d;
  std::memcpy(&d, &v, 8);
  return d;
}
std::uint32_t crc(const std::string& s) { return device::crc32(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); }

// ---- the version-3 record coding (chunk types 5 and 6)
//
// A record chunk is a table of f64 columns (t, then each finger's x, f, ... as the version-2
// record lays them out). Measured on a 70 s default five-finger workstation session
// (31 MB/min uncompressed), zstd level 3 of: the records as written, 7.8 MB/min; columns with
// byte planes, 6.5; columns XOR the previous value, byte planes, 6.4; columns minus the
// previous value (the bits as a wrapping integer, zigzag), byte planes, 5.0 (0.3 ms for
// a ticks and steps chunk pair with its write(2), less than version 2's larger writes). Subtraction wins over XOR because a small change of a smoothly moving
// value that carries across a mantissa bit flips many bits under XOR while the integer
// difference stays small;
// zigzag keeps a small negative step's high bytes zero; the byte planes put the (mostly
// zero or repeated) sign, exponent and high mantissa bytes of a column together for zstd.
// A second difference (delta of delta) gained nothing. Written by hand because Debian
// has no library for floating-point column delta coding; zstd does the entropy coding.
constexpr std::uint32_t kCodingDeltaPlanesZstd = 1;
constexpr int kZstdLevel = 3;

std::uint64_t load_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// rows: `count` records of `columns` little-endian f64. out: count * columns * 8 bytes,
// column after column, each as 8 planes (byte 0 of every value, then byte 1, ...).
void encode_columns(const unsigned char* rows, std::uint32_t count, std::uint32_t columns, unsigned char* out) {
  const std::size_t stride = std::size_t(columns) * 8;
  for (std::uint32_t c = 0; c < columns; ++c) {
    unsigned char* plane = out + std::size_t(c) * 8 * count;
    std::uint64_t prev = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint64_t v = load_u64(rows + i * stride + std::size_t(c) * 8);
      const std::uint64_t d = v - prev;
      prev = v;
      const std::uint64_t z = (d << 1) ^ (0 - (d >> 63));  // zigzag: small +-d -> small
      for (int b = 0; b < 8; ++b) plane[std::size_t(b) * count + i] = static_cast<unsigned char>(z >> (8 * b));
    }
  }
}

void decode_columns(const unsigned char* in, std::uint32_t count, std::uint32_t columns, unsigned char* rows) {
  const std::size_t stride = std::size_t(columns) * 8;
  for (std::uint32_t c = 0; c < columns; ++c) {
    const unsigned char* plane = in + std::size_t(c) * 8 * count;
    std::uint64_t prev = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      std::uint64_t z = 0;
      for (int b = 7; b >= 0; --b) z = (z << 8) | plane[std::size_t(b) * count + i];
      const std::uint64_t d = (z >> 1) ^ (0 - (z & 1));
      prev += d;
      unsigned char* o = rows + i * stride + std::size_t(c) * 8;
      for (int b = 0; b < 8; ++b) o[b] = static_cast<unsigned char>(prev >> (8 * b));
    }
  }
}

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string utc_now() {
  std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

}  // namespace

// ---------------------------------------------------------------- writer

RecordingWriter::RecordingWriter(const std::string& path, json header, int fingers, std::uint32_t version)
    : path_(path), fingers_(fingers), version_(version) {
  if (fingers < 1 || fingers > kRecordingMaxFingers)
    throw RecordingError(path + ": fingers: must be 1 to 5, got " + std::to_string(fingers));
  if (version < 1 || version > kRecordingVersion)
    throw RecordingError(path + ": version: writes 1 to " + std::to_string(kRecordingVersion) + ", not " +
                         std::to_string(version));
  if (!header.is_object() || !header.contains("scenario"))
    throw RecordingError(path + ": header: needs the scenario");
  header["format"] = "palpation-recording";
  header["version"] = version_;
  header["fingers"] = fingers;
  if (!header.contains("created")) header["created"] = utc_now();
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RecordingError(path + ": cannot create the recording (" + std::strerror(errno) + ")");
  const std::string h = header.dump();
  std::string s(kMagic, 8);
  put_u32(s, version_);
  put_u32(s, std::uint32_t(h.size()));
  s += h;
  put_u32(s, crc(h));
  if (!write_all(s.data(), s.size())) throw RecordingError(path + ": cannot write the header (" + error_ + ")");
  ::fdatasync(fd_);
  last_sync_ns_ = now_ns();
  buf_.reserve(4 + kTicksPerChunk * std::size_t(8 + 48 * fingers));
}

RecordingWriter::~RecordingWriter() {
  if (!closed_) {
    // Destroyed without close(): an error path. Keep what is there (the next start recovers it).
    flush(true);
  }
  if (fd_ >= 0) ::close(fd_);
  ZSTD_freeCCtx(zctx_);
}

bool RecordingWriter::write_all(const void* data, std::size_t n) {
  if (!error_.empty() || fd_ < 0) return false;
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    std::size_t want = n;
    if (limit_ > 0) {
      if (bytes_ >= limit_) {
        error_ = path_ + ": write failed at offset " + std::to_string(bytes_) + " (" + std::strerror(ENOSPC) + ")";
        return false;
      }
      want = std::min<std::uint64_t>(want, limit_ - bytes_);
    }
    const ssize_t w = ::write(fd_, p, want);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      error_ = path_ + ": write failed at offset " + std::to_string(bytes_) + " (" +
               std::strerror(w < 0 ? errno : ENOSPC) + ")";
      return false;
    }
    p += w;
    n -= std::size_t(w);
    bytes_ += std::uint64_t(w);
  }
  return true;
}

void RecordingWriter::write_chunk(std::uint32_t type, std::string_view payload) {
  if (failed()) return;
  std::string body;
  body.reserve(12 + payload.size());
  put_u32(body, type);
  put_u32(body, seq_);
  put_u32(body, std::uint32_t(payload.size()));
  body += payload;
  std::string s;
  s.reserve(body.size() + 8);
  put_u32(s, kChunkTag);
  s += body;
  put_u32(s, crc(body));
  if (write_all(s.data(), s.size())) ++seq_;
}

void RecordingWriter::write_records(std::uint32_t type, const std::string& payload, std::uint32_t count,
                                    std::uint32_t columns) {
  if (version_ >= 3) {
    if (zctx_ == nullptr) zctx_ = ZSTD_createCCtx();
    const std::size_t n = std::size_t(count) * columns * 8;
    columns_.resize(n);
    encode_columns(reinterpret_cast<const unsigned char*>(payload.data()) + 4, count, columns,
                   reinterpret_cast<unsigned char*>(columns_.data()));
    packed_.resize(12 + ZSTD_compressBound(n));
    const std::size_t z = zctx_ == nullptr ? 0
                                           : ZSTD_compressCCtx(zctx_, packed_.data() + 12, packed_.size() - 12,
                                                               columns_.data(), n, kZstdLevel);
    if (zctx_ != nullptr && !ZSTD_isError(z)) {
      packed_.resize(12 + z);
      std::string head;
      put_u32(head, count);
      put_u32(head, columns);
      put_u32(head, kCodingDeltaPlanesZstd);
      packed_.replace(0, 12, head);
      write_chunk(type == kTicks ? kTicksZ : kStepsZ, packed_);
      return;
    }
    // zstd failed (out of memory): the records as they are, which version 3 reads too.
  }
  write_chunk(type, payload);
}

void RecordingWriter::add_tick(double t, const Eigen::Vector3d* x, const Eigen::Vector3d* f) {
  if (failed() || closed_) return;
  if (buffered_ == 0) {
    buf_.clear();
    put_u32(buf_, 0);  // count, patched at flush
    buf_t0_ = t;
  }
  put_f64(buf_, t);
  for (int k = 0; k < fingers_; ++k) {
    for (int i = 0; i < 3; ++i) put_f64(buf_, x[k][i]);
    for (int i = 0; i < 3; ++i) put_f64(buf_, f[k][i]);
  }
  ++buffered_;
  ++ticks_;
  last_t_ = t;
  if (buffered_ >= kTicksPerChunk || t - buf_t0_ >= 0.25) flush();
}

void RecordingWriter::add_step(const RecordedStep& st) {
  if (failed() || closed_ || version_ < 2) return;  // version 1 has no steps
  if (step_buffered_ == 0) {
    step_buf_.clear();
    put_u32(step_buf_, 0);  // count, patched at flush
  }
  put_f64(step_buf_, st.t);
  put_f64(step_buf_, st.h);
  put_f64(step_buf_, double(st.commands_applied));
  for (int k = 0; k < fingers_; ++k) {
    const RecordedStep::Finger fi = k < int(st.fingers.size()) ? st.fingers[std::size_t(k)] : RecordedStep::Finger{};
    put_f64(step_buf_, fi.active ? 1.0 : 0.0);
    put_f64(step_buf_, fi.radius);
    for (int i = 0; i < 3; ++i) put_f64(step_buf_, fi.x[i]);
    for (int i = 0; i < 3; ++i) put_f64(step_buf_, fi.v[i]);
    for (int i = 0; i < 3; ++i) put_f64(step_buf_, fi.f[i]);
  }
  ++step_buffered_;
  ++steps_;
}

void RecordingWriter::add_event(double t, const std::string& kind, json data) {
  if (failed() || closed_) return;
  flush();
  if (!data.is_object()) data = json{{"value", data}};
  data["t"] = t;
  data["kind"] = kind;
  write_chunk(kEvent, data.dump());
}

void RecordingWriter::flush(bool sync) {
  if (failed() || fd_ < 0) return;
  if (buffered_ > 0) {
    for (int i = 0; i < 4; ++i) buf_[std::size_t(i)] = char((buffered_ >> (8 * i)) & 0xFF);
    write_records(kTicks, buf_, buffered_, 1 + 6 * std::uint32_t(fingers_));
    buffered_ = 0;
  }
  if (step_buffered_ > 0) {
    for (int i = 0; i < 4; ++i) step_buf_[std::size_t(i)] = char((step_buffered_ >> (8 * i)) & 0xFF);
    write_records(kSteps, step_buf_, step_buffered_, 3 + 11 * std::uint32_t(fingers_));
    step_buffered_ = 0;
  }
  const std::int64_t now = now_ns();
  if (sync || now - last_sync_ns_ > 1000000000LL) {
    ::fdatasync(fd_);
    last_sync_ns_ = now;
  }
}

void RecordingWriter::close(json footer) {
  if (closed_) return;
  flush();
  if (!footer.is_object()) footer = json{{"value", footer}};
  footer["ticks"] = ticks_;
  if (steps_ > 0) footer["steps"] = steps_;
  footer["duration_s"] = last_t_;
  footer["closed"] = utc_now();
  write_chunk(kEnd, footer.dump());
  flush(true);
  closed_ = true;
}

// ---------------------------------------------------------------- reader

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordingError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

namespace {

// Tick and step records, as the version-2 chunks lay them out (rows of f64), into values:
// the records read_recording has checked (no checks here).
void parse_ticks(const unsigned char* rows, std::uint32_t count, int fingers, std::vector<double>& t,
                 std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& f) {
  const std::size_t rec_bytes = 8 + 48 * std::size_t(fingers);
  for (std::uint32_t i = 0; i < count; ++i) {
    const unsigned char* rp = rows + i * rec_bytes;
    t.push_back(get_f64(rp));
    for (int k = 0; k < fingers; ++k) {
      const unsigned char* fp = rp + 8 + 48 * k;
      x.emplace_back(get_f64(fp), get_f64(fp + 8), get_f64(fp + 16));
      f.emplace_back(get_f64(fp + 24), get_f64(fp + 32), get_f64(fp + 40));
    }
  }
}

void parse_steps(const unsigned char* rows, std::uint32_t count, int fingers, std::vector<RecordedStep>& out) {
  const std::size_t step_bytes = 24 + 88 * std::size_t(fingers);
  for (std::uint32_t i = 0; i < count; ++i) {
    const unsigned char* sp = rows + std::size_t(i) * step_bytes;
    RecordedStep st;
    st.t = get_f64(sp);
    st.h = get_f64(sp + 8);
    st.commands_applied = std::uint64_t(get_f64(sp + 16));
    st.fingers.resize(std::size_t(fingers));
    for (int k = 0; k < fingers; ++k) {
      const unsigned char* fp = sp + 24 + 88 * std::size_t(k);
      RecordedStep::Finger& fi = st.fingers[std::size_t(k)];
      fi.active = get_f64(fp) == 1.0;
      fi.radius = get_f64(fp + 8);
      for (int c = 0; c < 3; ++c) {
        fi.x[c] = get_f64(fp + 16 + 8 * c);
        fi.v[c] = get_f64(fp + 40 + 8 * c);
        fi.f[c] = get_f64(fp + 64 + 8 * c);
      }
    }
    out.push_back(std::move(st));
  }
}

std::uint32_t tick_columns(int fingers) { return 1 + 6 * std::uint32_t(fingers); }
std::uint32_t step_columns(int fingers) { return 3 + 11 * std::uint32_t(fingers); }

// One chunk's records (count x columns f64) back from their coding: `rows` resized.
void decode_chunk(const std::string& coded, std::uint32_t count, std::uint32_t columns, std::string& rows) {
  thread_local std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> dctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  thread_local std::string planes;
  const std::size_t raw = std::size_t(count) * columns * 8;
  planes.resize(raw);
  if (!dctx) throw RecordingError("out of memory for the decompressor");
  const std::size_t got = ZSTD_decompressDCtx(dctx.get(), planes.data(), raw, coded.data(), coded.size());
  if (ZSTD_isError(got) || got != raw) throw RecordingError("a kept chunk does not decode (memory corrupted)");
  rows.resize(raw);
  decode_columns(reinterpret_cast<const unsigned char*>(planes.data()), count, columns,
                 reinterpret_cast<unsigned char*>(rows.data()));
}

// Reads and checks the file into `r`; with `compact`, each ticks and steps chunk's records
// are kept coded there (the file's zstd frame as it is, or an uncompressed chunk coded
// as version 3 codes it) with their times, and not in `r`.
void read_into(const std::string& path, Recording& r, CompactRecording::Sink* compact);

}  // namespace

Recording read_recording(const std::string& path) {
  Recording r;
  read_into(path, r, nullptr);
  return r;
}

namespace {

void read_into(const std::string& path, Recording& r, CompactRecording::Sink* compact) {
  const std::string data = read_file(path);
  const auto* p = reinterpret_cast<const unsigned char*>(data.data());
  const std::uint64_t n = data.size();
  r.path = path;
  r.file_bytes = n;
  auto fail = [&](const std::string& where, const std::string& why) -> RecordingError {
    return RecordingError(path + ": " + where + ": " + why);
  };
  if (n == 0) throw fail("offset 0", "empty file");
  if (n < 8 || std::memcmp(p, kMagic, 8) != 0) throw fail("offset 0", "not a palpation recording (bad magic)");
  if (n < 16) throw fail("header at offset 8", "truncated");
  r.version = get_u32(p + 8);
  if (r.version == 0 || r.version > kRecordingVersion)
    throw fail("header at offset 8", "format version " + std::to_string(r.version) +
                                         " is not readable by this program (it reads version " +
                                         std::to_string(kRecordingVersion) + "; newer recordings need a newer program)");
  const std::uint32_t hl = get_u32(p + 12);
  if (hl > kMaxHeader || 16 + std::uint64_t(hl) + 4 > n) throw fail("header at offset 16", "truncated or bad length " + std::to_string(hl));
  const std::string h(data, 16, hl);
  if (get_u32(p + 16 + hl) != crc(h)) throw fail("header at offset 16", "checksum mismatch (corrupted)");
  try {
    r.header = json::parse(h);
  } catch (const std::exception& e) {
    throw fail("header at offset 16", std::string("bad JSON: ") + e.what());
  }
  if (!r.header.is_object() || r.header.value("format", "") != "palpation-recording" || !r.header.contains("scenario") ||
      !r.header["fingers"].is_number_integer())
    throw fail("header at offset 16", "missing format, fingers or scenario");
  r.fingers = r.header["fingers"].get<int>();
  if (r.fingers < 1 || r.fingers > kRecordingMaxFingers) throw fail("header at offset 16", "fingers must be 1 to 5");
  const std::size_t rec_bytes = 8 + 48 * std::size_t(r.fingers);

  std::uint64_t off = 16 + std::uint64_t(hl) + 4;
  r.valid_bytes = off;
  std::uint32_t seq = 0;
  double last_t = -1e300;
  // The last step's time and commands applied, for the checks of the next.
  bool any_step = false;
  double last_step_t = 0;
  std::uint64_t last_applied = 0;
  std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> dctx(nullptr, &ZSTD_freeDCtx);
  std::unique_ptr<ZSTD_CCtx, std::size_t (*)(ZSTD_CCtx*)> cctx(nullptr, &ZSTD_freeCCtx);
  std::string columns_buf;
  // With `compact`: the chunk's records coded (the file's frame, or coded here).
  auto keep_coded = [&](const std::string& where, bool ticks, const unsigned char* frame, std::size_t frame_len,
                        const unsigned char* rows, std::uint32_t count) {
    const std::uint32_t columns = ticks ? tick_columns(r.fingers) : step_columns(r.fingers);
    std::string coded;
    if (frame != nullptr) {
      coded.assign(reinterpret_cast<const char*>(frame), frame_len);
    } else {
      const std::size_t raw = std::size_t(count) * columns * 8;
      columns_buf.resize(raw);
      encode_columns(rows, count, columns, reinterpret_cast<unsigned char*>(columns_buf.data()));
      if (!cctx) cctx.reset(ZSTD_createCCtx());
      if (!cctx) throw fail(where, "out of memory for the compressor");
      coded.resize(ZSTD_compressBound(raw));
      const std::size_t z = ZSTD_compressCCtx(cctx.get(), coded.data(), coded.size(), columns_buf.data(), raw, kZstdLevel);
      if (ZSTD_isError(z)) throw fail(where, std::string("zstd: ") + ZSTD_getErrorName(z));
      coded.resize(z);
      coded.shrink_to_fit();
    }
    compact->add(ticks, count, std::move(coded));
  };
  while (off < n) {
    const std::string where = "chunk " + std::to_string(seq) + " at offset " + std::to_string(off);
    if (r.complete) throw fail(where, std::to_string(n - off) + " bytes after the end chunk");
    if (n - off < 16) {
      r.interrupted = where + ": truncated chunk header (" + std::to_string(n - off) + " of 16 bytes)";
      break;
    }
    if (get_u32(p + off) != kChunkTag) {
      throw fail(where, "bad chunk tag (corrupted)");
    }
    std::uint32_t type = get_u32(p + off + 4);
    const std::uint32_t cseq = get_u32(p + off + 8), len = get_u32(p + off + 12);
    if (len > kMaxChunk) throw fail(where, "chunk length " + std::to_string(len) + " too large (corrupted)");
    const std::uint64_t end = off + 16 + len + 4;
    if (end > n) {
      r.interrupted = where + ": truncated chunk (" + std::to_string(n - off) + " of " + std::to_string(end - off) + " bytes)";
      break;
    }
    const std::string body(data, off + 4, 12 + len);
    if (get_u32(p + off + 16 + len) != crc(body)) {
      if (end == n) {
        r.interrupted = where + ": checksum mismatch in the last chunk (torn write)";
        break;
      }
      throw fail(where, "checksum mismatch (corrupted)");
    }
    if (cseq != seq) throw fail(where, "sequence number " + std::to_string(cseq) + ", expected " + std::to_string(seq));
    const unsigned char* q = p + off + 16;
    std::uint64_t size = len;  // of the records' payload, decompressed
    std::string decoded;
    const unsigned char* frame = nullptr;  // a compressed chunk's zstd frame
    std::size_t frame_len = 0;
    if ((type == kTicksZ || type == kStepsZ) && r.version >= 3) {
      // The compressed records of a version-3 file: back to the type 1 / type 4 payload.
      const bool ticks = type == kTicksZ;
      const std::string what = std::string("compressed ") + (ticks ? "ticks" : "steps") + " chunk: ";
      const std::uint32_t want = ticks ? 1 + 6 * std::uint32_t(r.fingers) : 3 + 11 * std::uint32_t(r.fingers);
      if (len < 12) throw fail(where, what + "too short (" + std::to_string(len) + " bytes)");
      const std::uint32_t count = get_u32(q), columns = get_u32(q + 4), coding = get_u32(q + 8);
      if (coding != kCodingDeltaPlanesZstd) throw fail(where, what + "unknown coding " + std::to_string(coding));
      if (columns != want)
        throw fail(where, what + std::to_string(columns) + " columns, expected " + std::to_string(want) + " for " +
                              std::to_string(r.fingers) + " fingers");
      const std::uint64_t raw = std::uint64_t(count) * columns * 8;
      if (raw > kMaxChunk) throw fail(where, what + std::to_string(count) + " records too many (corrupted)");
      const std::string sizes = "decompressed size does not match " + std::to_string(count) + " records of " +
                                std::to_string(columns) + " columns (" + std::to_string(raw) + " bytes)";
      const unsigned long long content = ZSTD_getFrameContentSize(q + 12, len - 12);
      if (content == ZSTD_CONTENTSIZE_ERROR) throw fail(where, what + "not a zstd frame (corrupted)");
      if (content != ZSTD_CONTENTSIZE_UNKNOWN && content != raw)
        throw fail(where, what + sizes + ": the frame holds " + std::to_string(content));
      if (!dctx) dctx.reset(ZSTD_createDCtx());
      if (!dctx) throw fail(where, what + "out of memory for the decompressor");
      std::string planes(raw, '\0');
      const std::size_t got = ZSTD_decompressDCtx(dctx.get(), planes.data(), planes.size(), q + 12, len - 12);
      if (ZSTD_isError(got)) throw fail(where, what + "zstd: " + ZSTD_getErrorName(got) + " (corrupted)");
      if (got != raw) throw fail(where, what + sizes + ": got " + std::to_string(got));
      decoded.resize(4 + raw);
      for (int i = 0; i < 4; ++i) decoded[std::size_t(i)] = char((count >> (8 * i)) & 0xFF);
      decode_columns(reinterpret_cast<const unsigned char*>(planes.data()), count, columns,
                     reinterpret_cast<unsigned char*>(decoded.data()) + 4);
      frame = q + 12;
      frame_len = len - 12;
      q = reinterpret_cast<const unsigned char*>(decoded.data());
      size = decoded.size();
      type = ticks ? kTicks : kSteps;
    }
    if (type == kTicks) {
      if (size < 4) throw fail(where, "ticks chunk too short");
      const std::uint32_t count = get_u32(q);
      if (size != 4 + std::uint64_t(count) * rec_bytes)
        throw fail(where, "ticks chunk length " + std::to_string(size) + " does not match " + std::to_string(count) + " ticks");
      for (std::uint32_t i = 0; i < count; ++i) {
        const unsigned char* rp = q + 4 + i * rec_bytes;
        const double t = get_f64(rp);
        if (!std::isfinite(t) || t <= last_t)
          throw fail(where, "tick " + std::to_string(i) + ": time " + std::to_string(t) + " not finite or not increasing");
        last_t = t;
        r.t.push_back(t);
        for (int k = 0; k < r.fingers; ++k) {
          const unsigned char* fp = rp + 8 + 48 * k;
          Eigen::Vector3d x(get_f64(fp), get_f64(fp + 8), get_f64(fp + 16));
          Eigen::Vector3d f(get_f64(fp + 24), get_f64(fp + 32), get_f64(fp + 40));
          if (!x.allFinite()) throw fail(where, "tick " + std::to_string(i) + " finger " + std::to_string(k) + ": position not finite");
          r.x.push_back(x);
          r.f.push_back(f);
        }
      }
      if (compact != nullptr && count > 0) {
        keep_coded(where, true, frame, frame_len, q + 4, count);
        compact->tick_t.insert(compact->tick_t.end(), r.t.begin(), r.t.end());
        r.t.clear();
        r.x.clear();
        r.f.clear();
      }
    } else if (type == kSteps && r.version >= 2) {
      const std::size_t step_bytes = 24 + 88 * std::size_t(r.fingers);
      if (size < 4) throw fail(where, "steps chunk too short");
      const std::uint32_t count = get_u32(q);
      if (size != 4 + std::uint64_t(count) * step_bytes)
        throw fail(where, "steps chunk length " + std::to_string(size) + " does not match " + std::to_string(count) + " steps");
      for (std::uint32_t i = 0; i < count; ++i) {
        const unsigned char* sp = q + 4 + std::size_t(i) * step_bytes;
        RecordedStep st;
        st.t = get_f64(sp);
        st.h = get_f64(sp + 8);
        const double applied = get_f64(sp + 16);
        const std::string which = "step " + std::to_string(i);
        if (!std::isfinite(st.t) || (any_step && st.t < last_step_t))
          throw fail(where, which + ": time not finite or decreasing");
        if (!(st.h > 0 && st.h <= 1.0)) throw fail(where, which + ": dt " + std::to_string(st.h) + " s not in (0, 1]");
        if (!(applied >= 0 && applied <= 9.0e15) || applied != std::floor(applied) ||
            (any_step && std::uint64_t(applied) < last_applied))
          throw fail(where, which + ": commands applied not a non-decreasing count");
        st.commands_applied = std::uint64_t(applied);
        st.fingers.resize(std::size_t(r.fingers));
        for (int k = 0; k < r.fingers; ++k) {
          const unsigned char* fp = sp + 24 + 88 * std::size_t(k);
          RecordedStep::Finger& fi = st.fingers[std::size_t(k)];
          const double active = get_f64(fp);
          fi.radius = get_f64(fp + 8);
          for (int c = 0; c < 3; ++c) {
            fi.x[c] = get_f64(fp + 16 + 8 * c);
            fi.v[c] = get_f64(fp + 40 + 8 * c);
            fi.f[c] = get_f64(fp + 64 + 8 * c);
          }
          if (!(active == 0.0 || active == 1.0) || !(fi.radius > 0 && fi.radius < 1.0) || !fi.x.allFinite() ||
              !fi.v.allFinite() || !fi.f.allFinite())
            throw fail(where, which + " finger " + std::to_string(k) + ": bad value (flag, radius or not finite)");
          fi.active = active == 1.0;
        }
        any_step = true;
        last_step_t = st.t;
        last_applied = st.commands_applied;
        if (compact != nullptr) compact->step_t.push_back(st.t);
        else r.steps.push_back(std::move(st));
      }
      if (compact != nullptr && count > 0) keep_coded(where, false, frame, frame_len, q + 4, count);
    } else if (type == kEvent || type == kEnd) {
      json j;
      try {
        j = json::parse(std::string(reinterpret_cast<const char*>(q), len));
      } catch (const std::exception& e) {
        throw fail(where, std::string("bad JSON: ") + e.what());
      }
      if (type == kEvent) {
        r.events.push_back(std::move(j));
      } else {
        r.footer = std::move(j);
        r.complete = true;
        r.recovered = r.footer.is_object() && r.footer.value("recovered", false);
      }
    } else {
      throw fail(where, "unknown chunk type " + std::to_string(type));
    }
    ++seq;
    ++r.chunks;
    off = end;
    r.valid_bytes = off;
  }
  if (!r.complete && r.interrupted.empty()) r.interrupted = "no end chunk after chunk " + std::to_string(seq) + " (interrupted)";
}

}  // namespace

CompactRecording read_recording_compact(const std::string& path) {
  Recording r;
  CompactRecording c;
  CompactRecording::Sink sink{c, c.tick_t_, c.step_t_};
  read_into(path, r, &sink);
  static_cast<RecordingInfo&>(c) = std::move(static_cast<RecordingInfo&>(r));
  c.tick_t_.shrink_to_fit();
  c.step_t_.shrink_to_fit();
  c.tick_chunks_.shrink_to_fit();
  c.step_chunks_.shrink_to_fit();
  return c;
}

void CompactRecording::Sink::add(bool ticks, std::uint32_t count, std::string coded) {
  auto& v = ticks ? rec.tick_chunks_ : rec.step_chunks_;
  const std::size_t first = v.empty() ? 0 : v.back().first + v.back().count;
  v.push_back({first, count, std::move(coded)});
}

void CompactRecording::decode_ticks(std::size_t c, Ticks& out) const {
  const Chunk& k = tick_chunks_.at(c);
  thread_local std::string rows;
  decode_chunk(k.coded, k.count, tick_columns(fingers), rows);
  out.first = k.first;
  out.t.clear();
  out.x.clear();
  out.f.clear();
  parse_ticks(reinterpret_cast<const unsigned char*>(rows.data()), k.count, fingers, out.t, out.x, out.f);
}

void CompactRecording::decode_steps(std::size_t c, Steps& out) const {
  const Chunk& k = step_chunks_.at(c);
  thread_local std::string rows;
  decode_chunk(k.coded, k.count, step_columns(fingers), rows);
  out.first = k.first;
  out.steps.clear();
  parse_steps(reinterpret_cast<const unsigned char*>(rows.data()), k.count, fingers, out.steps);
}

namespace {
std::size_t chunk_of(const auto& chunks, std::size_t i) {
  // The last chunk whose first record is at or before i.
  auto it = std::upper_bound(chunks.begin(), chunks.end(), i, [](std::size_t v, const auto& c) { return v < c.first; });
  return it == chunks.begin() ? 0 : std::size_t(it - chunks.begin()) - 1;
}
}  // namespace

std::size_t CompactRecording::tick_chunk_of(std::size_t i) const { return chunk_of(tick_chunks_, i); }
std::size_t CompactRecording::step_chunk_of(std::size_t i) const { return chunk_of(step_chunks_, i); }

Recording CompactRecording::decode() const {
  Recording r;
  static_cast<RecordingInfo&>(r) = *this;
  r.t.reserve(ticks());
  r.x.reserve(ticks() * std::size_t(fingers));
  r.f.reserve(ticks() * std::size_t(fingers));
  for_each_tick([&](std::size_t, double t, const Eigen::Vector3d* x, const Eigen::Vector3d* f) {
    r.t.push_back(t);
    r.x.insert(r.x.end(), x, x + fingers);
    r.f.insert(r.f.end(), f, f + fingers);
  });
  r.steps.reserve(step_count());
  for_each_step([&](std::size_t, const RecordedStep& s) { r.steps.push_back(s); });
  return r;
}

std::size_t CompactRecording::bytes() const {
  std::size_t b = sizeof(*this) + (tick_t_.capacity() + step_t_.capacity()) * sizeof(double) +
                  (tick_chunks_.capacity() + step_chunks_.capacity()) * sizeof(Chunk);
  for (const auto* v : {&tick_chunks_, &step_chunks_})
    for (const Chunk& c : *v) b += c.coded.capacity() + 16;
  b += events.capacity() * sizeof(nlohmann::json) + header.dump().size();
  for (const auto& e : events) b += e.dump().size();
  return b;
}

RecoverResult recover_recording(const std::string& path) {
  Recording r = read_recording(path);
  RecoverResult res;
  res.ticks = r.ticks();
  res.duration = r.duration();
  if (r.complete) {
    res.was_complete = true;
    return res;
  }
  res.dropped_bytes = r.file_bytes - r.valid_bytes;
  res.reason = r.interrupted;
  if (::truncate(path.c_str(), off_t(r.valid_bytes)) != 0)
    throw RecordingError(path + ": cannot cut the torn tail (" + std::strerror(errno) + ")");
  json footer{{"recovered", true},
              {"reason", r.interrupted},
              {"dropped_bytes", res.dropped_bytes},
              {"ticks", r.ticks()},
              {"duration_s", r.duration()},
              {"closed", utc_now()}};
  const std::string js = footer.dump();
  std::string body;
  put_u32(body, kEnd);
  put_u32(body, std::uint32_t(r.chunks));
  put_u32(body, std::uint32_t(js.size()));
  body += js;
  std::string s;
  put_u32(s, kChunkTag);
  s += body;
  put_u32(s, crc(body));
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw RecordingError(path + ": cannot reopen to mark it recovered (" + std::strerror(errno) + ")");
  const bool ok = ::write(fd, s.data(), s.size()) == ssize_t(s.size());
  ::fdatasync(fd);
  ::close(fd);
  if (!ok) throw RecordingError(path + ": cannot write the recovery mark (" + std::strerror(errno) + ")");
  return res;
}

double recorded_force_scale(const RecordingInfo& r) {
  if (!r.header.is_object() || !r.header.contains("session") || !r.header["session"].is_object()) return 1.0;
  const nlohmann::json& s = r.header["session"];
  if (!s.contains("force_scale") || !s["force_scale"].is_number()) return 1.0;
  const double v = s["force_scale"].get<double>();
  return std::isfinite(v) && v > 0 ? v : 1.0;
}

}  // namespace palpation::app::store
