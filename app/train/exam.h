// Training feedback (docs/training.md): what a trainee covered, how hard they pressed,
// what they found. Qt-free, so that `palpation score`, the workstation and the review
// compute the same figures from the same samples.
//
//   SkinMap      the patient's skin (boundary faces off the chest wall) with each face's
//                area, normal and tissue thickness (skin to chest wall along the normal)
//   PressureThresholds / classify   light, medium, deep from indentation / thickness and force
//   ExamTracker  fed fingertip samples (centre, radius, simulated force): the highest level
//                reached on each face and when each level was first reached there, the
//                contact path (for the search pattern), and the highest level reached over
//                each tumour
//   score_exam   marks against tumours: hits, false positives, errors, times, sensitivity,
//                positive predictive value, specificity (no tumour), coverage, pattern
//
// The body's rest geometry is used throughout: coverage is where on the skin a pad pressed,
// which the deformation does not change; depth is the fingertip sphere's reach below the
// rest skin, which is the tissue's indentation.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace palpation::sim {
struct Model;
struct Scenario;
}

namespace palpation::app::train {

enum class Level { None = 0, Light = 1, Medium = 2, Deep = 3 };
inline constexpr int kLevels = 3;  // light, medium, deep
/// "none", "light", "medium", "deep".
const char* level_name(Level l);

/// What makes a press light, medium or deep. A press reaches a level when its indentation
/// (the fingertip's reach below the rest skin) is at least that level's fraction of the
/// local tissue thickness, or its force at least that level's force. Defaults and their
/// sources: docs/training.md ("Pressure levels").
struct PressureThresholds {
  // Fractions of the skin-to-chest-wall thickness under the pad.
  double light_depth = 0.03;
  double medium_depth = 0.15;
  double deep_depth = 0.30;
  // Force on the finger pad, N (the simulated force on the tissue, not the device's).
  double light_force = 0.3;
  double medium_force = 3.0;
  double deep_force = 10.0;
  /// Throws std::invalid_argument naming the field when the thresholds are not increasing
  /// and positive (depth fractions below 1).
  void validate() const;
};
Level classify(double depth, double thickness, double force, const PressureThresholds& t);

nlohmann::json to_json(const PressureThresholds& t);
/// Missing fields keep their defaults; throws std::invalid_argument naming a bad field.
PressureThresholds thresholds_from_json(const nlohmann::json& j, const PressureThresholds& base = {});

/// The skin: the patient's boundary faces that are not on the chest wall, at rest.
struct SkinMap {
  std::vector<Eigen::Vector3d> nodes;           // rest positions (the model's), m
  std::vector<std::array<int, 3>> faces;        // skin faces, outward
  std::vector<int> model_face;                  // index in Model::surface
  std::vector<Eigen::Vector3d> centroid, normal;
  std::vector<double> area;                     // m^2
  std::vector<double> thickness;                // m, skin to chest wall along -normal
  std::vector<std::vector<int>> neighbours;     // faces sharing an edge
  double total_area = 0;                        // m^2
  Eigen::Vector3d lo, hi;                       // bounding box of the skin

  /// The face nearest to `p` (by centroid), -1 when the skin is empty.
  int nearest_face(const Eigen::Vector3d& p) const;
  /// Faces whose centroid lies within `r` of `p`.
  std::vector<int> faces_within(const Eigen::Vector3d& p, double r) const;
  /// The skin point above `p` along the chest wall's outward normal (+z), or the nearest
  /// face's centroid when no face lies above.
  Eigen::Vector3d skin_above(const Eigen::Vector3d& p) const;
  /// `p` projected onto the skin: onto the plane of the face nearest to it.
  Eigen::Vector3d project(const Eigen::Vector3d& p) const;
  /// Distance from `p` to the skin (to its projection), m.
  double distance(const Eigen::Vector3d& p) const;

