#include "train/curriculum.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "json_reader.h"

namespace palpation::app::train {

using nlohmann::json;
using sim::JsonReader;

namespace {

const char* const kLevelKeys[kLevels] = {"light", "medium", "deep"};

double fraction(const JsonReader& rd, const json& v, const std::string& f) {
  const double d = rd.number(v, f);
  if (d < 0 || d > 1) rd.fail(f, "must be within 0..1, got " + JsonReader::fmt(d));
  return d;
}

PassCriteria parse_pass(const JsonReader& rd, const json& j, const std::string& field, const PassCriteria& base) {
  rd.only_keys(j, field, {"min_sensitivity", "max_false_positives", "min_coverage", "deep_over_each_tumour", "max_exam_time"});
  PassCriteria p = base;
  rd.opt(j, "min_sensitivity", field, [&](const json& v, const std::string& f) { p.min_sensitivity = fraction(rd, v, f); });
  rd.opt(j, "max_false_positives", field,
         [&](const json& v, const std::string& f) { p.max_false_positives = rd.integer(v, f, 0, 1000); });
  rd.opt(j, "min_coverage", field, [&](const json& v, const std::string& f) {
    rd.only_keys(v, f, {"light", "medium", "deep"});
    for (int l = 0; l < kLevels; ++l)
      rd.opt(v, kLevelKeys[l], f, [&](const json& x, const std::string& fl) { p.min_coverage[std::size_t(l)] = fraction(rd, x, fl); });
  });
  rd.opt(j, "deep_over_each_tumour", field, [&](const json& v, const std::string& f) {
    if (!v.is_boolean()) rd.fail(f, "must be true or false");
    p.deep_over_each_tumour = v.get<bool>();
  });
  rd.opt(j, "max_exam_time", field, [&](const json& v, const std::string& f) {
    const double t = rd.positive(v, f);
    if (t > 7200) rd.fail(f, "must be at most 7200 s, got " + JsonReader::fmt(t));
    p.max_exam_time = t;
  });
  return p;
}

std::string percent(double f) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f%%", f * 100.0);
  return b;
}
std::string fixed(double v, int decimals) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

}  // namespace

std::string CurriculumCase::name() const { return seed ? generated_case_name(*seed) : patient; }

Curriculum parse_curriculum(const std::string& text, const std::string& source) {
  const JsonReader rd(source, /*comments=*/true);
  const json j = rd.parse(text);
  rd.only_keys(j, "", {"name", "description", "pass", "cases"});
  Curriculum c;
  c.source = source;
  c.name = j.contains("name") ? rd.string(j["name"], "name") : std::filesystem::path(source).stem().string();
  if (c.name.empty() || c.name.size() > 200) rd.fail("name", "must be 1 to 200 characters");
  if (j.contains("description")) c.description = rd.string(j["description"], "description");
  PassCriteria defaults;
  if (j.contains("pass")) defaults = parse_pass(rd, j["pass"], "pass", {});
  if (!j.contains("cases")) rd.fail("cases", "is required (an array of cases)");
  const json& arr = j["cases"];
  if (!arr.is_array() || arr.empty()) rd.fail("cases", "must be a non-empty array of cases");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string f = "cases[" + std::to_string(i) + "]";
    const json& cj = arr[i];
    rd.only_keys(cj, f, {"patient", "generate", "pass"});
    if (cj.contains("patient") == cj.contains("generate")) rd.fail(f, "give exactly one of \"patient\" (a library patient) or \"generate\"");
    CurriculumCase cc;
    if (cj.contains("patient")) {
      cc.patient = rd.string(cj["patient"], f + ".patient");
      if (cc.patient.empty() || cc.patient.size() > 200) rd.fail(f + ".patient", "must be a patient name (1 to 200 characters)");
    } else {
      const json& g = cj["generate"];
      const std::string gf = f + ".generate";
      rd.only_keys(g, gf, {"seed", "ranges"});
      if (!g.contains("seed")) rd.fail(gf + ".seed", "is required (a whole number >= 0)");
      const json& sd = g["seed"];
      if (!sd.is_number_unsigned() && !(sd.is_number_integer() && sd.get<long long>() >= 0))
        rd.fail(gf + ".seed", "must be a whole number >= 0");
      cc.seed = sd.get<std::uint64_t>();
      if (g.contains("ranges")) cc.ranges = ranges_from_json(g["ranges"], source, gf + ".ranges");
    }
    cc.pass = cj.contains("pass") ? parse_pass(rd, cj["pass"], f + ".pass", defaults) : defaults;
    for (std::size_t k = 0; k < c.cases.size(); ++k)
      if (c.cases[k].name() == cc.name())
        rd.fail(f, "\"" + cc.name() + "\" is already cases[" + std::to_string(k) + "] (results are recorded by case name)");
    c.cases.push_back(std::move(cc));
  }
  return c;
}

