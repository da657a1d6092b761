#include "live/event.h"

#include <array>
#include <cstdio>
#include <utility>

namespace palpation::app::live {

using nlohmann::json;

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

// Names of the enumerations in recordings.
constexpr std::array<std::pair<EventKind, const char*>, 12> kKindNames{{{EventKind::PatientLoading, "patient-loading"},
                                                                       {EventKind::PatientLoaded, "patient-loaded"},
                                                                       {EventKind::PatientNotLoaded, "patient-not-loaded"},
                                                                       {EventKind::Params, "params"},
                                                                       {EventKind::Material, "material"},
                                                                       {EventKind::Mode, "mode"},
                                                                       {EventKind::Mark, "mark"},
                                                                       {EventKind::ExamEnded, "exam-ended"},
                                                                       {EventKind::Fallback, "fallback"},
                                                                       {EventKind::Reset, "reset"},
                                                                       {EventKind::Error, "error"},
                                                                       {EventKind::Stopped, "stopped"}}};
constexpr std::array<std::pair<ModeChange, const char*>, 6> kModeNames{{{ModeChange::MousePalpation, "mouse-palpation"},
                                                                       {ModeChange::ScriptedHand, "scripted-hand"},
                                                                       {ModeChange::Trainee, "trainee"},
                                                                       {ModeChange::Instructor, "instructor"},
                                                                       {ModeChange::GuidedPractice, "guided-practice"},
                                                                       {ModeChange::Exam, "exam"}}};
constexpr std::array<std::pair<MaterialEdit::Kind, const char*>, 4> kEditNames{{{MaterialEdit::Kind::AddTumour, "add-tumour"},
                                                                               {MaterialEdit::Kind::RemoveTumour, "remove-tumour"},
                                                                               {MaterialEdit::Kind::Dab, "dab"},
                                                                               {MaterialEdit::Kind::Stroke, "stroke"}}};
constexpr std::array<std::pair<TumourLabel::Origin, const char*>, 3> kOriginNames{{{TumourLabel::Origin::Patient, "patient"},
                                                                                  {TumourLabel::Origin::Shape, "shape"},
                                                                                  {TumourLabel::Origin::Painted, "painted"}}};
constexpr std::array<std::pair<TumourShape, const char*>, 2> kShapeNames{{{TumourShape::Sphere, "sphere"},
                                                                        {TumourShape::Ellipsoid, "ellipsoid"}}};

template <typename E, std::size_t N>
const char* name_of(const std::array<std::pair<E, const char*>, N>& names, E v) {
  for (const auto& [e, n] : names)
    if (e == v) return n;
  return "";
}
template <typename E, std::size_t N>
std::optional<E> value_of(const std::array<std::pair<E, const char*>, N>& names, const json& j) {
  if (!j.is_string()) return std::nullopt;
  for (const auto& [e, n] : names)
    if (j.get_ref<const std::string&>() == n) return e;
  return std::nullopt;
}

json vec_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
std::optional<Eigen::Vector3d> vec_from(const json& j) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number()) return std::nullopt;
  return Eigen::Vector3d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

}  // namespace

// ---------------------------------------------------------------------------- makers

Event Event::patient_loading(const std::string& source) { return with_detail(EventKind::PatientLoading, source); }

Event Event::patient_loaded(int nodes, int tetrahedra, const std::string& backend) {
  Event e = with_detail(EventKind::PatientLoaded, backend);
  e.nodes = nodes;
  e.tetrahedra = tetrahedra;
  return e;
}

Event Event::with_detail(EventKind kind, const std::string& detail) {
  Event e;
  e.kind = kind;
  e.detail = detail;
  return e;
}

Event Event::params() {
  Event e;
  e.kind = EventKind::Params;
  return e;
}

Event Event::material(const MaterialEdit& edit) {
  Event e;
  e.kind = EventKind::Material;
  e.edit = edit;
  return e;
}

Event Event::mode_change(ModeChange m) {
  Event e;
  e.kind = EventKind::Mode;
  e.mode = m;
  return e;
}

Event Event::trainee_mark(int number, std::optional<Eigen::Vector3d> position, const std::string& note, double confidence) {
  Event e = with_detail(EventKind::Mark, note);
  e.mark = number;
  e.position = position;
  e.confidence = confidence;
  return e;
}

Event Event::exam_ended(ModeChange mode) {
  Event e;
  e.kind = EventKind::ExamEnded;
  e.mode = mode;
  return e;
}

