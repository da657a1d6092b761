// palpation bench --review FILE: the memory a review of the recording keeps (the review
// window's worker, app/review/review_session.h): re-simulates it to the end, then reports
// the kept frames' bytes (per frame, per minute, extrapolated to 30 minutes), the rest of
// what the review keeps, the process's resident memory, and the time to show a frame
// (playback: the next frame; scrubbing: a frame anywhere).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "cli/bench.h"
#include "review/review_session.h"
#include "store/output_dir.h"

namespace palpation::app::cli {

namespace {

using clk = std::chrono::steady_clock;

// VmRSS and VmHWM of this process, bytes (0 where /proc is not there).
std::pair<double, double> resident_bytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  double rss = 0, hwm = 0;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string key;
    double kb = 0;
    s >> key >> kb;
    if (key == "VmRSS:") rss = kb * 1024;
    else if (key == "VmHWM:") hwm = kb * 1024;
  }
  return {rss, hwm};
}

}  // namespace

nlohmann::json run_review_bench(const BenchOptions& opt, const std::string& recording) {
  const auto [rss0, hwm0] = resident_bytes();
  review::ReviewSession s(recording);
  const auto [rss_read, hwm_read] = resident_bytes();
  const auto t0 = clk::now();
  s.start();
  while (!s.finished()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double resim_s = std::chrono::duration<double>(clk::now() - t0).count();
  if (!s.error().empty()) throw std::runtime_error("review: " + s.error());
  const auto [rss1, hwm1] = resident_bytes();
  const std::size_t frames = s.frame_count();
  if (frames == 0) throw std::runtime_error("review: no frames");
  const std::size_t nodes = s.frame_at(0)->snapshot.positions.size() / 3;
  // Showing frames: playback (every frame in order) and scrubbing (random times).
  auto t1 = clk::now();
  for (std::size_t i = 0; i < frames; ++i) s.frame_at(double(i) * s.frame_period + 1e-9);
  const double play_ms = std::chrono::duration<double, std::milli>(clk::now() - t1).count() / double(frames);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> at(0, s.duration());
  const int scrubs = opt.quick ? 50 : 300;
  t1 = clk::now();
  for (int i = 0; i < scrubs; ++i) s.frame_at(at(rng));
  const double scrub_ms = std::chrono::duration<double, std::milli>(clk::now() - t1).count() / scrubs;
  const auto m = s.memory();
  const auto [rss2, hwm2] = resident_bytes();

  const double minutes = s.duration() / 60;
  const double per_frame = double(m.frames) / double(frames);
  // Frames as they were kept before they were coded: the positions as float and a
  // ReviewFrame with its shared_ptr's control block.
  const double uncoded = double(nodes) * 3 * sizeof(float) + sizeof(review::ReviewFrame) + 32 + 16;
  const double frames_30 = double(m.frames) / minutes * 30;
  // What grows with the recording's length, extrapolated; the rest (geometry, cache) fixed.
  const double kept_30 = double(m.frames + m.resimulation + m.recording) / minutes * 30 + double(m.geometry + m.frame_cache);
  nlohmann::json j = {{"recording", recording},
                      {"duration_s", s.duration()},
                      {"nodes", nodes},
                      {"frames", frames},
                      {"resimulation_s", resim_s},
                      {"bytes_per_frame", per_frame},
                      {"bytes_per_frame_uncoded", uncoded},
                      {"frames_mb_per_minute", double(m.frames) / minutes / 1e6},
                      {"frames_mb_30_min", frames_30 / 1e6},
                      {"uncoded_frames_mb_30_min", uncoded * 30 * 60 * 30 / 1e6},
                      {"memory_mb", {{"frames", m.frames / 1e6}, {"frame_cache", m.frame_cache / 1e6},
                                     {"resimulation", m.resimulation / 1e6}, {"recording", m.recording / 1e6},
                                     {"geometry", m.geometry / 1e6}, {"total", m.total() / 1e6}}},
                      {"review_mb_30_min", kept_30 / 1e6},
                      {"rss_mb", {{"start", rss0 / 1e6}, {"read", rss_read / 1e6}, {"resimulated", rss1 / 1e6},
                                  {"after_showing", rss2 / 1e6}, {"peak", std::max({hwm0, hwm_read, hwm1, hwm2}) / 1e6}}},
                      {"rss_growth_mb_per_minute", (rss2 - rss_read) / minutes / 1e6},
                      {"frame_ms_playback", play_ms},
                      {"frame_ms_scrub", scrub_ms}};
  std::printf("bench --review: %s, %.1f s, %zu nodes, %zu frames (re-simulated in %.0f s)\n", recording.c_str(), s.duration(),
              nodes, frames, resim_s);
  std::printf("  frames: %.0f bytes per frame (uncoded %.0f), %.2f MB per minute, %.0f MB for 30 minutes (uncoded %.0f MB)\n",
              per_frame, uncoded, double(m.frames) / minutes / 1e6, frames_30 / 1e6, uncoded * 54000 / 1e6);
  std::printf("  kept: frames %.1f MB, frame cache %.1f MB, re-simulated forces %.1f MB, recording %.1f MB, geometry %.1f MB: "
              "%.1f MB; 30 minutes: %.0f MB\n",
              m.frames / 1e6, m.frame_cache / 1e6, m.resimulation / 1e6, m.recording / 1e6, m.geometry / 1e6, m.total() / 1e6,
              kept_30 / 1e6);
  std::printf("  RSS: %.0f MB at start, %.0f MB read, %.0f MB re-simulated, %.0f MB after showing frames (peak %.0f MB)\n",
              rss0 / 1e6, rss_read / 1e6, rss1 / 1e6, rss2 / 1e6, std::max({hwm0, hwm_read, hwm1, hwm2}) / 1e6);
  std::printf("  showing a frame: %.3f ms in playback, %.3f ms scrubbing\n", play_ms, scrub_ms);
  if (!opt.out.empty()) {
    store::OutputDir out(opt.out);
    std::ofstream f(out.path("review-bench.json"));
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error(out.path("review-bench.json") + ": write failed");
    out.commit();
  }
  return j;
}

}  // namespace palpation::app::cli
