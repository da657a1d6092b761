#include "cli/sweep_analysis.h"

#include <algorithm>
#include <cmath>

namespace palpation::app::cli {

using live::FingerSample;

SweepAnalysis analyze_sweep(const std::vector<FingerSample>& samples, int finger, double threshold) {
  SweepAnalysis out;
  std::vector<const FingerSample*> s;
  for (const auto& x : samples)
    if (x.finger == finger) s.push_back(&x);
  if (s.size() < 3) return out;
  double fmax = 0;
  for (auto* p : s) fmax = std::max(fmax, p->f.z());
  if (!(fmax > 0)) return out;
  // Pass index of each sample: the x direction, with reversals detected over a window
  // of 50 ms to ignore noise.
  std::vector<int> pass(s.size(), 0);
  int current = 0, dir = 0;
  std::size_t anchor = 0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const double dx = s[i]->x.x() - s[anchor]->x.x();
    if (s[i]->t - s[anchor]->t >= 0.05 && std::abs(dx) > 1e-6) {
      const int d = dx > 0 ? 1 : -1;
      if (dir != 0 && d != dir) ++current;
      dir = d;
      anchor = i;
    }
    pass[i] = current;
  }
  // Direction per pass.
  std::vector<int> pass_dir(current + 1, 0);
  {
    std::vector<double> first(current + 1, NAN), last(current + 1, NAN);
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (std::isnan(first[pass[i]])) first[pass[i]] = s[i]->x.x();
      last[pass[i]] = s[i]->x.x();
    }
    for (int p = 0; p <= current; ++p) pass_dir[p] = last[p] >= first[p] ? 1 : -1;
  }
  const double thr = threshold * fmax;
  bool in = false;
  PushPeak best{};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double fz = s[i]->f.z();
    if (fz > thr) {
      if (!in || fz > best.fz) best = {s[i]->t, s[i]->x.x(), fz, pass[i]};
      in = true;
    } else if (in) {
      out.pushes.push_back(best);
      in = false;
    }
  }
  if (in) out.pushes.push_back(best);
  for (int p = 0; p <= current; ++p) {
    PassPeak pp{p, NAN, -1, pass_dir[p]};
    for (const auto& q : out.pushes)
      if (q.pass == p && q.fz > pp.fz) {
        pp.fz = q.fz;
        pp.x = q.x;
      }
    if (pp.fz > 0) out.passes.push_back(pp);
  }
  return out;
}

std::vector<double> peaks_near(const SweepAnalysis& a, double x0) {
  std::vector<double> out;
  for (const auto& p : a.passes) {
    const PushPeak* best = nullptr;
    for (const auto& q : a.pushes)
      if (q.pass == p.pass && (!best || std::abs(q.x - x0) < std::abs(best->x - x0))) best = &q;
    if (best) out.push_back(best->fz);
  }
  return out;
}

nlohmann::json SweepAnalysis::to_json() const {
  nlohmann::json j;
  j["pushes"] = nlohmann::json::array();
  for (const auto& p : pushes) j["pushes"].push_back({{"t", p.t}, {"x", p.x}, {"fz", p.fz}, {"pass", p.pass}});
  j["passes"] = nlohmann::json::array();
  for (const auto& p : passes) j["passes"].push_back({{"pass", p.pass}, {"peak_x", p.x}, {"peak_fz", p.fz}, {"direction", p.direction}});
  return j;
}

}  // namespace palpation::app::cli
