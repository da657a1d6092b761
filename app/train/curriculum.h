// Curricula (docs/training.md, "Cases and curricula"): an ordered list of exam cases, each
// a library patient or a generated case, with the criteria an exam of it must meet to pass.
// Qt-free: the library's patients are named here, looked up by the caller.
//
// File format (JSON; keys starting with "_" are comments):
//   {"name": "CBE basics", "description": "...",
//    "pass": {...},                                   default criteria for every case
//    "cases": [{"patient": "tumour-2.0cm-superficial-hard", "pass": {...}},
//              {"generate": {"seed": 1234, "ranges": {...}}, "pass": {...}}, ...]}
//   pass: {"min_sensitivity": 0..1, "max_false_positives": N,
//          "min_coverage": {"light": 0..1, "medium": 0..1, "deep": 0..1},
//          "deep_over_each_tumour": true, "max_exam_time": SECONDS}
// A case's "pass" overrides the curriculum's key by key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/patient_library.h"  // ExamResult (a plain struct: no Qt here)
#include "train/case_generator.h"
#include "train/exam.h"

namespace palpation::app::train {

/// What an exam must reach to pass; an absent criterion is not checked.
struct PassCriteria {
  std::optional<double> min_sensitivity;               // 0..1 (cases without tumours: not applicable)
  std::optional<int> max_false_positives;
  std::array<std::optional<double>, kLevels> min_coverage;  // light, medium, deep: skin fractions 0..1
  std::optional<bool> deep_over_each_tumour;           // deep pressure reached over every tumour
  std::optional<double> max_exam_time;                 // s, first contact to the end
};

struct CurriculumCase {
  std::string patient;                 // a library patient's name, or empty for a generated case
  std::optional<std::uint64_t> seed;   // a generated case
  CaseRanges ranges;                   // its ranges
  PassCriteria pass;                   // the curriculum's defaults with the case's own on top
  /// The library patient's name, or "Generated case SEED": what results are recorded under.
  std::string name() const;
  bool generated() const { return seed.has_value(); }
};

struct Curriculum {
  std::string source;                  // the file (for messages)
  std::string name;                    // from the file, else the file's stem
  std::string description;
  std::vector<CurriculumCase> cases;
};

/// Parses and validates. Throws sim::ScenarioError "SOURCE: FIELD: reason", e.g.
/// "cbe.json: cases[2].pass.min_sensitivity: must be within 0..1, got 1.5". Generated
/// cases' ranges are checked; whether the ranges leave room for the tumours of a seed is
/// known only by generating it (check_generated).
Curriculum parse_curriculum(const std::string& json_text, const std::string& source);
/// Reads a file and parses it; an unreadable file is a ScenarioError too.
Curriculum load_curriculum(const std::string& path);
/// Generates every generated case once (ScenarioError naming the case on failure).
std::vector<GeneratedCase> check_generated(const Curriculum& c);

nlohmann::json to_json(const PassCriteria& p);

/// One criterion's outcome, e.g. {"min_sensitivity", false, "sensitivity 0.50 < 1.00: 1 of 2
/// tumours found"}.
struct CriterionResult {
  std::string criterion;               // the pass key: "min_sensitivity", "min_coverage.deep", ...
  bool passed = false;
  std::string detail;                  // one English line: the figure against the bound
};

struct Evaluation {
  bool passed = true;                  // every criterion passed
  std::vector<CriterionResult> criteria;
  std::vector<std::string> failed() const;   // the failed criteria's details
};

/// The score against the criteria, in the order of PassCriteria's fields.
Evaluation evaluate(const PassCriteria& p, const ExamScore& s);
nlohmann::json to_json(const Evaluation& e);

/// The library's record of an exam (store::ExamResult): the score's figures as columns,
/// the whole score as JSON with the evaluation under "evaluation"; passed when the
/// evaluation passed (a free exam, without one, is recorded as not passed). `started`: UTC
/// "YYYY-MM-DDTHH:MM:SSZ", empty for now.
store::ExamResult exam_result(const ExamScore& s, const std::optional<Evaluation>& evaluation, const std::string& trainee,
                              const std::string& case_name, const std::string& curriculum, const std::string& started = {},
                              const std::string& recording = {});

/// Index of the first case not yet passed, given the names of the cases passed (a trainee's
/// passed results in this curriculum); nothing when every case is passed.
std::optional<std::size_t> next_case(const Curriculum& c, const std::vector<std::string>& passed_case_names);
/// The names of the cases a trainee passed (their results, store::PatientLibrary::results),
/// counting only results recorded under curriculum `c` (all passed results when null).
std::vector<std::string> passed_case_names(const std::vector<store::ExamResult>& results, const Curriculum* c);

}  // namespace palpation::app::train
