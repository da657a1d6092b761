#include "train/score_recording.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "phantom.h"
#include "scenario.h"
#include "simulation.h"
#include "store/recorded_scenario.h"

namespace palpation::app::train {

using nlohmann::json;

namespace {

std::string fmt_m(const Eigen::Vector3d& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.3f, %.3f, %.3f) m", p.x(), p.y(), p.z());
  return b;
}

// The fingertip samples are thinned to one per finger every 4 ms: a pad moves well under
// a millimetre in that time at palpation speeds (a few cm/s), below the skin mesh's
// resolution, and a 5-minute recording scores in a fraction of a second.
constexpr double kSamplePeriod = 0.004;
constexpr double kPlotPeriod = 0.02;

}  // namespace

PressureThresholds recorded_thresholds(const store::RecordingInfo& rec) {
  const nlohmann::json* found = nullptr;
  if (rec.header.is_object() && rec.header.contains("settings") && rec.header["settings"].is_object() &&
      rec.header["settings"].contains("thresholds"))
    found = &rec.header["settings"]["thresholds"];
  for (const auto& e : rec.events)
    if (e.is_object() && e.value("kind", std::string()) == "thresholds") found = &e;
  if (!found) return {};
  nlohmann::json j = *found;
  if (j.is_object()) {
    j.erase("t");
    j.erase("kind");
  }
  try {
    return thresholds_from_json(j);
  } catch (const std::exception& e) {
    throw std::invalid_argument(rec.path + ": recorded pressure thresholds: " + e.what());
  }
}

