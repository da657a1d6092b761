#include "cli/trace.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "backend.h"
#include "simulation.h"
#include "model_cache.h"

namespace palpation::app::cli {

std::vector<int> snapshot_steps(int steps) { return {steps / 4, steps / 2, 3 * steps / 4, steps}; }

Trace run_trace(const sim::Scenario& s, const sim::Model& model, const std::string& backend, int steps) {
  // The guarded step every session takes (Simulation::step: the divergence guard, the
  // error controller), on the backend named: "cpu" and "cuda" as the scenario would make
  // them, a library baseline (cuda-csr, cuda-bsr) put in after.
  sim::Scenario sb = s;
  const bool kind = backend == "cpu" || backend == "cuda";
  sb.backend = kind ? backend : "cpu";
  sim::Simulation sim(sb, model);
  if (!kind) sim.replace_backend(sim::make_named_backend(backend, sim.model(), s.params));
  const int nf = static_cast<int>(s.fingers.size());
  Trace tr;
  tr.force.reserve(std::size_t(steps) * std::size_t(nf) * 3);
  const auto snaps = snapshot_steps(steps);
  std::vector<double> x;
  for (int k = 1; k <= steps; ++k) {
    const auto a = std::chrono::steady_clock::now();
    const sim::StepStats st = sim.step();
    tr.step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
    tr.iterations.push_back(st.cg_iterations);
    tr.tolerance.push_back(sim.backend().params().solver.cg_tolerance);
    tr.contacts.push_back(st.contacts);
    tr.finite = tr.finite && st.finite;
    if (st.solved) {
      tr.worst_residual = std::max(tr.worst_residual, st.cg_residual);
      if (!(st.cg_residual <= sim.backend().params().solver.cg_tolerance)) ++tr.steps_above_tolerance;
    }
    for (int f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) tr.force.push_back(sim.outputs()[f].force[c]);
    if (std::find(snaps.begin(), snaps.end(), k) != snaps.end()) {
      sim.backend().positions(x);
      tr.snaps.push_back(x);
    }
  }
  tr.control = sim.error_control();
  tr.check_place = sim.check_place();
  tr.divergences = sim.divergences();
  tr.fallbacks = sim.fallbacks();
  tr.multigrid = sim.backend().multigrid_counts();
  tr.preconditioner = sim.backend().params().solver.preconditioner;
  tr.warm_start = sim.backend().params().solver.warm_start;
  return tr;
}

double rel_l2(const std::vector<double>& a, const std::vector<double>& ref) {
  if (a.size() != ref.size()) return INFINITY;
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += (a[i] - ref[i]) * (a[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

double displacement_error(const Trace& a, const Trace& ref, const sim::Model& m) {
  double dn = 0, dd = 0;
  for (std::size_t s = 0; s < ref.snaps.size() && s < a.snaps.size(); ++s)
    for (std::size_t j = 0; j < ref.snaps[s].size() && j < a.snaps[s].size(); ++j) {
      const double X = m.rest[j / 3][int(j % 3)];
      const double ua = a.snaps[s][j] - X, ur = ref.snaps[s][j] - X;
      dn += (ua - ur) * (ua - ur);
      dd += ur * ur;
    }
  return dd > 0 ? std::sqrt(dn / dd) : std::sqrt(dn);
}

namespace {
template <class V>
void put(std::ofstream& o, const V& v) {
  const std::uint64_t n = v.size();
  o.write(reinterpret_cast<const char*>(&n), 8);
  o.write(reinterpret_cast<const char*>(v.data()), std::streamsize(n * sizeof(v[0])));
}
template <class V>
bool get(std::ifstream& in, V& v) {
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), 8);
  if (!in || n > (1ull << 31)) return false;
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(v[0])));
  return bool(in);
}
std::uint64_t trace_sum(const Trace& t) {
  return sim::key_hash(std::string(reinterpret_cast<const char*>(t.force.data()), t.force.size() * 8));
}
}  // namespace

std::string trace_cache_key(const std::string& kind, const sim::Model& model, const sim::Scenario& s, int steps) {
  sim::TetMesh mesh;
  mesh.nodes = model.rest;
  mesh.tets = model.tets;
  std::vector<double> inputs;
  inputs.reserve(std::size_t(steps) * s.fingers.size() * 3);
  for (int k = 1; k <= steps; ++k)
    for (const auto& f : s.fingers) {
      Eigen::Vector3d x, v;
      f.sample(k * s.params.solver.dt, x, v);
      inputs.insert(inputs.end(), {x.x(), x.y(), x.z()});
    }
  std::ostringstream key;
  key << kind << '-' << std::hex << mesh.hash() << '-' << sim::key_hash(sim::scenario_to_json(s)) << '-'
      << sim::key_hash(std::string(reinterpret_cast<const char*>(inputs.data()), inputs.size() * sizeof(double)))
      << std::dec << '-' << steps;
  return key.str();
}

bool load_trace(const std::string& path, Trace& t) {
  std::ifstream in(path, std::ios::binary);
  char magic[8];
  in.read(magic, 8);
  if (!in || std::memcmp(magic, "PALPCPU1", 8) != 0) return false;
  std::uint64_t ns = 0, sum = 0;
  if (!get(in, t.force) || !get(in, t.iterations) || !get(in, t.contacts) || !get(in, t.step_ms)) return false;
  in.read(reinterpret_cast<char*>(&ns), 8);
  if (!in || ns > 16) return false;
  t.snaps.resize(ns);
  for (auto& s : t.snaps)
    if (!get(in, s)) return false;
  in.read(reinterpret_cast<char*>(&sum), 8);
  return in && sum == trace_sum(t);
}

void save_trace(const std::string& path, const Trace& t) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    o.write("PALPCPU1", 8);
    put(o, t.force);
    put(o, t.iterations);
    put(o, t.contacts);
    put(o, t.step_ms);
    const std::uint64_t ns = t.snaps.size();
    o.write(reinterpret_cast<const char*>(&ns), 8);
    for (const auto& s : t.snaps) put(o, s);
    const std::uint64_t sum = trace_sum(t);
    o.write(reinterpret_cast<const char*>(&sum), 8);
    if (!o) return;
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace palpation::app::cli