Curriculum load_curriculum(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw sim::ScenarioError(path + ": (file): cannot be read (" + std::string(std::strerror(errno)) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_curriculum(ss.str(), path);
}

std::vector<GeneratedCase> check_generated(const Curriculum& c) {
  std::vector<GeneratedCase> v;
  for (std::size_t i = 0; i < c.cases.size(); ++i)
    if (c.cases[i].generated())
      v.push_back(generate_case(*c.cases[i].seed, c.cases[i].ranges, c.source + ": cases[" + std::to_string(i) + "].generate"));
  return v;
}

json to_json(const PassCriteria& p) {
  json j = json::object();
  if (p.min_sensitivity) j["min_sensitivity"] = *p.min_sensitivity;
  if (p.max_false_positives) j["max_false_positives"] = *p.max_false_positives;
  json cov = json::object();
  for (int l = 0; l < kLevels; ++l)
    if (p.min_coverage[std::size_t(l)]) cov[kLevelKeys[l]] = *p.min_coverage[std::size_t(l)];
  if (!cov.empty()) j["min_coverage"] = cov;
  if (p.deep_over_each_tumour) j["deep_over_each_tumour"] = *p.deep_over_each_tumour;
  if (p.max_exam_time) j["max_exam_time"] = *p.max_exam_time;
  return j;
}

std::vector<std::string> Evaluation::failed() const {
  std::vector<std::string> v;
  for (const auto& c : criteria)
    if (!c.passed) v.push_back(c.detail);
  return v;
}

Evaluation evaluate(const PassCriteria& p, const ExamScore& s) {
  Evaluation e;
  auto add = [&](std::string criterion, bool ok, std::string detail) {
    e.criteria.push_back({std::move(criterion), ok, std::move(detail)});
    if (!ok) e.passed = false;
  };
  const std::size_t n = s.tumours.size();
  if (p.min_sensitivity) {
    if (!s.sensitivity || n == 0) {
      add("min_sensitivity", true, "no tumour to find: sensitivity does not apply");
    } else {
      const bool ok = *s.sensitivity >= *p.min_sensitivity;
      add("min_sensitivity", ok,
          "sensitivity " + fixed(*s.sensitivity, 2) + (ok ? " >= " : " < ") + fixed(*p.min_sensitivity, 2) + ": " +
              std::to_string(s.hits) + " of " + std::to_string(n) + " tumour" + (n == 1 ? "" : "s") + " found");
    }
  }
  if (p.max_false_positives) {
    const bool ok = s.false_positives <= *p.max_false_positives;
    add("max_false_positives", ok,
        std::to_string(s.false_positives) + " false positive" + (s.false_positives == 1 ? "" : "s") + (ok ? " <= " : " > ") +
            std::to_string(*p.max_false_positives) + " allowed");
  }
  for (int l = 0; l < kLevels; ++l) {
    const auto& bound = p.min_coverage[std::size_t(l)];
    if (!bound) continue;
    const double got = s.coverage[std::size_t(l)];
    const bool ok = got >= *bound;
    add(std::string("min_coverage.") + kLevelKeys[l], ok,
        std::string(kLevelKeys[l]) + " coverage " + percent(got) + (ok ? " >= " : " < ") + percent(*bound) + " of the skin");
  }
  if (p.deep_over_each_tumour && *p.deep_over_each_tumour) {
    if (n == 0) {
      add("deep_over_each_tumour", true, "no tumour: deep pressure over tumours does not apply");
    } else {
      std::string missed;
      int reached = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (s.tumours[i].deep_reached)
          ++reached;
        else
          missed += (missed.empty() ? "" : ", ") + std::to_string(i + 1);
      }
      const bool ok = missed.empty();
      add("deep_over_each_tumour", ok,
          ok ? "deep pressure reached over every tumour (" + std::to_string(n) + ")"
             : "deep pressure reached over " + std::to_string(reached) + " of " + std::to_string(n) +
                   " tumours (not over tumour " + missed + ")");
    }
  }
  if (p.max_exam_time) {
    const bool ok = s.exam_time <= *p.max_exam_time;
    add("max_exam_time", ok, "exam time " + fixed(s.exam_time, 0) + " s" + (ok ? " <= " : " > ") + fixed(*p.max_exam_time, 0) + " s");
  }
  return e;
}

json to_json(const Evaluation& e) {
  json c = json::array();
  for (const auto& r : e.criteria) c.push_back({{"criterion", r.criterion}, {"passed", r.passed}, {"detail", r.detail}});
  return {{"passed", e.passed}, {"criteria", c}};
}

store::ExamResult exam_result(const ExamScore& s, const std::optional<Evaluation>& evaluation, const std::string& trainee,
                              const std::string& case_name, const std::string& curriculum, const std::string& started,
                              const std::string& recording) {
  store::ExamResult r;
  r.trainee = trainee;
  r.case_name = case_name;
  r.curriculum = curriculum;
  r.started = started;
  r.duration = s.duration;
  r.sensitivity = s.tumours.empty() ? std::nullopt : s.sensitivity;
  r.false_positives = s.false_positives;
  r.coverage_light = s.coverage[0];
  r.coverage_medium = s.coverage[1];
  r.coverage_deep = s.coverage[2];
  if (!s.tumours.empty()) {
    int deep = 0;
    for (const auto& t : s.tumours) deep += t.deep_reached ? 1 : 0;
    r.deep_reached = double(deep) / double(s.tumours.size());
  }
  r.exam_time = s.exam_time;
  r.passed = evaluation && evaluation->passed;
  r.score = to_json(s);
  if (evaluation) r.score["evaluation"] = to_json(*evaluation);
  r.recording = recording;
  return r;
}

std::optional<std::size_t> next_case(const Curriculum& c, const std::vector<std::string>& passed) {
  for (std::size_t i = 0; i < c.cases.size(); ++i) {
    const std::string n = c.cases[i].name();
    if (std::find(passed.begin(), passed.end(), n) == passed.end()) return i;
  }
  return std::nullopt;
}

std::vector<std::string> passed_case_names(const std::vector<store::ExamResult>& results, const Curriculum* c) {
  std::vector<std::string> out;
  for (const auto& r : results)
    if (r.passed && (!c || r.curriculum == c->name)) out.push_back(r.case_name);
  return out;
}

}  // namespace palpation::app::train
