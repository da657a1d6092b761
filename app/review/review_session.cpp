#include "review/review_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "review/replay.h"
#include "simulation.h"
#include "store/recorded_scenario.h"
#include "live/simulation_loop.h"

namespace palpation::app::review {

namespace dv = palpation::device;

using live::PatientGeometry;
using live::RenderSnapshot;
using live::apply_params;
using live::configure_realtime_threads;
using live::make_patient_geometry;
using store::RecordedStep;
using store::read_recording_compact;

using nlohmann::json;

namespace {

// The event a recorded entry holds as data: a trainee's mark (data in every version), or
// an instructor or parameter entry with its kind and arguments (live/event.h).
std::optional<live::Event> recorded_event(const json& e, double t) {
  const std::string kind = e.value("kind", "");
  if (kind == "mark") {
    std::optional<Eigen::Vector3d> at;
    const json& p = e.contains("position") ? e["position"] : json();
    if (p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() && p[2].is_number())
      at = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    const int n = e.contains("mark") && e["mark"].is_number_integer() ? e["mark"].get<int>() : 0;
    const std::string note = e.contains("note") && e["note"].is_string() ? e["note"].get<std::string>() : std::string();
    // Marks recorded before they carried a confidence: certain.
    const double confidence = e.contains("confidence") && e["confidence"].is_number() ? e["confidence"].get<double>() : 1.0;
    live::Event ev = live::Event::trainee_mark(n, at, note, confidence);
    ev.t = t;
    return ev;
  }
  if ((kind == "instructor" || kind == "parameter") && e.contains("event") && e["event"].is_string() && e.contains("args"))
    return live::event_from_json(e["event"].get<std::string>(), e["args"], t);
  return std::nullopt;
}

// The one-line text of an entry recorded without its arguments.
std::string one_line(const json& e) {
  const std::string kind = e.value("kind", "");
  if (e.contains("text") && e["text"].is_string() && !e["text"].get<std::string>().empty()) return e["text"].get<std::string>();
  if (e.contains("event") && e["event"].is_string()) return kind + ": " + e["event"].get<std::string>();
  if (e.contains("command") && e["command"].is_string()) return "change: " + e["command"].get<std::string>();
  return kind;
}

}  // namespace

ReviewSession::ReviewSession(const std::string& path) : rec_(read_recording_compact(path)) {
  // The workstation records an instructor's change twice: as data for the re-simulation
  // ("parameter") and as a line of its event log ("instructor", the same text within a
  // few ms); a trainee's mark likewise ("mark" with its position, and the log's "trainee
  // mark N"). The list and the timeline show each once: the data's entry.
  std::vector<std::pair<double, std::string>> data_twins;
  for (const json& e : rec_.events) {
    if (!e.is_object() || !e.contains("t") || !e["t"].is_number()) continue;
    const std::string kind = e.value("kind", "");
    if (kind == "parameter" && e.contains("text") && e["text"].is_string())
      data_twins.emplace_back(e["t"].get<double>(), e["text"].get<std::string>());
    else if (kind == "mark" && e.contains("mark") && e["mark"].is_number_integer())
      // The log's line of the mark: its number and confidence, without the position.
      data_twins.emplace_back(e["t"].get<double>(),
                              live::Event::trainee_mark(e["mark"].get<int>(), std::nullopt, {},
                                                        e.contains("confidence") && e["confidence"].is_number()
                                                            ? e["confidence"].get<double>()
                                                            : 1.0)
                                  .text());
  }
  auto is_log_twin = [&](double t, const json& e) {
    if (!e.contains("text") || !e["text"].is_string()) return false;
    const std::string& text = e["text"].get_ref<const std::string&>();
    for (const auto& [td, d] : data_twins)
      if (d == text && std::abs(td - t) < 0.1) return true;
    return false;
  };
  for (const json& e : rec_.events) {
    if (!e.is_object() || !e.contains("t") || !e["t"].is_number()) continue;
    if (e.value("kind", "") == "instructor" && is_log_twin(e["t"].get<double>(), e)) continue;
    ReviewMarker m;
    m.t = e["t"].get<double>();
    m.kind = e.value("kind", "");
    m.event = recorded_event(e, m.t);
    m.text = m.event ? m.event->text() : one_line(e);
    if (m.kind == "mark" && e.contains("position") && e["position"].is_array() && e["position"].size() == 3 &&
        e["position"][0].is_number()) {
      m.has_position = true;
      for (int i = 0; i < 3; ++i) m.position[i] = e["position"][std::size_t(i)].get<double>();
    }
    if (m.kind == "session") continue;  // start/end: the timeline's ends
    markers_.push_back(std::move(m));
  }
  // Parameter changes as data: applied by the re-simulation before the step that saw them.
  commands_ = recorded_commands(rec_);
  const std::size_t n = has_steps() ? rec_.step_count() : rec_.ticks();
  resim_f_.assign(n * std::size_t(rec_.fingers), Eigen::Vector3f::Zero());
  rec_.for_each_tick([&](std::size_t, double, const Eigen::Vector3d*, const Eigen::Vector3d* f) {
    for (int k = 0; k < rec_.fingers; ++k)
      if (f[k].allFinite()) max_recorded_force_ = std::max(max_recorded_force_, f[k].norm());
  });
}

ReviewSession::~ReviewSession() { cancel(); }

double ReviewSession::duration() const {
  double d = rec_.duration();
  if (has_steps()) d = std::max(d, rec_.step_times().back());
  return d;
}

std::size_t ReviewSession::total() const { return has_steps() ? rec_.step_count() : rec_.ticks(); }

std::string ReviewSession::error() const {
  std::lock_guard<std::mutex> lk(mu_);
  return error_;
}

std::string ReviewSession::backend() const {
  std::lock_guard<std::mutex> lk(mu_);
  return backend_;
}

ReviewSession::Compare ReviewSession::compare() const {
  std::lock_guard<std::mutex> lk(mu_);
  return compare_;
}

void ReviewSession::start(const std::string& backend) {
  if (worker_.joinable()) return;
  cancel_.store(false);
  worker_ = std::thread([this, backend] {
    score();  // before the re-simulation: the review's score and coverage are ready first
    try {
      if (has_steps()) run_steps(backend);
      else run_ticks(backend);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lk(mu_);
      error_ = e.what();
    }
    finished_.store(true, std::memory_order_release);
  });
}

const train::ScoredExam* ReviewSession::score() const {
  std::lock_guard<std::mutex> lk(score_mu_);
  if (!scored_) {
    scored_ = true;
    try {
      score_ = std::make_unique<const train::ScoredExam>(train::score_recording(rec_));
    } catch (const std::exception& e) {
      score_error_ = e.what();
    }
    score_ready_.store(true, std::memory_order_release);
  }
  return score_.get();
}

std::string ReviewSession::score_error() const {
  score();
  std::lock_guard<std::mutex> lk(score_mu_);
  return score_error_;
}

std::vector<unsigned char> ReviewSession::surface_levels(std::size_t surface_faces, double t) const {
  const train::ScoredExam* ex = score();
  if (!ex || !ex->skin) return {};
  const std::vector<unsigned char> at = t >= duration() ? ex->face_level : train::levels_at(ex->face_reached, t);
  std::vector<unsigned char> out(surface_faces, 0);
  for (std::size_t i = 0; i < at.size() && i < ex->skin->model_face.size(); ++i) {
    const int f = ex->skin->model_face[i];
    if (f >= 0 && std::size_t(f) < out.size()) out[std::size_t(f)] = at[i];
  }
  return out;
}

std::optional<std::array<double, train::kLevels>> ReviewSession::coverage_at(double t) const {
  const train::ScoredExam* ex = score();
  if (!ex || !ex->skin) return std::nullopt;
  if (t >= duration()) return ex->score.coverage;
  return train::coverage_at(*ex->skin, ex->face_reached, t);
}

void ReviewSession::cancel() {
  cancel_.store(true);
  if (worker_.joinable()) worker_.join();
}

void ReviewSession::keep_frame(double t, sim::Simulation& s, const std::shared_ptr<const PatientGeometry>& g,
                               const std::vector<sim::FingerInput>& in, const std::vector<Eigen::Vector3d>& f) {
  std::vector<double> xyz;
  s.backend().positions(xyz);
  FrameStore::Fingers fingers;
  for (std::size_t d = 0; d < in.size() && d < std::size_t(dv::kMaxFingers); ++d) {
    fingers.position[d] = in[d].position;
    fingers.force[d] = f[d];
    fingers.active[d] = in[d].active;
    fingers.radius = in[d].radius;
  }
  if (keep_raw_) {
    std::lock_guard<std::mutex> lk(mu_);
    raw_frames_.emplace_back(xyz.begin(), xyz.end());
  }
  frames_.add(t, g, xyz, fingers);
}

std::vector<float> ReviewSession::raw_frame_for_test(std::size_t i) const {
  std::lock_guard<std::mutex> lk(mu_);
  return i < raw_frames_.size() ? raw_frames_[i] : std::vector<float>();
}

ReviewSession::Memory ReviewSession::memory() const {
  Memory m;
  m.frames = frames_.bytes();
  m.frame_cache = frames_.cache_bytes();
  m.resimulation = resim_f_.capacity() * sizeof(Eigen::Vector3f);
  {
    std::lock_guard<std::mutex> lk(mu_);
    for (const auto& r : raw_frames_) m.frame_cache += r.capacity() * sizeof(float);
  }
  // The recording: its coded chunks, the times, the events as their JSON text.
  m.recording = rec_.bytes();
  for (const auto& g : frames_.patients()) {
    if (!g) continue;
    m.geometry += g->rest.capacity() * sizeof(Eigen::Vector3d) + g->tets.capacity() * sizeof(std::array<int, 4>) +
                  g->surface.capacity() * sizeof(std::array<int, 3>) + g->centroid.capacity() * sizeof(Eigen::Vector3d) +
                  g->young.capacity() * sizeof(double);
  }
  return m;
}

void ReviewSession::run_steps(const std::string& backend) {
  const std::string where = rec_.path + ": header.scenario";
  sim::Scenario s = store::parse_recorded_scenario(rec_.header["scenario"], where);
  if (!backend.empty()) s.backend = backend;
  auto build = [&](const sim::Scenario& sc) {
    auto sim = std::make_unique<sim::Simulation>(sc);
    sim->reset();
    configure_realtime_threads(*sim);
    return sim;
  };
  std::unique_ptr<sim::Simulation> simulation = build(s);
  std::uint64_t generation = 1;
  std::shared_ptr<const PatientGeometry> geometry = make_patient_geometry(*simulation, generation);
  {
    std::lock_guard<std::mutex> lk(mu_);
    backend_ = simulation->backend().name();
  }
  const int nf = rec_.fingers;
  std::vector<sim::FingerInput> in(static_cast<std::size_t>(nf));
  std::vector<sim::FingerOutput> out(static_cast<std::size_t>(nf));
  std::vector<Eigen::Vector3d> f(static_cast<std::size_t>(nf));
  std::size_t ci = 0;
  double last_frame = -1e300;
  Compare cmp;
  // The steps decoded a chunk (0.25 s) at a time: the recording stays coded in memory.
  const std::size_t nsteps = rec_.step_count();
  CompactRecording::Steps chunk;
  for (std::size_t i = 0; i < nsteps; ++i) {
    if (cancel_.load(std::memory_order_relaxed)) return;
    if (i == 0 || i >= chunk.first + chunk.steps.size()) rec_.decode_steps(rec_.step_chunk_of(i), chunk);
    const RecordedStep& st = chunk.steps[i - chunk.first];
    // The commands this step saw, applied as the workstation's simulation thread applies a
    // batch: in order on the current model, a patient swap after the batch.
    const json* swap = nullptr;
    while (ci < commands_.size() && commands_[ci].index < st.commands_applied) {
      const RecordedCommand& c = commands_[ci++];
      if (c.kind == "young") apply_recorded_young(*simulation, c);
      else if (c.kind == "params") apply_params(*simulation, store::parse_recorded_scenario(c.scenario, rec_.path + ": params change").params);
      else if (c.kind == "patient") swap = &c.scenario;
    }
    if (swap) {
      sim::Scenario s2 = store::parse_recorded_scenario(*swap, rec_.path + ": patient change");
      if (!backend.empty()) s2.backend = backend;
      simulation = build(s2);
      geometry = make_patient_geometry(*simulation, ++generation);
      last_frame = -1e300;
    }
    store::recorded_inputs(st, in);
    // The workstation's guarded step (sim::Simulation::advance): a backend error falls
    // back to the CPU from rest, the divergence guard resets the body.
    const bool ok = simulation->advance(in, out, st.h).ok;
    for (int k = 0; k < nf; ++k) {
      f[std::size_t(k)] = ok ? Eigen::Vector3d(out[std::size_t(k)].force) : Eigen::Vector3d::Zero();
      resim_f_[i * std::size_t(nf) + std::size_t(k)] = f[std::size_t(k)].cast<float>();
      const Eigen::Vector3d& fr = st.fingers[std::size_t(k)].f;
      cmp.max_force = std::max(cmp.max_force, fr.norm());
      const double d = (f[std::size_t(k)] - fr).norm();
      if (!(d <= cmp.max_diff)) {
        cmp.max_diff = std::isfinite(d) ? d : HUGE_VAL;
        cmp.at_t = st.t;
        cmp.finger = k;
      }
      ++cmp.compared;
    }
    if (st.t - last_frame >= frame_period || i + 1 == nsteps) {
      last_frame = st.t;
      keep_frame(st.t, *simulation, geometry, in, f);
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      compare_ = cmp;
    }
    done_.store(i + 1, std::memory_order_release);
    done_t_.store(st.t, std::memory_order_release);
  }
  // The forces sent at 1 kHz (the haptic loop: local contact model, coupling, safety filter)
  // against the step forces held until the next step: reported, not expected to vanish.
  const std::vector<double>& step_t = rec_.step_times();
  std::size_t j = 0;
  rec_.for_each_tick([&](std::size_t, double t, const Eigen::Vector3d*, const Eigen::Vector3d* fs) {
    while (j + 1 < step_t.size() && step_t[j + 1] <= t) ++j;
    if (step_t[j] > t) return;
    for (int k = 0; k < nf; ++k) {
      const double d = (fs[k] - resim_f_[j * std::size_t(nf) + std::size_t(k)].cast<double>()).norm();
      if (std::isfinite(d)) cmp.max_sent_diff = std::max(cmp.max_sent_diff, d);
    }
  });
  std::lock_guard<std::mutex> lk(mu_);
  compare_ = cmp;
}

void ReviewSession::run_ticks(const std::string& backend) {
  // As replay_recording (palpation replay): the recorded device input as finger paths, the
  // forces at each 1 kHz tick with the local contact model between simulation steps.
  // The finger paths are built from the ticks decoded whole (a recording without steps is
  // a short scripted one; the paths are as large as the ticks in any case).
  sim::Scenario s = replay_scenario(rec_.decode());
  if (!backend.empty()) s.backend = backend;
  sim::Simulation simulation(s);
  simulation.reset();
  std::shared_ptr<const PatientGeometry> geometry = make_patient_geometry(simulation, 1);
  {
    std::lock_guard<std::mutex> lk(mu_);
    backend_ = simulation.backend().name();
  }
  const int nf = rec_.fingers;
  std::vector<Eigen::Vector3d> step_pos(static_cast<std::size_t>(nf), Eigen::Vector3d::Zero()), f(static_cast<std::size_t>(nf));
  std::vector<sim::FingerInput> in(static_cast<std::size_t>(nf));
  double last_frame = -1e300;
  Compare cmp;
  const std::size_t nticks = rec_.ticks();
  CompactRecording::Ticks chunk;
  for (std::size_t i = 0; i < nticks; ++i) {
    if (cancel_.load(std::memory_order_relaxed)) return;
    if (i == 0 || i >= chunk.first + chunk.t.size()) rec_.decode_ticks(rec_.tick_chunk_of(i), chunk);
    const std::size_t ci = i - chunk.first;
    const double ti = chunk.t[ci];
    const double tk = double(i + 1) * 0.001;
    while (simulation.time() < tk - 1e-9) {
      simulation.step();
      for (int k = 0; k < nf; ++k) step_pos[std::size_t(k)] = simulation.fingers()[std::size_t(k)].position;
    }
    for (int k = 0; k < nf; ++k) {
      Eigen::Vector3d x, v;
      s.fingers[std::size_t(k)].sample(tk, x, v);
      const sim::FingerOutput& o = simulation.outputs()[std::size_t(k)];
      Eigen::Vector3d force = o.force;
      if (o.contacts > 0) force += o.stiffness * (x - step_pos[std::size_t(k)]);
      f[std::size_t(k)] = force;
      in[std::size_t(k)].position = x;
      in[std::size_t(k)].radius = s.fingers[std::size_t(k)].radius;
      in[std::size_t(k)].active = true;
      resim_f_[i * std::size_t(nf) + std::size_t(k)] = force.cast<float>();
      const Eigen::Vector3d& fr = chunk.f[ci * std::size_t(nf) + std::size_t(k)];
      if (!fr.allFinite()) continue;
      cmp.max_force = std::max(cmp.max_force, fr.norm());
      const double d = (force - fr).norm();
      if (!(d <= cmp.max_diff)) {
        cmp.max_diff = std::isfinite(d) ? d : HUGE_VAL;
        cmp.at_t = ti;
        cmp.finger = k;
      }
      ++cmp.compared;
    }
    if (ti - last_frame >= frame_period || i + 1 == nticks) {
      last_frame = ti;
      keep_frame(ti, simulation, geometry, in, f);
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      compare_ = cmp;
    }
    done_.store(i + 1, std::memory_order_release);
    done_t_.store(ti, std::memory_order_release);
  }
}

std::shared_ptr<const ReviewFrame> ReviewSession::frame_at(double t) const { return frames_.at_time(t); }

bool ReviewSession::resim_force_at(double t, int k, Eigen::Vector3d& f) const {
  const std::size_t n = done();
  if (n == 0 || k < 0 || k >= rec_.fingers) return false;
  // The first step (tick) after t among the n done.
  std::size_t lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (t < resim_t(mid)) hi = mid;
    else lo = mid + 1;
  }
  if (lo == 0) return false;
  const std::size_t i = lo - 1;
  f = resim_f_[i * std::size_t(rec_.fingers) + std::size_t(k)].cast<double>();
  return true;
}

