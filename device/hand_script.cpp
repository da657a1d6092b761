#include "hand_script.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace palpation::device {

void HandScript::set_path(int finger, std::vector<PathKey> keys) {
  if (finger < 0 || finger >= kMaxFingers) throw std::invalid_argument("hand script: finger index out of range");
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (!std::isfinite(keys[i].t) || !finite(keys[i].p)) throw std::invalid_argument("hand script: non-finite key");
    if (i > 0 && !(keys[i].t > keys[i - 1].t)) throw std::invalid_argument("hand script: key times must increase");
  }
  paths_[finger] = std::move(keys);
}

int HandScript::driven_count() const {
  int n = 0;
  for (int f = 0; f < kMaxFingers; ++f) n += driven(f) ? 1 : 0;
  return n;
}

bool HandScript::sample(double t, int finger, Vec3& position, Vec3& velocity) const {
  if (!driven(finger)) return false;
  const auto& k = paths_[finger];
  velocity = {};
  if (k.size() == 1 || t <= k.front().t) {
    position = k.front().p;
    return true;
  }
  if (t >= k.back().t) {
    position = k.back().p;
    return true;
  }
  const auto it = std::upper_bound(k.begin(), k.end(), t, [](double v, const PathKey& key) { return v < key.t; });
  const PathKey& b = *it;
  const PathKey& a = *(it - 1);
  const double u = (t - a.t) / (b.t - a.t);
  position = a.p + (b.p - a.p) * u;
  velocity = (b.p - a.p) * (1.0 / (b.t - a.t));
  return true;
}

double HandScript::duration() const {
  double d = 0;
  for (const auto& p : paths_)
    if (!p.empty()) d = std::max(d, p.back().t);
  return d;
}

std::vector<std::vector<PathKey>> load_fingers_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::string line;
  int n = 0;
  auto fail = [&](const std::string& why) { throw std::runtime_error(path + ": line " + std::to_string(n) + ": " + why); };
  if (!std::getline(in, line)) {
    n = 1;
    fail("empty file (expected the header t,finger,x,y,z,fx,fy,fz)");
  }
  ++n;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.rfind("t,finger,x,y,z", 0) != 0) fail("header must start with t,finger,x,y,z");
  std::vector<std::vector<PathKey>> out;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line == "\r") continue;
    double v[5];
    const char* p = line.c_str();
    for (int i = 0; i < 5; ++i) {
      char* end = nullptr;
      v[i] = std::strtod(p, &end);
      if (end == p || !std::isfinite(v[i])) fail("field " + std::to_string(i + 1) + " is not a finite number");
      p = end;
      if (i < 4) {
        if (*p != ',') fail("expected a comma after field " + std::to_string(i + 1));
        ++p;
      }
    }
    const int finger = int(v[1]);
    if (double(finger) != v[1] || finger < 0 || finger >= kMaxFingers) fail("finger must be an integer in [0, 4]");
    if (out.size() <= std::size_t(finger)) out.resize(std::size_t(finger) + 1);
    auto& keys = out[std::size_t(finger)];
    if (!keys.empty() && !(v[0] > keys.back().t)) {
      if (v[0] == keys.back().t) continue;  // repeated sample: keep the first
      fail("time goes backwards for finger " + std::to_string(finger));
    }
    keys.push_back({v[0], {v[2], v[3], v[4]}});
  }
  if (out.empty()) fail("no samples");
  return out;
}

}  // namespace palpation::device
