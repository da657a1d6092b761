// palpation bench --score: the time to score a 5-minute workstation exam, the path
// `palpation score` runs (read the recording, rebuild the patient, score, write the
// report), on a synthetic recording: the scripted trainee's vertical strips on the default
// patient, five fingers, 400 simulation steps a second (the workstation's rate on a 2-core
// CPU), repeated to fill 5 minutes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "cli/bench.h"
#include "cli/exam_report.h"
#include "live/workstation.h"
#include "phantom.h"
#include "simulation.h"
#include "store/output_dir.h"
#include "store/recording.h"
#include "train/score_recording.h"

namespace palpation::app::cli {

namespace fs = std::filesystem;
using clk = std::chrono::steady_clock;

nlohmann::json run_score_bench(const BenchOptions& opt) {
  const double minutes = 5.0, rate = 400.0;
  sim::Scenario sc = live::default_workstation_scenario();
  const sim::Model model = sim::build_scenario_model(sc, sim::patient_mesh(sc));
  const train::SkinMap skin = train::build_skin_map(model);
  const auto strips = train::vertical_strip_exam(skin, {}, {});
  const fs::path dir = fs::temp_directory_path() / ("palpation-bench-score-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "exam.palrec").string();
  const int nsteps = int(minutes * 60 * rate);
  {
    store::RecordingWriter w(path, {{"scenario", nlohmann::json::parse(sim::scenario_to_json(sc))}}, 5);
    const double period = strips.back().t;
    for (int i = 0; i < nsteps; ++i) {
      const double t = i / rate;
      // The strips' sample at this time (looped), each finger 2 cm further along y.
      const double u = std::fmod(t, period);
      const auto it = std::lower_bound(strips.begin(), strips.end(), u, [](const auto& s, double v) { return s.t < v; });
      const train::FingerSample& s = it == strips.end() ? strips.back() : *it;
      store::RecordedStep st;
      st.t = t;
      st.h = 1 / rate;
      st.fingers.resize(5);
      for (int k = 0; k < 5; ++k)
        st.fingers[std::size_t(k)] = {true, s.radius, s.centre + Eigen::Vector3d(0, 0.02 * (k - 1), 0), Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d(0, 0, 2.0)};
      w.add_step(st);
    }
    w.add_event(100.0, "mark", {{"mark", 1}, {"position", {0.125, 0.0, 0.065}}, {"confidence", 1.0}});
    w.close();
  }
  const double mb = double(fs::file_size(path)) / 1e6;
  std::vector<double> read_ms, score_ms, report_ms;
  const int reps = opt.quick ? 3 : 5;
  int samples = 0;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = clk::now();
    const store::Recording rec = store::read_recording(path);
    const auto t1 = clk::now();
    const train::ScoredExam e = train::score_recording(rec);
    const auto t2 = clk::now();
    write_exam_report(e, (dir / "report").string(), {path, "", "bench", ""});
    const auto t3 = clk::now();
    samples = e.samples;
    read_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    score_ms.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    report_ms.push_back(std::chrono::duration<double, std::milli>(t3 - t2).count());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  nlohmann::json j = {{"recording_minutes", minutes}, {"steps", nsteps}, {"fingers", 5}, {"recording_mb", mb},
                      {"samples_scored", samples}, {"repeats", reps},
                      {"read_ms_median", median(read_ms)}, {"score_ms_median", median(score_ms)},
                      {"report_ms_median", median(report_ms)},
                      {"total_ms_median", median(read_ms) + median(score_ms) + median(report_ms)}};
  std::printf("bench --score: 5-minute exam (%d steps x 5 fingers, %.0f MB): read %.0f ms, score %.0f ms (%d samples), "
              "report %.0f ms; %.2f s in all (medians of %d)\n",
              nsteps, mb, median(read_ms), median(score_ms), samples, median(report_ms),
              (median(read_ms) + median(score_ms) + median(report_ms)) / 1000, reps);
  if (!opt.out.empty()) {
    store::OutputDir out(opt.out);
    std::ofstream f(out.path("score-bench.json"));
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error(out.path("score-bench.json") + ": write failed");
    out.commit();
  }
  fs::remove_all(dir);
  return j;
}

}  // namespace palpation::app::cli