std::size_t ReviewSession::tick_index(double t) const {
  const std::vector<double>& ts = rec_.tick_times();
  if (ts.empty()) return 0;
  auto it = std::upper_bound(ts.begin(), ts.end(), t);
  return it == ts.begin() ? 0 : std::size_t(it - ts.begin()) - 1;
}

std::vector<std::pair<double, double>> ReviewSession::recorded_series(int k, double step) const {
  std::vector<std::pair<double, double>> v;
  if (k < 0 || k >= rec_.fingers) return v;
  double last = -1e300;
  const std::size_t n = rec_.ticks();
  rec_.for_each_tick([&](std::size_t i, double t, const Eigen::Vector3d*, const Eigen::Vector3d* f) {
    if (t - last < step && i + 1 != n) return;
    last = t;
    v.emplace_back(t, f[k].norm());
  });
  return v;
}

std::vector<std::pair<double, double>> ReviewSession::resim_series(int k, double step) const {
  std::vector<std::pair<double, double>> v;
  if (k < 0 || k >= rec_.fingers) return v;
  const std::size_t n = done();
  double last = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    if (resim_t(i) - last < step && i + 1 != n) continue;
    last = resim_t(i);
    v.emplace_back(resim_t(i), double(resim_f_[i * std::size_t(rec_.fingers) + std::size_t(k)].norm()));
  }
  return v;
}

