// palpation score RECORDING --out DIR: scores an exam from a session recording (any
// version: the workstation's, `palpation session`'s) and writes DIR/score.json and the
// report (docs/training.md).
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "cli/cli.h"
#include "cli/exam_report.h"
#include "store/recording.h"
#include "train/curriculum.h"
#include "train/score_recording.h"
#include "cli/plot_png.h"
#ifdef PALPATION_HAVE_SQL
#include "store/patient_library.h"
#endif

namespace palpation::app::cli {

using store::Recording;

namespace {
std::string now_iso() {
  const std::time_t t = std::time(nullptr);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return b;
}
}  // namespace

CommandAction add_score_command(CLI::App& app) {
  auto* sub = app.add_subcommand("score", "Score an exam from a session recording: coverage at each pressure level, "
                                          "search pattern, tumours found, false positives; writes DIR/score.json and the "
                                          "report (report.html, report.pdf, coverage.png, forces.png)");
  struct Opts {
    std::string recording, out, thresholds, trainee, case_name, db, curriculum;
    int curriculum_case = 0;
    bool partial = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("recording", o->recording, "Recording (.palrec)")->required();
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_option("--thresholds", o->thresholds,
                  "Pressure-level thresholds: a JSON file with any of light_depth, medium_depth, deep_depth (fractions "
                  "of the tissue thickness) and light_force, medium_force, deep_force (N); default: those the "
                  "recorded session used");
  sub->add_option("--trainee", o->trainee, "Trainee's name for the report");
  sub->add_option("--case", o->case_name, "Case name for the report");
  sub->add_flag("--partial", o->partial, "Score what an interrupted recording holds (the file is not changed)");
#ifdef PALPATION_HAVE_SQL
  sub->add_option("--db", o->db, "Library (SQLite file or postgresql://...): store the result under --trainee");
  sub->add_option("--curriculum", o->curriculum, "Curriculum file: judge the exam by the pass criteria of --curriculum-case");
  sub->add_option("--curriculum-case", o->curriculum_case, "The curriculum's case (1, 2, ...) this exam was")->check(CLI::PositiveNumber);
#endif
  return [o]() {
    Recording rec = read_recording_arg(o->recording);
    // The thresholds the session ran with, unless the command names others.
    train::PressureThresholds th;
    if (o->thresholds.empty()) {
      try {
        th = train::recorded_thresholds(rec);
      } catch (const std::invalid_argument& e) {
        throw sim::ScenarioError(e.what());
      }
    } else {
      std::ifstream in(o->thresholds);
      if (!in) throw sim::ScenarioError(o->thresholds + ": (file): cannot be read");
      std::stringstream ss;
      ss << in.rdbuf();
      try {
        th = train::thresholds_from_json(nlohmann::json::parse(ss.str()));
      } catch (const nlohmann::json::exception& e) {
        throw sim::ScenarioError(o->thresholds + ": (syntax): " + e.what());
      } catch (const std::invalid_argument& e) {
        throw sim::ScenarioError(o->thresholds + ": " + e.what());
      }
    }
    if (o->partial && !rec.complete) {
      std::fprintf(stderr, "score: %s was interrupted (%s): scoring the %.1f s it holds\n", rec.path.c_str(),
                   rec.interrupted.c_str(), rec.duration());
      rec.complete = true;
    }
#ifdef PALPATION_HAVE_SQL
    // The library is checked before anything is written: an unknown trainee or a bad
    // curriculum changes nothing.
    std::optional<train::Curriculum> cur;
    if (!o->curriculum.empty()) {
      cur = train::load_curriculum(o->curriculum);
      if (o->curriculum_case < 1 || o->curriculum_case > int(cur->cases.size()))
        throw sim::ScenarioError("--curriculum-case: " + std::to_string(o->curriculum_case) + ": " + o->curriculum + " has " +
                                 std::to_string(cur->cases.size()) + " case(s)");
    }
    std::unique_ptr<store::PatientLibrary> lib;
    if (!o->db.empty()) {
      if (o->trainee.empty()) throw sim::ScenarioError("--db: needs --trainee (whose result to store)");
      ensure_gui_application();  // QtSql loads its drivers as plugins; the report draws text
      store::PatientLibrary::Options lo;
      lo.db = o->db;
      try {
        lib = std::make_unique<store::PatientLibrary>(lo);
        if (!lib->find_trainee(o->trainee))
          throw sim::ScenarioError("--trainee: \"" + o->trainee + "\": no such trainee in " + lib->location() +
                                   " (palpation trainee add NAME --db ...)");
      } catch (const store::LibraryError& e) {
        throw sim::ScenarioError(e.what());
      }
    }
#endif
    train::ScoredExam exam;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      exam = train::score_recording(rec, th);
    } catch (const train::ScoreError& e) {
      throw sim::ScenarioError(e.what());
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ReportInfo info{rec.path, o->trainee, o->case_name, now_iso()};
    const auto files = write_exam_report(exam, o->out, info);
    const train::ExamScore& s = exam.score;
    std::printf("score: %d of %zu tumour(s) found, %d false positive(s); coverage light %.0f%%, medium %.0f%%, deep %.0f%%; "
                "%d vertical strip(s); exam %.1f s (scored %d samples in %.0f ms)\n",
                s.hits, s.tumours.size(), s.false_positives, 100 * s.coverage[0], 100 * s.coverage[1], 100 * s.coverage[2],
                s.pattern.strips, s.exam_time, exam.samples, ms);
    std::string list;
    for (const auto& f : files) list += (list.empty() ? "" : ", ") + f;
    std::printf("score: wrote %s in %s\n", list.c_str(), o->out.c_str());
#ifdef PALPATION_HAVE_SQL
    if (lib) {
      std::optional<train::Evaluation> ev;
      std::string case_name = o->case_name, cur_name;
      if (cur) {
        const train::CurriculumCase& c = cur->cases[std::size_t(o->curriculum_case - 1)];
        ev = train::evaluate(c.pass, s);
        if (case_name.empty()) case_name = c.name();
        cur_name = cur->name;
      }
      if (case_name.empty()) case_name = exam.patient;
      store::StoreOutcome stored;
      try {
        // The trainee was checked above; a PostgreSQL server gone meanwhile keeps the result
        // on this machine, sent when the library is next used with the server back.
        stored = lib->store_result(train::exam_result(s, ev, o->trainee, case_name, cur_name, {}, rec.path), false);
      } catch (const store::LibraryError& e) {
        throw sim::ScenarioError(e.what());
      }
      if (stored.id == 0) {
        std::fprintf(stderr, "score: %s\n", stored.message.c_str());
        return kExitOk;
      }
      std::printf("score: stored for %s in %s%s\n", o->trainee.c_str(), lib->location().c_str(),
                  ev ? (ev->passed ? " (passed)" : " (not passed)") : "");
    }
#endif
    return kExitOk;
  };
}

}  // namespace palpation::app::cli