namespace {

// Either kind of recording (store::Recording, store::CompactRecording): the same pass.
template <class Rec>
ScoredExam score_any(const Rec& rec, const PressureThresholds& thresholds) {
  if (!rec.complete)
    throw ScoreError(rec.path + ": the recording was cut short (" +
                     (rec.interrupted.empty() ? std::string("no end chunk") : rec.interrupted) +
                     "): recover it first (palpation replay " + rec.path + " --recover), then score it");
  if (!rec.header.contains("scenario") || !rec.header["scenario"].is_object())
    throw ScoreError(rec.path + ": header: no scenario (the patient cannot be rebuilt)");
  sim::Scenario sc;
  std::uint64_t swap_index = 0;
  bool swapped = false;
  try {
    sc = store::parse_recorded_scenario(rec.header["scenario"], rec.path + ": header scenario");
    // The exam is on the last patient the session loaded.
    for (const json& e : rec.events)
      if (e.is_object() && e.value("kind", "") == "parameter" && e.value("command", "") == "patient" && e.contains("scenario") &&
          e.contains("index") && e["index"].is_number_unsigned()) {
        sc = store::parse_recorded_scenario(e["scenario"], rec.path + ": patient change");
        swap_index = e["index"].get<std::uint64_t>();
        swapped = true;
      }
  } catch (const sim::ScenarioError& e) {
    throw ScoreError(e.what());
  }
  ScoredExam out;
  out.patient = sc.patient.mesh.empty() ? sc.patient.phantom : sc.patient.mesh;
  auto model = std::make_shared<const sim::Model>(sim::build_scenario_model(sc, sim::patient_mesh(sc)));
  // The moduli at the end: the scenario's inclusions and the instructor's edits since.
  std::vector<double> young = model->materials.young;
  const bool mesh_order = store::young_in_mesh_order(rec);
  for (const json& e : rec.events) {
    if (!e.is_object() || e.value("kind", "") != "parameter" || e.value("command", "") != "young") continue;
    if (swapped && (!e.contains("index") || !e["index"].is_number_unsigned() || e["index"].get<std::uint64_t>() < swap_index))
      continue;
    for (const auto& [el, E] : store::young_in_model_order(*model, store::recorded_young_changes(e), mesh_order))
      if (el >= 0 && std::size_t(el) < young.size()) young[std::size_t(el)] = E;
  }
  auto skin = std::make_shared<const SkinMap>(build_skin_map(*model));
  out.skin = skin;
  ExamTracker tracker(skin, thresholds);
  const int nf = std::max(0, rec.fingers);
  std::vector<double> last(std::size_t(nf), -1e300);
  out.plot_force.assign(std::size_t(nf), {});
  double last_plot = -1e300;
  auto sample = [&](double t, int k, const Eigen::Vector3d& x, double r, double f) {
    if (t - last[std::size_t(k)] < kSamplePeriod) return;
    last[std::size_t(k)] = t;
    tracker.add({t, k, x, r, f});
    ++out.samples;
  };
  if (rec.step_count() > 0) {
    rec.for_each_step([&](std::size_t, const store::RecordedStep& st) {
      if (swapped && st.commands_applied <= swap_index) return;
      for (int k = 0; k < nf && k < int(st.fingers.size()); ++k) {
        const auto& fi = st.fingers[std::size_t(k)];
        if (fi.active) sample(st.t, k, fi.x, fi.radius, fi.f.norm());
      }
      if (st.t - last_plot >= kPlotPeriod) {
        last_plot = st.t;
        out.plot_t.push_back(st.t);
        for (int k = 0; k < nf; ++k)
          out.plot_force[std::size_t(k)].push_back(k < int(st.fingers.size()) ? st.fingers[std::size_t(k)].f.norm() : 0.0);
      }
    });
  } else {
    // Ticks hold the forces sent to the device: back to simulated ones for the levels.
    const double to_sim = 1.0 / store::recorded_force_scale(rec);
    rec.for_each_tick([&](std::size_t, double t, const Eigen::Vector3d* x, const Eigen::Vector3d* f) {
      for (int k = 0; k < nf; ++k) {
        const double r = k < int(sc.fingers.size()) ? sc.fingers[std::size_t(k)].radius : 0.008;
        sample(t, k, x[k], r, to_sim * f[k].norm());
      }
      if (t - last_plot >= kPlotPeriod) {
        last_plot = t;
        out.plot_t.push_back(t);
        for (int k = 0; k < nf; ++k) out.plot_force[std::size_t(k)].push_back(to_sim * f[k].norm());
      }
    });
  }
  // Marks: the session's mark events and the scripted trainee's.
  std::vector<Mark> marks;
  for (const json& e : rec.events) {
    if (!e.is_object() || e.value("kind", "") != "mark" || !e.contains("t") || !e["t"].is_number()) continue;
    const json& p = e.contains("position") ? e["position"] : json();
    if (!(p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() && p[2].is_number())) continue;
    Mark m;
    m.t = e["t"].get<double>();
    m.position = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    if (e.contains("confidence") && e["confidence"].is_number()) m.confidence = std::clamp(e["confidence"].get<double>(), 0.0, 1.0);
    marks.push_back(m);
  }
  for (const sim::ScenarioMark& sm : sc.marks) marks.push_back({sm.t, sm.position, sm.confidence});
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const double d = skin->distance(marks[i].position);
    if (!marks[i].position.allFinite() || !(d <= kMarkMaxDistance))
      throw ScoreError(rec.path + ": mark " + std::to_string(i + 1) + " at t = " + std::to_string(marks[i].t) + " s, " +
                       fmt_m(marks[i].position) + ": outside the body (" + std::to_string(int(std::lround(d * 1000))) +
                       " mm from the skin; at most " + std::to_string(int(kMarkMaxDistance * 1000)) + " mm)");
  }
  const double pad = sc.fingers.empty() ? kPadRadius : sc.fingers.front().radius;
  const auto tumours = find_tumours(model->rest, model->tets, young, model->tissue_young, *skin, pad);
  double duration = rec.duration();
  if constexpr (std::is_same_v<Rec, store::CompactRecording>) {
    if (rec.step_count() > 0) duration = std::max(duration, rec.step_times().back());
  } else {
    if (!rec.steps.empty()) duration = std::max(duration, rec.steps.back().t);
  }
  out.score = score_exam(tracker, tumours, std::move(marks), duration);
  out.face_level = tracker.face_level();
  out.face_reached = tracker.face_reached();
  return out;
}

}  // namespace

ScoredExam score_recording(const store::Recording& rec, const PressureThresholds& thresholds) {
  return score_any(rec, thresholds);
}

ScoredExam score_recording(const store::CompactRecording& rec, const PressureThresholds& thresholds) {
  return score_any(rec, thresholds);
}

}  // namespace palpation::app::train