void ReviewSession::export_csv(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "t,finger,x,y,z,fx,fy,fz,fx_resim,fy_resim,fz_resim\n";
  out.precision(9);
  rec_.for_each_tick([&](std::size_t, double t, const Eigen::Vector3d* xs, const Eigen::Vector3d* fs) {
    for (int k = 0; k < rec_.fingers; ++k) {
      const Eigen::Vector3d& x = xs[k];
      const Eigen::Vector3d& f = fs[k];
      out << t << ',' << k << ',' << x.x() << ',' << x.y() << ',' << x.z() << ',' << f.x() << ',' << f.y() << ',' << f.z();
      Eigen::Vector3d fr;
      if (resim_force_at(t, k, fr)) out << ',' << fr.x() << ',' << fr.y() << ',' << fr.z() << '\n';
      else out << ",,,\n";
    }
  });
  if (!out) throw std::runtime_error(path + ": write failed");
}

void ReviewSession::seek(double t) { time_ = std::clamp(t, 0.0, duration()); }

void ReviewSession::set_playing(bool on) {
  if (on && time_ >= duration()) time_ = 0;  // play again from the start
  playing_ = on;
}

void ReviewSession::set_speed(double s) { speed_ = std::clamp(s, 0.25, 4.0); }

void ReviewSession::advance(double wall_dt) {
  if (!playing_) return;
  time_ += wall_dt * speed_;
  if (time_ >= duration()) {
    time_ = duration();
    playing_ = false;
  }
}

}  // namespace palpation::app::review