  // Uniform grid over the face centroids (cell_ m), for the queries above.
  double cell_ = 0.01;
  std::array<int, 3> dims_{};
  std::vector<std::vector<int>> grid_;
};
SkinMap build_skin_map(const sim::Model& m);

/// A hidden tumour as the scorer sees it: connected stiff elements.
struct TumourTruth {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   // volume-weighted, m
  double lateral_radius = 0;                          // m, extent across the skin (x-y)
  double depth = 0;                                   // m, skin above the centre to the tumour's top
  double young = 0;                                   // Pa, mean
  double contrast = 0;                                // young / the tissue it replaced
  int elements = 0;
  Eigen::Vector3d skin_point = Eigen::Vector3d::Zero(); // projection on the skin (skin_above)
  /// A mark within this distance of skin_point finds the tumour (m): the tumour's lateral
  /// radius plus a finger pad radius (docs/training.md, "Hit tolerance").
  double tolerance = 0;
};
/// Tumours from per-element moduli: elements above the tumour rule (E > 1.2 x the element's
/// tissue, `tissue_young`, sim::Model::tissue_young), grouped by shared nodes.
std::vector<TumourTruth> find_tumours(const std::vector<Eigen::Vector3d>& rest, const std::vector<std::array<int, 4>>& tets,
                                      const std::vector<double>& young, const std::vector<double>& tissue_young,
                                      const SkinMap& skin,
                                      double pad_radius);
inline constexpr double kPadRadius = 0.008;  // m, the fingertip's (the paper's index finger)

/// One fingertip sample: a device finger's simulated sphere and the force on it.
struct FingerSample {
  double t = 0;                                       // s
  int finger = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   // world, m
  double radius = 0.008;                              // m
  double force = 0;                                   // |simulated force| on the finger, N
};

/// A trainee's mark: "I feel a lump here".
struct Mark {
  double t = 0;                                       // s since the exam started
  Eigen::Vector3d position = Eigen::Vector3d::Zero(); // world, m
  double confidence = 1.0;                            // 0..1
};

struct PatternFigures {
  int strips = 0;                  // vertical strips (runs along y of at least a third of the skin's length)
  double vertical_fraction = 0;    // share of the pressed path length in vertical strips
  double mean_overlap = 0;         // between neighbouring strips: 1 - spacing / pad width (negative: gaps)
  struct Region {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double area = 0;               // m^2
  };
  std::vector<Region> skipped;     // unpalpated skin regions of at least 1 cm^2, largest first
  double path_length = 0;          // m, pressed path of all fingers
};

/// When one skin face first reached each level (light, medium, deep), s since the
/// recording's start; kNever where it never did. Reaching a level reaches the ones below
/// it, so the times never decrease from light to deep.
using LevelTimes = std::array<double, kLevels>;
inline constexpr double kNever = std::numeric_limits<double>::infinity();
/// The highest level each face had reached at time t (at or before t): the coverage as it
/// grew during the exam (the review's overlay at its playback time). Levels up to the
/// last sample's time are the tracker's face_level().
std::vector<unsigned char> levels_at(const std::vector<LevelTimes>& reached, double t);
/// Area fraction of the skin reached at least at each level by time t.
std::array<double, kLevels> coverage_at(const SkinMap& skin, const std::vector<LevelTimes>& reached, double t);

/// Accumulates an exam from fingertip samples (any rate; the workstation feeds each
/// simulation step, `palpation score` the recording's steps or ticks).
class ExamTracker {
 public:
  ExamTracker(std::shared_ptr<const SkinMap> skin, PressureThresholds t = {});
  void add(const FingerSample& s);
  /// The highest level reached on each skin face.
  const std::vector<unsigned char>& face_level() const { return level_; }
  /// When each skin face first reached each level (samples' times; levels_at(face_reached(), t)
  /// is face_level() as it stood at time t).
  const std::vector<LevelTimes>& face_reached() const { return reached_; }
  /// Area fraction of the skin reached at least at each level (light, medium, deep).
  std::array<double, kLevels> coverage() const;
  /// Area fraction of the skin touched at all (any contact, below light pressure too).
  double touched() const;
  /// Highest level reached on the faces within `r` of `p`.
  Level level_near(const Eigen::Vector3d& p, double r) const;
  PatternFigures pattern() const;
  double first_contact() const { return first_; }     // s, -1 before any contact
  double last_contact() const { return last_; }
  const SkinMap& skin() const { return *skin_; }
  const PressureThresholds& thresholds() const { return t_; }
  /// Forgets everything (a new exam on the same patient).
  void reset();

