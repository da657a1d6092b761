// Scenarios: the JSON contract of design.md section 5, parsed and validated.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "params.h"

namespace palpation::sim {

/// A bad scenario: what() is one line naming the file, the field and the reason.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A stiff region: elements whose centroid lies inside get its material.
struct Inclusion {
  std::string shape = "sphere";                          // "sphere" | "ellipsoid"
  Eigen::Vector3d center = Eigen::Vector3d::Zero();       // m
  Eigen::Vector3d radii = Eigen::Vector3d::Constant(0.01);  // m (sphere: all equal)
  double young_modulus = 107000.0;                        // Pa
  double poisson_ratio = 0.45;
  bool contains(const Eigen::Vector3d& p) const {
    return ((p - center).array() / radii.array()).square().sum() <= 1.0;
  }
};

struct PatientSpec {
  std::string phantom = "breast";     // "breast" | "box" | "" when mesh is set
  std::string mesh;                   // mesh file (resolved against the scenario's folder)
  std::string resolution = "paper";   // named level, or empty when edge is numeric
  double edge = 0.0;                  // m, target edge length (resolved from the level)
  Eigen::Vector3d size = Eigen::Vector3d(0.1, 0.1, 0.05);  // box only, m
  double grading = 1.0;               // box only: >1 concentrates cells at the top centre
  double base_radius = 0.08;          // breast only, m: radius of the base on the chest wall
  double height = 0.065;              // breast only, m: skin above the chest wall on the axis
  /// Breast only, m: target edge length at the skin, graded back to `edge` by 1 cm below
  /// it; 0: the skin is meshed at `edge`. The fingertip (8 mm) touches the tissue through
  /// the skin's elements, and the force of a press converges slowly while they are about
  /// its size (docs/simulation.md, "Mesh convergence").
  double skin_edge = 0.0;
};

/// How a finger path runs between its keys ("fingers[i].interpolation").
///  - Linear (the default): straight at constant velocity; the velocity jumps at each key.
///  - MonotoneCubic: a C1 piecewise cubic Hermite curve per coordinate (three-point
///    slopes limited for monotonicity, Hyman 1983), through every key, with velocity zero
///    at the first and last keys (the path is held outside them). Between two keys each coordinate
///    stays between the keys' values, so a press is never deeper than its keys say; where
///    a coordinate turns (a press that turns back up, a sweep that reverses) its velocity is
///    zero at that key. For keys sampled from a smooth motion, as a hand moves: the linear
///    path's jumps in velocity are what the implicit step's warm start cannot foresee, and
///    cost the solver several times a smooth step's CG iterations (docs/simulation.md,
///    "Finger paths").
enum class PathInterpolation { Linear, MonotoneCubic };
const char* path_interpolation_name(PathInterpolation p);
/// The names path_interpolation_name gives, in the enum's order (scenario and CLI choices).
std::vector<std::string> path_interpolation_names();
/// The interpolation of a name path_interpolation_name gives (one of
/// path_interpolation_names(); the caller checks it is).
PathInterpolation parse_path_interpolation(const std::string& name);

struct FingerPath {
  double radius = 0.008;                        // m
  std::vector<std::array<double, 4>> keys;      // [t, x, y, z], t increasing
  PathInterpolation interpolation = PathInterpolation::Linear;
  /// Centre position and velocity at time t (by `interpolation` between keys, held
  /// outside). Never allocates.
  void sample(double t, Eigen::Vector3d& pos, Eigen::Vector3d& vel) const;
  /// Keys that a linear follower (device::HandScript) traces as this path: the keys
  /// themselves when linear, else the path sampled every `step` s from the first key to
  /// the last (both kept). At step = 1 ms (the haptic tick) the chord of a monotone
  /// cubic lies within max|x''| step^2 / 8 of it: 0.4 um on the paper sweep.
  std::vector<std::array<double, 4>> linear_keys(double step) const;
};

/// A trainee's mark in a scripted session ("marks": [[t, x, y, z, confidence], ...]): where
/// a scripted trainee said "I feel a lump here", scored like a live one.
struct ScenarioMark {
  double t = 0;                                        // s
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, m
  double confidence = 1.0;                             // 0..1
};

struct Scenario {
  std::string source;                 // file it came from (for messages)
  PatientSpec patient;
  double young_modulus = 19000.0;     // tissue, Pa
  double poisson_ratio = 0.45;
  double density = 1000.0;            // kg/m^3
  /// tissue.layers: skin, fat, glandular tissue... from the skin inward (tissue_layers.h);
  /// empty: the tissue is uniform. With layers each element takes its layers' modulus and
  /// young_modulus is the reference modulus of reports.
  std::vector<TissueLayer> layers;
  /// tissue.skin: the skin as a membrane on the surface (fem_membrane.h); none by default.
  SkinSpec skin;
  std::vector<Inclusion> inclusions;
  std::string backend = "auto";       // "auto" | "cpu" | "cuda"
  SimParams params;
  std::vector<FingerPath> fingers;    // 1..5
  double duration = 1.0;              // s
  std::vector<ScenarioMark> marks;    // a scripted trainee's marks, in time order
};

/// Largest tumour/tissue Young's modulus ratio (either way) a scenario may ask for: the
/// stability bound measured by `palpation stress` (docs/stability.md).
inline constexpr double kMaxStiffnessContrast = 10000.0;
/// Most layers a tissue may have.
inline constexpr std::size_t kMaxLayers = 8;
/// The thickest skin a membrane stands for (m): breast skin is 0.8-3 mm (facts.md); past
/// 5 mm a sheet's bending, which a membrane leaves out, is no longer small.
inline constexpr double kMaxSkinThickness = 0.005;

/// Parses and validates. Throws ScenarioError("FILE: FIELD: reason").
Scenario parse_scenario(const std::string& json_text, const std::string& source_name);
/// Reads a file and parses it. Throws ScenarioError on unreadable files too.
Scenario load_scenario(const std::string& path);
/// Serialises (round-trips through parse_scenario).
std::string scenario_to_json(const Scenario& s);

/// Built-in scenarios: "paper-sweep", "paper-sweep-no-tumour", their layered twins
/// "paper-sweep-layered" and "paper-sweep-layered-no-tumour" (skin, fat, glandular tissue:
/// tissue_layers.h), "hertz", "idle".
std::vector<std::string> builtin_scenario_names();
/// Throws ScenarioError for an unknown name.
Scenario builtin_scenario(const std::string& name);

/// Edge length (m) of a named resolution for a phantom: coarse, paper, fine, xfine.
/// Returns nullopt for an unknown name.
std::optional<double> resolution_edge(const std::string& phantom, const std::string& name);
std::vector<std::string> resolution_names();

/// The edge lengths a mesh may be asked for (patient.resolution, patient.skin_edge, the
/// levels of a convergence study), m: below, Gmsh's meshes outgrow any machine here;
/// above, a breast is a handful of elements.
inline constexpr double kMinEdge = 5e-4;
inline constexpr double kMaxEdge = 0.05;
/// Whether an edge length lies in [kMinEdge, kMaxEdge], and the range as text for messages.
inline bool edge_in_range(double v) { return v >= kMinEdge && v <= kMaxEdge; }
inline constexpr const char* kEdgeRange = "[0.0005, 0.05] m";

}  // namespace palpation::sim
