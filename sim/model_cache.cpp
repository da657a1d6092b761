#include "model_cache.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace palpation::sim {

namespace {
constexpr char kMagic[8] = {'P', 'A', 'L', 'P', 'M', 'S', 'H', '\0'};

struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
};
}  // namespace

std::uint64_t key_hash(const std::string& key) {
  Fnv f;
  f.add(key.data(), key.size());
  return f.h;
}

void save_mesh_cache(const std::string& path, const TetMesh& mesh, const std::string& key) {
  std::string buf;
  auto put = [&buf](const void* d, std::size_t n) { buf.append(static_cast<const char*>(d), n); };
  const std::uint32_t version = kCacheVersion, reserved = 0;
  const std::uint64_t kh = key_hash(key), nn = mesh.nodes.size(), nt = mesh.tets.size();
  put(kMagic, 8);
  put(&version, 4);
  put(&reserved, 4);
  put(&kh, 8);
  put(&nn, 8);
  put(&nt, 8);
  for (const auto& p : mesh.nodes) put(p.data(), 3 * sizeof(double));
  put(mesh.tets.data(), nt * 4 * sizeof(int));
  std::vector<int> region = mesh.region;
  region.resize(nt, 0);
  put(region.data(), nt * sizeof(int));
  Fnv f;
  f.add(buf.data(), buf.size());
  put(&f.h, 8);

  std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string tmp = path + ".tmp" + std::to_string(std::rand());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(tmp + ": cannot be written");
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    out.flush();
    if (!out) {
      std::filesystem::remove(tmp);
      throw std::runtime_error(tmp + ": write failed (disk full?)");
    }
  }
  std::filesystem::rename(tmp, path);
}

bool load_mesh_cache(const std::string& path, const std::string& key, TetMesh& mesh, std::string* why,
                     bool check_key) {
  auto no = [why](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) return no("missing");
  std::string buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr std::size_t kHeader = 8 + 4 + 4 + 8 + 8 + 8;
  if (buf.size() < kHeader + 8) return no("corrupt: truncated header");
  if (std::memcmp(buf.data(), kMagic, 8) != 0) return no("corrupt: not a palpation mesh cache");
  std::uint32_t version;
  std::uint64_t kh, nn, nt;
  std::memcpy(&version, buf.data() + 8, 4);
  std::memcpy(&kh, buf.data() + 16, 8);
  std::memcpy(&nn, buf.data() + 24, 8);
  std::memcpy(&nt, buf.data() + 32, 8);
  if (version != kCacheVersion)
    return no("stale: format version " + std::to_string(version) + " != " + std::to_string(kCacheVersion));
  if (nn > (1u << 28) || nt > (1u << 28)) return no("corrupt: implausible sizes");
  const std::size_t body = nn * 3 * sizeof(double) + nt * 5 * sizeof(int);
  if (buf.size() != kHeader + body + 8) return no("corrupt: size does not match header");
  Fnv f;
  f.add(buf.data(), kHeader + body);
  std::uint64_t sum;
  std::memcpy(&sum, buf.data() + kHeader + body, 8);
  if (sum != f.h) return no("corrupt: checksum mismatch");
  if (check_key && kh != key_hash(key)) return no("stale: generated for other parameters");
  TetMesh m;
  m.nodes.resize(nn);
  m.tets.resize(nt);
  m.region.resize(nt);
  const char* p = buf.data() + kHeader;
  for (auto& v : m.nodes) {
    std::memcpy(v.data(), p, 3 * sizeof(double));
    p += 3 * sizeof(double);
  }
  if (nt > 0) {  // memcpy to an empty vector's null data() is undefined (UBSan)
    std::memcpy(m.tets.data(), p, nt * 4 * sizeof(int));
    p += nt * 4 * sizeof(int);
    std::memcpy(m.region.data(), p, nt * sizeof(int));
  }
  if (std::string v = m.validate(); !v.empty()) return no("corrupt: " + v);
  mesh = std::move(m);
  return true;
}

std::string cache_dir() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* e = std::getenv("PALPATION_CACHE_DIR"); e && *e)
    dir = e;
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    dir = fs::path(x) / "palpation";
  else if (const char* h = std::getenv("HOME"); h && *h)
    dir = fs::path(h) / ".cache" / "palpation";
  else
    dir = ".palpation-cache";
  std::error_code ec;
  fs::create_directories(dir, ec);
  return dir.string();
}

}  // namespace palpation::sim
