// palpation replay RECORDING --out DIR: re-simulates a session recording from its device
// input with its patient and settings; writes DIR/fingers.csv (as `run` writes it) and
// DIR/summary.json, and prints the largest difference from the recorded forces.
#include <cstdio>
#include <fstream>

#include "cli/cli.h"
#include "store/output_dir.h"
#include "store/recording.h"
#include "review/replay.h"

namespace palpation::app::cli {

using live::write_fingers_csv;
using review::ReplayOptions;
using review::ReplayResult;
using review::replay_recording;
using store::OutputDir;
using store::Recording;

CommandAction add_replay_command(CLI::App& app) {
  auto* sub = app.add_subcommand("replay", "Re-simulate a session recording; writes DIR/fingers.csv and DIR/summary.json "
                                           "and prints the largest difference from the recorded forces");
  struct Opts {
    std::string recording, out, backend;
    bool quiet = false, check = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("recording", o->recording, "Recording (.palrec)")->required();
  sub->add_option("--out", o->out, "Output folder (not needed with --check)");
  sub->add_option("--backend", o->backend, "Override the recorded backend (auto, cpu, cuda)")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}));
  sub->add_flag("--check", o->check, "Only validate the recording and print what it holds");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return [o]() {
    Recording rec = read_recording_arg(o->recording);
    const char* state = rec.complete ? (rec.recovered ? "recovered after an interruption" : "complete") : "interrupted";
    std::printf("recording: %s: version %u, %d finger(s), %zu ticks (%.3f s), %zu events, %s%s%s\n", rec.path.c_str(),
                rec.version, rec.fingers, rec.ticks(), rec.duration(), rec.events.size(), state,
                rec.interrupted.empty() ? "" : ": ", rec.interrupted.c_str());
    if (o->check) return kExitOk;
    if (o->out.empty()) throw sim::ScenarioError("--out: required (or --check)");
    OutputDir out(o->out);
    ReplayOptions opt;
    opt.backend = o->backend;
    opt.progress = !o->quiet;
    if (!o->quiet) opt.log = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    ReplayResult r = replay_recording(rec, opt);
    write_fingers_csv(out.path("fingers.csv"), r.run.samples);
    {
      std::ofstream js(out.path("summary.json"));
      js << r.run.summary.dump(2) << "\n";
      if (!js) throw std::runtime_error(out.path("summary.json") + ": write failed");
    }
    out.commit();
    const std::string backend = r.run.summary["backend"].get<std::string>();
    if (r.compared_force == review::ReplayForce::Simulated) {
      // A workstation recording: its steps re-run exactly; simulated against simulated.
      std::printf("replay: simulated force, every recorded step re-simulated (its dt, fingertip inputs and changes): "
                  "largest difference %.3g N (finger %d at t = %.3f s; largest recorded step force %.3g N) over %zu finger "
                  "steps, backend %s -> %s\n",
                  r.max_force_diff, r.max_diff_finger, r.max_diff_t, r.max_recorded_force, r.compared, backend.c_str(),
                  o->out.c_str());
      std::printf("replay: force sent to the device, the re-simulated steps through the device's force path (force scale "
                  "%.3f %s, local contact model, haptic loop: coupling, fades, safety filter): largest difference %.3g N "
                  "(finger %d at t = %.3f s; largest recorded %.3g N) over %zu finger ticks\n",
                  r.force_scale, r.force_scale_source.c_str(), r.sent.max_diff, r.sent.finger, r.sent.at_t,
                  r.sent.max_recorded_force, r.sent.compared);
    } else {
      std::printf("replay: force sent, re-simulated at the scenario's dt from the recorded fingertip positions, times the "
                  "recorded force scale %.3f: largest difference %.3g N (finger %d at t = %.3f s; largest recorded force "
                  "%.3g N) over %zu finger ticks, backend %s -> %s\n",
                  r.force_scale, r.max_force_diff, r.max_diff_finger, r.max_diff_t, r.max_recorded_force, r.compared,
                  backend.c_str(), o->out.c_str());
      if (rec.header.contains("session"))
        std::printf("replay: note: this session's forces came through the haptic loop (wall-clock dt, virtual coupling, "
                    "safety filter) and it recorded no simulation steps; the headless re-simulation differs by that "
                    "(docs/recording.md)\n");
    }
    return r.run.summary["finite"].get<bool>() ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
