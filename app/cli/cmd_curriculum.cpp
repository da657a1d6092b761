// palpation curriculum check FILE [--db DB] [--json]
// Curricula (train/curriculum.h, docs/training.md "Cases and curricula"): the file is
// parsed, every generated case generated, every library patient looked up.
#include <cstdio>
#include <map>

#ifdef PALPATION_HAVE_SQL
#include <QCoreApplication>

#include "store/patient_library.h"
#endif

#include "cli/cli.h"
#include "train/curriculum.h"

namespace palpation::app::cli {

namespace {

// The criteria in one line: "sensitivity >= 1.00, false positives <= 1, coverage light >= 90% ..."
std::string criteria_line(const train::PassCriteria& p) {
  std::string s;
  auto add = [&s](const char* fmt, double v) {
    char b[96];
    std::snprintf(b, sizeof b, fmt, v);
    s += (s.empty() ? "" : ", ") + std::string(b);
  };
  if (p.min_sensitivity) add("sensitivity >= %.2f", *p.min_sensitivity);
  if (p.max_false_positives) add("false positives <= %.0f", *p.max_false_positives);
  const char* const formats[] = {"light coverage >= %.0f%%", "medium coverage >= %.0f%%", "deep coverage >= %.0f%%"};
  for (int l = 0; l < train::kLevels; ++l)
    if (p.min_coverage[std::size_t(l)]) add(formats[l], *p.min_coverage[std::size_t(l)] * 100);
  if (p.deep_over_each_tumour && *p.deep_over_each_tumour) s += (s.empty() ? "" : ", ") + std::string("deep pressure over each tumour");
  if (p.max_exam_time) add("exam time <= %.0f s", *p.max_exam_time);
  return s.empty() ? "(no criteria: always passes)" : s;
}

}  // namespace

CommandAction add_curriculum_command(CLI::App& app) {
  auto* sub = app.add_subcommand("curriculum", "Curricula: ordered exam cases with pass criteria");
  sub->require_subcommand(1);
  struct Opts {
    std::string file, db;
    bool json_out = false;
  };
  auto o = std::make_shared<Opts>();
  auto* check = sub->add_subcommand("check", "Validate a curriculum file and list its cases");
  check->add_option("file", o->file, "Curriculum (JSON), e.g. resources/curricula/cbe-basics.json")->required();
  check->add_flag("--json", o->json_out, "As JSON");
#ifdef PALPATION_HAVE_SQL
  check->add_option("--db", o->db, "Patient library the cases' patients must be in: SQLite file or "
                                   "postgresql://user:pass@host:port/db (default: $PALPATION_DB, else the user's data folder)");
#endif

  return [o]() -> int {
    const train::Curriculum c = train::load_curriculum(o->file);
    const std::vector<train::GeneratedCase> generated = train::check_generated(c);
    std::map<std::size_t, train::Difficulty> library_difficulty;  // by case index
#ifdef PALPATION_HAVE_SQL
    {
      int argc = 1;
      char name[] = "palpation";
      char* argv[] = {name, nullptr};
      std::unique_ptr<QCoreApplication> qt;
      if (!QCoreApplication::instance()) qt = std::make_unique<QCoreApplication>(argc, argv);
      try {
        store::PatientLibrary::Options lo;
        lo.db = o->db;
        store::PatientLibrary lib(lo);
        for (std::size_t i = 0; i < c.cases.size(); ++i) {
          if (c.cases[i].generated()) continue;
          const auto p = lib.find(c.cases[i].patient);
          if (!p)
            throw sim::ScenarioError(c.source + ": cases[" + std::to_string(i) + "].patient: no patient named \"" +
                                     c.cases[i].patient + "\" in " + lib.location() + " (see `palpation patient list`)");
          // The patient's difficulty, estimated as for generated cases (phantom patients only).
          try {
            if (const auto d = train::scenario_difficulty(sim::parse_scenario(store::patient_scenario(*p).dump(), p->name)))
              library_difficulty[i] = *d;
          } catch (const sim::ScenarioError&) {
          }
        }
      } catch (const store::LibraryError& e) {
        throw sim::ScenarioError(e.what());
      }
    }
#endif
    std::size_t g = 0;
    nlohmann::json cases = nlohmann::json::array();
    for (std::size_t i = 0; i < c.cases.size(); ++i) {
      const auto& cc = c.cases[i];
      nlohmann::json j = {{"name", cc.name()}, {"pass", train::to_json(cc.pass)}};
      if (cc.generated()) {
        const auto& gc = generated[g++];
        j["seed"] = *cc.seed;
        j["difficulty"] = gc.difficulty;
        j["difficulty_name"] = train::difficulty_name(gc.difficulty);
        j["tumours"] = gc.tumours.size();
      } else {
        j["patient"] = cc.patient;
        if (const auto it = library_difficulty.find(i); it != library_difficulty.end()) {
          j["difficulty"] = it->second.grade;
          j["difficulty_name"] = train::difficulty_name(it->second.grade);
        }
      }
      cases.push_back(j);
    }
    if (o->json_out) {
      std::printf("%s\n", nlohmann::json({{"name", c.name}, {"description", c.description}, {"cases", cases}}).dump(2).c_str());
      return kExitOk;
    }
    std::printf("%s: curriculum \"%s\", %zu cases, valid\n", c.source.c_str(), c.name.c_str(), c.cases.size());
    for (std::size_t i = 0; i < c.cases.size(); ++i) {
      const auto& j = cases[i];
      std::string kind = j.contains("seed") ? "generated" : "library patient";
      if (j.contains("difficulty"))
        kind += ", difficulty " + std::to_string(j["difficulty"].get<int>()) + " (" + j["difficulty_name"].get<std::string>() + ")";
      std::printf("%2zu. %-34s %s\n    pass: %s\n", i + 1, c.cases[i].name().c_str(), kind.c_str(),
                  criteria_line(c.cases[i].pass).c_str());
    }
    return kExitOk;
  };
}

}  // namespace palpation::app::cli