 private:
  std::shared_ptr<const SkinMap> skin_;
  PressureThresholds t_;
  std::vector<unsigned char> level_, touched_;
  std::vector<LevelTimes> reached_;
  struct PathPoint {
    double t;
    Eigen::Vector3d p;
    int finger;
    bool start;  // the first point of a press
  };
  std::vector<PathPoint> path_;  // pressed contact points, decimated to 1 mm of travel per finger
  std::array<Eigen::Vector3d, 5> last_p_{};
  std::array<bool, 5> pressing_{};
  double first_ = -1, last_ = -1;
};

struct TumourResult {
  TumourTruth truth;
  bool found = false;
  int mark = -1;                   // index of the mark that found it
  double error = 0;                // m, mark to the tumour's skin point
  double time_to_find = 0;         // s after the exam started
  Level max_level_over = Level::None;  // highest pressure level over the tumour
  bool deep_reached = false;
};

/// One line of what to practise next, as data: its kind and its figures. text() is its
/// English line (score.json, the report, `palpation score`); the GUI composes the line in
/// the chosen language from the same data (ui/score_dialog).
struct Advice {
  enum class Kind {
    Coverage,        // a level's coverage under 90 %: `level`, `percent` of the skin reached at it
    Strips,          // fewer than three strips or under half the path in strips: `count` strips, `percent` of the path
    Overlap,         // neighbouring strips left gaps between them
    PressDeep,       // a tumour missed where deep pressure was not reached: `depth_mm` below the skin
    FalsePositives,  // `count` marks found no lump
    Complete,        // nothing to practise
  };
  Kind kind = Kind::Complete;
  Level level = Level::None;  // Coverage
  int percent = 0;            // Coverage, Strips: rounded to a whole per cent
  int count = 0;              // Strips, FalsePositives
  int depth_mm = 0;           // PressDeep: rounded to a whole millimetre
  /// The English line.
  std::string text() const;
  bool operator==(const Advice&) const = default;
};

struct ExamScore {
  std::array<double, kLevels> coverage{};  // fractions of the skin, at least light / medium / deep
  double touched = 0;                      // fraction of the skin touched at all
  PatternFigures pattern;
  std::vector<TumourResult> tumours;
  std::vector<Mark> marks;                 // in time order
  std::vector<Eigen::Vector3d> marks_on_skin;  // each mark projected onto the skin
  std::vector<int> false_positive_marks;   // indices into marks
  int hits = 0, false_positives = 0;
  std::optional<double> sensitivity;       // hits / tumours (none without tumours)
  std::optional<double> ppv;               // true marks / marks (none without marks)
  std::optional<bool> specific;            // no tumour: true when nothing was marked
  double mean_error = 0;                   // m, over hits
  double exam_time = 0;                    // s, first contact to the end
  double duration = 0;                     // s, the whole session
  PressureThresholds thresholds;
  /// What to practise next, one line each (Advice::text() in English).
  std::vector<Advice> advice;
};

/// A scripted trainee: vertical strips (along y) over the skin between x_min and x_max,
/// `spacing` apart, each gone over at every level of `levels` at a depth inside that level's
/// band (forces left at zero: the depth decides). For tests, the bench and demonstrations.
struct StripExamSpec {
  double x_min = -1, x_max = 1;   // m, clipped to the skin
  double spacing = 0.006;         // m between strips
  double step = 0.002;            // m between samples along a strip
  double speed = 0.02;            // m/s along a strip
  std::vector<Level> levels{Level::Light, Level::Medium, Level::Deep};
  double radius = 0.008;          // m, fingertip
  int finger = 1;                 // the index finger
};
std::vector<FingerSample> vertical_strip_exam(const SkinMap& skin, const PressureThresholds& t, const StripExamSpec& spec);

ExamScore score_exam(const ExamTracker& tracker, const std::vector<TumourTruth>& tumours, std::vector<Mark> marks,
                     double duration);
nlohmann::json to_json(const ExamScore& s);

}  // namespace palpation::app::train