std::string Event::text() const { return event_text(*this); }

// ---------------------------------------------------------------------------- English

std::string tumour_label_text(const TumourLabel& l) {
  switch (l.origin) {
    case TumourLabel::Origin::Patient: return "Patient's tumour";
    case TumourLabel::Origin::Shape:
      return std::string(l.shape == TumourShape::Sphere ? "Sphere" : "Ellipsoid") +
             format(" at (%.1f, %.1f, %.1f) cm, %.0f kPa", l.centre.x() * 100, l.centre.y() * 100, l.centre.z() * 100,
                    l.young / 1000);
    case TumourLabel::Origin::Painted: return "Painted tumour " + std::to_string(l.number) + format(", %.0f kPa", l.young / 1000);
  }
  return {};
}

std::string material_edit_text(const MaterialEdit& e) {
  std::string s;
  switch (e.kind) {
    case MaterialEdit::Kind::AddTumour: s = "Add tumour: " + tumour_label_text(e.tumour); break;
    case MaterialEdit::Kind::RemoveTumour: s = "Remove tumour: " + tumour_label_text(e.tumour); break;
    case MaterialEdit::Kind::Dab: s = e.erase ? "Erase" : "Paint"; break;
    case MaterialEdit::Kind::Stroke:
      s = std::string(e.erase ? "Erase" : "Paint") + " stroke (" + std::to_string(e.elements) +
          (e.elements == 1 ? " element)" : " elements)");
      break;
  }
  return e.undo ? "Undo: " + s : s;
}

std::string event_text(const Event& e) {
  switch (e.kind) {
    case EventKind::PatientLoading: return "loading patient: " + e.detail;
    case EventKind::PatientLoaded:
      return "patient loaded: " + std::to_string(e.nodes) + " nodes, " + std::to_string(e.tetrahedra) + " tetrahedra, backend " +
             e.detail;
    case EventKind::PatientNotLoaded: return "patient not loaded: " + e.detail;
    case EventKind::Params: return "solver/contact parameters changed";
    case EventKind::Material: return material_edit_text(e.edit);
    case EventKind::Mode:
      switch (e.mode) {
        case ModeChange::MousePalpation: return "device: mouse palpation";
        case ModeChange::ScriptedHand: return "device: scripted hand";
        case ModeChange::Trainee: return "trainee mode";
        case ModeChange::Instructor: return "instructor mode";
        case ModeChange::GuidedPractice: return "guided practice (trainee)";
        case ModeChange::Exam: return "exam (trainee)";
      }
      return {};
    case EventKind::Mark: {
      std::string s = "trainee mark " + std::to_string(e.mark);
      if (e.position) s += format(" at (%.1f, %.1f, %.1f) cm", e.position->x() * 100, e.position->y() * 100, e.position->z() * 100);
      // A certain mark (and every mark of older recordings) reads as before.
      if (e.confidence < 1.0) s += format(", %.0f %% confident", e.confidence * 100);
      if (!e.detail.empty()) s += ": " + e.detail;
      return s;
    }
    case EventKind::ExamEnded: return e.mode == ModeChange::GuidedPractice ? "guided practice ended" : "exam ended";
    case EventKind::Fallback: return "backend error: " + e.detail + "; continuing on the CPU from rest (forces held, then blended)";
    case EventKind::Reset: return "simulation diverged (" + e.detail + "): body reset to rest (forces held, then blended)";
    case EventKind::Error: return e.detail;
    case EventKind::Stopped: return "simulation stopped: " + e.detail;
  }
  return {};
}

// ---------------------------------------------------------------------------- JSON

const char* event_kind_name(EventKind k) { return name_of(kKindNames, k); }

std::optional<EventKind> event_kind_from_name(const std::string& name) { return value_of(kKindNames, json(name)); }

