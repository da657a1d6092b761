// palpation trainee add NAME | list | progress NAME [--json] [--curriculum FILE]
// Trainees and their exam results in the patient library (docs/training.md "Trainees and
// progress"); --db or $PALPATION_DB choose the database.
#include <algorithm>
#include <cstdio>

#include <QCoreApplication>

#include "cli/cli.h"
#include "store/patient_library.h"
#include "train/curriculum.h"

namespace palpation::app::cli {

using store::ExamResult;
using store::LibraryError;
using store::PatientLibrary;

namespace {

nlohmann::json result_json(const ExamResult& r) {
  auto opt = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"id", r.id},
          {"trainee", r.trainee},
          {"case", r.case_name},
          {"curriculum", r.curriculum},
          {"started", r.started},
          {"duration_s", r.duration},
          {"sensitivity", opt(r.sensitivity)},
          {"false_positives", r.false_positives},
          {"coverage", {{"light", r.coverage_light}, {"medium", r.coverage_medium}, {"deep", r.coverage_deep}}},
          {"deep_reached", opt(r.deep_reached)},
          {"exam_time_s", r.exam_time},
          {"passed", r.passed},
          {"recording", r.recording},
          {"score", r.score}};
}

std::string opt_text(const std::optional<double>& v, const char* fmt) {
  if (!v) return "-";
  char b[32];
  std::snprintf(b, sizeof b, fmt, *v);
  return b;
}

// "2026-11-24 05:12" from "2026-11-24T05:12:33Z".
std::string short_time(const std::string& t) { return t.size() >= 16 ? t.substr(0, 10) + " " + t.substr(11, 5) : t; }

}  // namespace

CommandAction add_trainee_command(CLI::App& app) {
  auto* sub = app.add_subcommand("trainee", "Trainees and their exam results: add, list, progress");
  sub->require_subcommand(1);
  struct Opts {
    std::string db, name, curriculum;
    bool json_out = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("--db", o->db, "Database: SQLite file or postgresql://user:pass@host:port/db "
                                 "(default: $PALPATION_DB, else the user's data folder)");
  auto* add = sub->add_subcommand("add", "Add a trainee");
  add->add_option("name", o->name, "Trainee's name (unique)")->required();
  auto* list = sub->add_subcommand("list", "The class: each trainee's exams, passes, latest and best result");
  list->add_flag("--json", o->json_out, "As JSON");
  auto* progress = sub->add_subcommand("progress", "A trainee's exams over time");
  progress->add_option("name", o->name, "Trainee's name")->required();
  progress->add_flag("--json", o->json_out, "As JSON");
  progress->add_option("--curriculum", o->curriculum, "Curriculum file: also say which of its cases are passed and which comes next");
  for (auto* c : {add, list, progress})
    c->add_option("--db", o->db, "Database: SQLite file or postgresql://user:pass@host:port/db");

  return [o, add, list, progress]() -> int {
    int argc = 1;
    char name[] = "palpation";
    char* argv[] = {name, nullptr};
    std::unique_ptr<QCoreApplication> qt;  // QtSql loads its drivers as plugins
    if (!QCoreApplication::instance()) qt = std::make_unique<QCoreApplication>(argc, argv);
    try {
      // A curriculum is read before the library is touched: a bad file changes nothing.
      std::optional<train::Curriculum> cur;
      if (progress->parsed() && !o->curriculum.empty()) cur = train::load_curriculum(o->curriculum);
      PatientLibrary::Options lo;
      lo.db = o->db;
      PatientLibrary lib(lo);
      if (add->parsed()) {
        lib.add_trainee(o->name);
        std::printf("added trainee \"%s\" to %s\n", o->name.c_str(), lib.location().c_str());
        return kExitOk;
      }
      if (list->parsed()) {
        const auto v = lib.class_summary();
        if (o->json_out) {
          nlohmann::json a = nlohmann::json::array();
          for (const auto& s : v)
            a.push_back({{"name", s.trainee.name},
                         {"created", s.trainee.created},
                         {"exams", s.exams},
                         {"passed", s.passed},
                         {"latest", s.latest ? result_json(*s.latest) : nlohmann::json(nullptr)},
                         {"best", s.best ? result_json(*s.best) : nlohmann::json(nullptr)}});
          std::printf("%s\n", a.dump(2).c_str());
          return kExitOk;
        }
        std::printf("# %s: %zu trainee%s\n", lib.location().c_str(), v.size(), v.size() == 1 ? "" : "s");
        std::printf("%-24s %5s %6s  %-40s  %s\n", "trainee", "exams", "passed", "latest", "best");
        for (const auto& s : v) {
          auto brief = [](const std::optional<ExamResult>& r) {
            if (!r) return std::string("-");
            return short_time(r->started) + " " + r->case_name + (r->passed ? " pass" : " fail");
          };
          std::printf("%-24s %5d %6d  %-40s  %s\n", s.trainee.name.c_str(), s.exams, s.passed, brief(s.latest).c_str(),
                      brief(s.best).c_str());
        }
        return kExitOk;
      }
      // progress
      const auto results = lib.results(o->name);
      const std::vector<std::string> passed_cases = train::passed_case_names(results, cur ? &*cur : nullptr);
      std::optional<std::size_t> next;
      if (cur) next = train::next_case(*cur, passed_cases);
      if (o->json_out) {
        nlohmann::json a = nlohmann::json::array();
        for (const auto& r : results) a.push_back(result_json(r));
        nlohmann::json j = {{"trainee", o->name}, {"results", a}};
        if (cur) {
          nlohmann::json cases = nlohmann::json::array();
          for (const auto& c : cur->cases)
            cases.push_back({{"name", c.name()},
                             {"passed", std::find(passed_cases.begin(), passed_cases.end(), c.name()) != passed_cases.end()}});
          j["curriculum"] = {{"name", cur->name}, {"cases", cases},
                             {"next", next ? nlohmann::json(cur->cases[*next].name()) : nlohmann::json(nullptr)}};
        }
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
      }
      std::printf("# %s: %zu exam%s\n", o->name.c_str(), results.size(), results.size() == 1 ? "" : "s");
      std::printf("%-16s  %-32s %-16s %7s %5s %3s %5s %5s %5s %5s  %s\n", "started (UTC)", "case", "curriculum", "time s",
                  "sens", "FP", "light", "med", "deep", "deep@", "result");
      for (const auto& r : results)
        std::printf("%-16s  %-32s %-16s %7.0f %5s %3d %4.0f%% %4.0f%% %4.0f%% %5s  %s\n", short_time(r.started).c_str(),
                    r.case_name.c_str(), r.curriculum.empty() ? "-" : r.curriculum.c_str(), r.exam_time,
                    opt_text(r.sensitivity, "%.2f").c_str(), r.false_positives, r.coverage_light * 100, r.coverage_medium * 100,
                    r.coverage_deep * 100, opt_text(r.deep_reached, "%.2f").c_str(), r.passed ? "pass" : "fail");
      if (cur) {
        std::size_t done = 0;
        for (const auto& c : cur->cases)
          if (std::find(passed_cases.begin(), passed_cases.end(), c.name()) != passed_cases.end()) ++done;
        std::printf("curriculum \"%s\": %zu of %zu cases passed; next: %s\n", cur->name.c_str(), done, cur->cases.size(),
                    next ? (std::to_string(*next + 1) + ". " + cur->cases[*next].name()).c_str() : "none (all passed)");
      }
      return kExitOk;
    } catch (const LibraryError& e) {
      throw sim::ScenarioError(e.what());
    }
  };
}

}  // namespace palpation::app::cli
