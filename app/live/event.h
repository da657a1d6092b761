// The workstation's events as data: what happened (EventKind) and its arguments (patient
// name, node and element counts, a tumour's shape, centre and modulus, a mark's number and
// position, a reason). The English one-line text is composed here, in one place (event_text:
// the event log, the command line, the recording); the GUI composes its translated text
// from the same kind and arguments (ui/event_text.h). A recording keeps both: the English
// line and the kind with its arguments as JSON (event_to_json / event_from_json).
// Qt-free.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace palpation::app::live {

enum class TumourShape { Sphere, Ellipsoid };

/// What a tumour of the tumour list is called, as data: the patient's own (scenario
/// inclusions), one added by shape (shape, centre, modulus) or one painted (its number
/// among the painted ones, modulus).
struct TumourLabel {
  enum class Origin { Patient, Shape, Painted };
  Origin origin = Origin::Patient;
  TumourShape shape = TumourShape::Sphere;                // Shape
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       // Shape: world, m
  double young = 0;                                       // Shape, Painted: Pa
  int number = 0;                                         // Painted: 1, 2, ...
};

/// An instructor's change of element moduli (a tumour-editor step or one brush dab).
struct MaterialEdit {
  enum class Kind { AddTumour, RemoveTumour, Dab, Stroke };
  Kind kind = Kind::Dab;
  bool erase = false;   // Dab, Stroke: back to the tissue's modulus
  bool undo = false;    // the edit undone
  int elements = 0;     // Stroke: elements it changed
  TumourLabel tumour;   // AddTumour, RemoveTumour
};

/// The mode changes the workstation logs: the device's (mouse or scripted hand) and the
/// training mode's (live/training_session.h). `Trainee` is the one trainee mode of
/// recordings made before guided practice and exams were told apart.
enum class ModeChange { MousePalpation, ScriptedHand, Trainee, Instructor, GuidedPractice, Exam };

enum class EventKind {
  PatientLoading,    // detail: the patient's source (library name, phantom, file)
  PatientLoaded,     // nodes, tetrahedra; detail: the backend
  PatientNotLoaded,  // detail: why
  Params,            // solver or contact parameters changed
  Material,          // edit
  Mode,              // mode
  Mark,              // mark, position (where known), confidence; detail: the trainee's note
  ExamEnded,         // mode: the trainee mode whose exam ended (GuidedPractice or Exam)
  Fallback,          // detail: the backend's error (continuing on the CPU from rest)
  Reset,             // detail: why the simulation diverged (body reset to rest)
  Error,             // detail: what failed, as the system said it
  Stopped,           // detail: why the simulation stopped
};

struct Event {
  double t = 0;  // s since the workstation started
  EventKind kind = EventKind::Error;
  std::string detail;                      // see EventKind
  int nodes = 0, tetrahedra = 0;           // PatientLoaded
  MaterialEdit edit;                       // Material
  ModeChange mode = ModeChange::ScriptedHand;  // Mode, ExamEnded
  int mark = 0;                            // Mark: its number (1, 2, ...)
  std::optional<Eigen::Vector3d> position;  // Mark: world, m
  double confidence = 1.0;                 // Mark: how sure the trainee is, 0..1 (1 in older recordings)

  /// The English one-line text (event_text).
  std::string text() const;

  static Event patient_loading(const std::string& source);
  static Event patient_loaded(int nodes, int tetrahedra, const std::string& backend);
  static Event with_detail(EventKind kind, const std::string& detail);
  static Event params();
  static Event material(const MaterialEdit& edit);
  static Event mode_change(ModeChange m);
  static Event trainee_mark(int number, std::optional<Eigen::Vector3d> position = {}, const std::string& note = {},
                            double confidence = 1.0);
  /// The end of a trainee's exam (or guided practice: `mode`).
  static Event exam_ended(ModeChange mode);
};

/// The English one-line text of an event (the one composition of it).
std::string event_text(const Event& e);
/// English texts of the parts (used by event_text).
std::string tumour_label_text(const TumourLabel& l);
std::string material_edit_text(const MaterialEdit& e);

/// The kind's stable name in recordings ("patient-loaded", "material", ...), and back.
const char* event_kind_name(EventKind k);
std::optional<EventKind> event_kind_from_name(const std::string& name);

/// The event's arguments as JSON (without t and kind).
nlohmann::json event_args_json(const Event& e);
/// An event from its kind name and arguments (a recording's); nothing when the name is
/// unknown or an argument is missing or of the wrong type.
std::optional<Event> event_from_json(const std::string& kind_name, const nlohmann::json& args, double t = 0);

}  // namespace palpation::app::live