json event_args_json(const Event& e) {
  json a = json::object();
  switch (e.kind) {
    case EventKind::PatientLoaded:
      a["nodes"] = e.nodes;
      a["tetrahedra"] = e.tetrahedra;
      a["detail"] = e.detail;
      break;
    case EventKind::Params: break;
    case EventKind::Material: {
      json t{{"origin", name_of(kOriginNames, e.edit.tumour.origin)}};
      if (e.edit.tumour.origin == TumourLabel::Origin::Shape) {
        t["shape"] = name_of(kShapeNames, e.edit.tumour.shape);
        t["centre"] = vec_json(e.edit.tumour.centre);
      }
      if (e.edit.tumour.origin != TumourLabel::Origin::Patient) t["young"] = e.edit.tumour.young;
      if (e.edit.tumour.origin == TumourLabel::Origin::Painted) t["number"] = e.edit.tumour.number;
      a["edit"] = name_of(kEditNames, e.edit.kind);
      a["erase"] = e.edit.erase;
      a["undo"] = e.edit.undo;
      a["elements"] = e.edit.elements;
      a["tumour"] = std::move(t);
      break;
    }
    case EventKind::Mode: a["mode"] = name_of(kModeNames, e.mode); break;
    case EventKind::Mark:
      a["mark"] = e.mark;
      if (e.position) a["position"] = vec_json(*e.position);
      a["confidence"] = e.confidence;
      if (!e.detail.empty()) a["detail"] = e.detail;
      break;
    case EventKind::ExamEnded: a["mode"] = name_of(kModeNames, e.mode); break;
    default: a["detail"] = e.detail; break;
  }
  return a;
}

std::optional<Event> event_from_json(const std::string& kind_name, const json& a, double t) {
  const auto kind = event_kind_from_name(kind_name);
  if (!kind || !a.is_object()) return std::nullopt;
  Event e;
  e.t = t;
  e.kind = *kind;
  auto integer = [&](const char* key, int& out) {
    if (!a.contains(key) || !a[key].is_number_integer()) return false;
    out = a[key].get<int>();
    return true;
  };
  auto boolean = [&](const char* key, bool& out) {
    if (!a.contains(key) || !a[key].is_boolean()) return false;
    out = a[key].get<bool>();
    return true;
  };
  if (a.contains("detail")) {
    if (!a["detail"].is_string()) return std::nullopt;
    e.detail = a["detail"].get<std::string>();
  }
  switch (e.kind) {
    case EventKind::PatientLoaded:
      if (!integer("nodes", e.nodes) || !integer("tetrahedra", e.tetrahedra)) return std::nullopt;
      break;
    case EventKind::Params: break;
    case EventKind::Material: {
      const auto kind_of_edit = a.contains("edit") ? value_of(kEditNames, a["edit"]) : std::nullopt;
      if (!kind_of_edit || !boolean("erase", e.edit.erase) || !boolean("undo", e.edit.undo) || !integer("elements", e.edit.elements) ||
          !a.contains("tumour") || !a["tumour"].is_object())
        return std::nullopt;
      e.edit.kind = *kind_of_edit;
      const json& tumour = a["tumour"];
      const auto origin = tumour.contains("origin") ? value_of(kOriginNames, tumour["origin"]) : std::nullopt;
      if (!origin) return std::nullopt;
      TumourLabel& l = e.edit.tumour;
      l.origin = *origin;
      if (l.origin == TumourLabel::Origin::Shape) {
        const auto shape = tumour.contains("shape") ? value_of(kShapeNames, tumour["shape"]) : std::nullopt;
        const auto centre = tumour.contains("centre") ? vec_from(tumour["centre"]) : std::nullopt;
        if (!shape || !centre) return std::nullopt;
        l.shape = *shape;
        l.centre = *centre;
      }
      if (l.origin != TumourLabel::Origin::Patient) {
        if (!tumour.contains("young") || !tumour["young"].is_number()) return std::nullopt;
        l.young = tumour["young"].get<double>();
      }
      if (l.origin == TumourLabel::Origin::Painted) {
        if (!tumour.contains("number") || !tumour["number"].is_number_integer()) return std::nullopt;
        l.number = tumour["number"].get<int>();
      }
      break;
    }
    case EventKind::Mode:
    case EventKind::ExamEnded: {
      const auto m = a.contains("mode") ? value_of(kModeNames, a["mode"]) : std::nullopt;
      if (!m) return std::nullopt;
      e.mode = *m;
      break;
    }
    case EventKind::Mark:
      if (!integer("mark", e.mark)) return std::nullopt;
      if (a.contains("position")) {
        e.position = vec_from(a["position"]);
        if (!e.position) return std::nullopt;
      }
      // Recordings made before marks carried a confidence: certain.
      if (a.contains("confidence")) {
        if (!a["confidence"].is_number()) return std::nullopt;
        e.confidence = a["confidence"].get<double>();
      }
      break;
    default:
      if (!a.contains("detail")) return std::nullopt;
      break;
  }
  return e;
}

}  // namespace palpation::app::live
