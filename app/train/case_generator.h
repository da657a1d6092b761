// Generated exam cases (docs/training.md, "Cases and curricula"): from a seed and ranges,
// a breast phantom with 0 to 3 hidden tumours, as a sim::Scenario. Qt-free.
//
// Repeatable on any machine: the seed drives std::mt19937_64 (its output sequence is fixed
// by the C++ standard), integers are mapped to ranges here (not by std::uniform_*_distribution,
// whose results are implementation-defined), every length is drawn on a 0.1 mm grid and
// every modulus is a whole number of pascals, and the placement tests use only +, -, *, /
// and sqrt (correctly rounded in IEEE arithmetic; the file is compiled without contracting
// multiply-adds). The same seed and ranges give a byte-identical scenario_to_json.
//
// The case's name for trainees says nothing of its tumours ("Generated case 1234"); its
// difficulty grade is for the instructor and the curriculum.
//
// The tissue is layered as the built-in breasts are (sim::breast_layers: subcutaneous fat
// over glandular tissue, scaled so that the fat has the ranges' tissue modulus), and a
// tumour's hardness is against the layer around its centre: a tumour 5x the tissue is 5x
// the fat it sits in near the skin and 5x the gland deeper down, which is what a finger
// compares it with.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenario.h"

namespace palpation::app::train {

/// What a generated case may hold. Lengths m, moduli Pa; every range is [min, max].
struct CaseRanges {
  int tumours_min = 0, tumours_max = 3;
  double diameter_min = 0.003, diameter_max = 0.02;  // m, largest diameter of a tumour
  /// Tissue over the tumour: skin above the tumour's centre (vertically) to its top, m
  /// (the scorer's TumourTruth::depth).
  double depth_min = 0.003, depth_max = 0.03;
  double hardness_min = 2.0, hardness_max = 13.0;    // tumour / its layer's Young's modulus
  double base_radius_min = 0.06, base_radius_max = 0.088;  // m (the library's small to large breasts)
  double height_min = 0.045, height_max = 0.077;     // m
  /// Chance that a tumour is an ellipsoid (axis-aligned, the two shorter radii 0.6 to 1
  /// times the longest) rather than a sphere.
  double ellipsoid_fraction = 0.25;
  double tissue_young = 19000.0;                     // Pa, the fat layer's (the paper's, Krouskop's fat)
  std::string resolution = "paper";                  // the scenario's mesh resolution level

  // Bounds on the ranges themselves (what a curriculum may ask for).
  static constexpr int kMaxTumours = 3;
  static constexpr double kMinDiameter = 0.002, kMaxDiameter = 0.03;
  static constexpr double kMinDepth = 0.002, kMaxDepth = 0.05;
  static constexpr double kMinHardness = 1.5;        // below, the scorer's tumour rule (1.2x) is too close
  // Above, no published lesion: invasive ductal carcinoma reaches 460-558 kPa against fat's
  // 20-24 kPa at 15 % precompression (docs/training.md), about 25x; the simulation itself
  // handles up to sim::kMaxStiffnessContrast.
  static constexpr double kMaxHardness = 30;
  static constexpr double kMinBaseRadius = 0.05, kMaxBaseRadius = 0.1;
  static constexpr double kMinHeight = 0.035, kMaxHeight = 0.09;
};

/// Clearances kept by every generated case, m.
inline constexpr double kSkinClearance = 0.002;       // tumour surface to skin, along the normal
inline constexpr double kChestWallClearance = 0.003;  // tumour bottom to the chest wall (z = 0)
inline constexpr double kTumourGap = 0.003;           // between two tumours' bounding spheres

/// Ranges from JSON: {"tumours": [0, 3], "diameter": [0.003, 0.02], "depth": [..],
/// "hardness": [2, 13], "base_radius": [..], "height": [..], "ellipsoid_fraction": 0.25,
/// "tissue_young_modulus": 19000, "resolution": "paper"}; missing keys keep `base`.
/// Throws sim::ScenarioError "SOURCE: FIELD.key: reason" (field: the object's path, e.g.
/// "cases[2].generate.ranges").
CaseRanges ranges_from_json(const nlohmann::json& j, const std::string& source, const std::string& field,
                            const CaseRanges& base = {});
nlohmann::json to_json(const CaseRanges& r);
/// Throws sim::ScenarioError naming the field when a range is empty, reversed or out of bounds.
void validate(const CaseRanges& r, const std::string& source, const std::string& field);

/// One generated tumour as the instructor sees it.
struct GeneratedTumour {
  double diameter = 0;     // m, largest
  double depth = 0;        // m, tissue over its top (vertical)
  double hardness = 0;     // x the tissue of the layer around its centre
  double detection = 0;    // estimated chance a trained examiner finds it (see estimate_detection)
};

struct GeneratedCase {
  std::uint64_t seed = 0;
  CaseRanges ranges;
  std::string name;        // "Generated case SEED": nothing of its tumours
  sim::Scenario scenario;  // breast phantom, inclusions, a press over the apex
  std::vector<GeneratedTumour> tumours;
  /// Estimated chance that a trained examiner finds every tumour (product over tumours;
  /// 0.94 without tumours: the pooled clinical specificity, Barton 1999).
  double detection = 1;
  int difficulty = 1;      // 1 (very easy) .. 5 (very hard), from `detection`
};

/// The case of `seed` within `ranges` (validated first). Throws sim::ScenarioError when the
/// ranges leave no room for the tumours (after a fixed number of tries, so also repeatable).
GeneratedCase generate_case(std::uint64_t seed, const CaseRanges& ranges = {}, const std::string& source = "case");

/// "Generated case SEED".
std::string generated_case_name(std::uint64_t seed);

/// Estimated detection chance of one tumour by a trained examiner, 0..1, interpolated from
/// published figures (facts.md): size on silicone models (0.3 cm 14%, 1 cm 87%, 2 cm 99.6%
/// superficial; Pugh), depth (2 cm deep 60-75% against 99.6% superficial; Pugh), hardness
/// (deep hard 75% against deep firm 60%; hard lumps are found more than soft).
double estimate_detection(double diameter, double depth, double hardness);
/// 1..5 from an estimated chance of finding every tumour: >= 0.85, 0.65, 0.45, 0.25, below.
int difficulty_grade(double detection);
/// "very easy", "easy", "moderate", "hard", "very hard".
const char* difficulty_name(int grade);

/// The tissue's Young's modulus around a point `depth` m below the skin: the layer's there,
/// or the uniform tissue's where the scenario has no layers.
double surrounding_modulus(const sim::Scenario& s, double depth);

/// Estimated detection chance and grade of any breast-phantom scenario (a library patient,
/// a generated case): each inclusion stiffer than 1.2x the tissue around its centre (the
/// scorer's tumour rule) is a tumour of its largest diameter, the tissue over it
/// (vertically, on the dome) and its hardness against that tissue. Other phantoms and
/// meshes: nothing.
struct Difficulty {
  double detection = 1;
  int grade = 1;
};
std::optional<Difficulty> scenario_difficulty(const sim::Scenario& s);

/// {"name", "seed", "difficulty", "difficulty_name", "detection", "ranges"} and, with
/// `answer`, "tumours" (for the instructor; never shown to a trainee during an exam).
nlohmann::json case_summary(const GeneratedCase& c, bool answer);

}  // namespace palpation::app::train
