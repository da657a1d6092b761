// palpation session SCENARIO.json --device emulator|scripted|replay --out DIR: the whole
// real-time pipeline, headless (device, 1 kHz haptic thread, simulation thread) for the
// scenario's duration. Writes DIR/fingers.csv (what the device received, as `run`
// writes it) and DIR/loop.json (rates, jitter, overruns, forces, safety events).
#include <climits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "cli/cli.h"
#include "live/device_config.h"
#include "live/headless_run.h"
#include "store/output_dir.h"
#include "store/recording.h"
#include "scenario.h"
#include "live/session.h"

namespace palpation::app::cli {

using live::SessionOptions;
using live::SessionResult;
using live::load_device_config;
using live::run_session;
using live::write_fingers_csv;
using store::OutputDir;
using store::RecordingError;
using store::RecoverResult;
using store::recover_recording;

namespace {

std::string emulator_next_to_self() {
  char buf[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "handhiro-emulator";
  buf[n] = 0;
  return (std::filesystem::path(buf).parent_path() / "handhiro-emulator").string();
}

}  // namespace

CommandAction add_session_command(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "session", "Run the real-time pipeline headless (device, 1 kHz haptic thread, simulation thread); writes "
                 "DIR/fingers.csv and DIR/loop.json");
  struct Opts {
    std::string record;
    std::string scenario, out, device = "emulator", config, coupling, backend, resolution, recording, sim_dt = "realtime", emulator_exe;
    double duration = 0, sim_max_dt = 0.01, vib_from = -1, vib_to = -1, force_error = -1;
    int priority = 80;
    bool rigid = false, no_passivity = false, no_rt = false, process = false, quiet = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("scenario", o->scenario, "Scenario JSON file (or a built-in name)")->required();
  sub->add_option("--device", o->device, "emulator (HandHIRO protocol over loopback UDP), scripted (in-process, "
                                         "follows the paths exactly) or replay (plays --recording)")
      ->check(CLI::IsMember({"emulator", "scripted", "replay"}));
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_option("--device-config", o->config, "Device configuration (default: built-in, = resources/handhiro.json)");
  sub->add_option("--duration", o->duration, "Seconds to run (default: the scenario's duration)");
  sub->add_option("--backend", o->backend, "Override solver.backend (auto, cpu, cuda)")->check(CLI::IsMember({"auto", "cpu", "cuda"}));
  sub->add_option("--resolution", o->resolution, "Override patient.resolution (coarse, paper, fine, xfine)");
  add_force_error_option(sub, o->force_error);
  sub->add_option("--recording", o->recording, "Drive the hand by a recorded fingers.csv instead of the scenario's paths");
  sub->add_flag("--rigid-hand", o->rigid, "Emulator: fingertips follow the path exactly (default: a compliant finger)");
  sub->add_flag("--no-passivity", o->no_passivity, "Switch off the energy (passivity) controller");
  sub->add_option("--coupling", o->coupling, "virtual (default: a spring of the device's stiffness to a simulated "
                                             "proxy) or direct (the local model at the device position)")
      ->check(CLI::IsMember({"virtual", "direct"}));
  sub->add_option("--sim-dt", o->sim_dt, "realtime: the simulation's dt follows the wall clock; fixed: the scenario's dt")
      ->check(CLI::IsMember({"realtime", "fixed"}));
  sub->add_option("--sim-max-dt", o->sim_max_dt, "Largest real-time simulation dt, s")->check(CLI::Range(1e-4, 0.1));
  sub->add_option("--priority", o->priority, "SCHED_FIFO priority of the haptic thread")->check(CLI::Range(1, 99));
  sub->add_flag("--no-rt", o->no_rt, "Do not ask for real-time priority");
  sub->add_flag("--emulator-process", o->process, "Run handhiro-emulator as a child process (default: a thread)");
  sub->add_option("--emulator-exe", o->emulator_exe, "Path of handhiro-emulator (default: next to this program)");
  sub->add_option("--vibration-from", o->vib_from, "Start of the vibration window, s (default: half the duration)");
  sub->add_option("--vibration-to", o->vib_to, "End of the vibration window, s (default: the end)");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  sub->add_option("--record", o->record, "Session recording (default: DIR/session.palrec; an interrupted one left "
                                         "there is recovered first and kept as session-recovered-N.palrec)");
  return [o]() {
    sim::Scenario s = load_scenario_arg(o->scenario, o->backend, o->resolution, o->force_error);
    if (o->duration < 0) throw sim::ScenarioError("--duration: must be > 0");
    SessionOptions opt;
    opt.device = o->device;
    if (!o->config.empty()) {
      opt.config = load_device_config(o->config);
      opt.device_config_path = o->config;
    }
    if (o->no_passivity) opt.config.loop.safety.passivity = false;
    if (!o->coupling.empty()) opt.config.loop.virtual_coupling = o->coupling == "virtual";
    opt.duration = o->duration;
    opt.priority = o->no_rt ? 0 : o->priority;
    opt.rigid_hand = o->rigid;
    opt.recording = o->recording;
    opt.scenario_arg = o->scenario;
    opt.sim_realtime = o->sim_dt == "realtime";
    opt.sim_max_dt = o->sim_max_dt;
    opt.vibration_from = o->vib_from;
    opt.vibration_to = o->vib_to;
    if (o->process) opt.emulator_exe = o->emulator_exe.empty() ? emulator_next_to_self() : o->emulator_exe;
    if (o->process && o->device != "emulator") throw sim::ScenarioError("--emulator-process: only with --device emulator");
    opt.progress = !o->quiet;
    if (!o->quiet) opt.log = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    OutputDir out(o->out);
    // Every session records, straight into DIR (not staged: it must survive a crash).
    opt.record_path = o->record.empty() ? (std::filesystem::path(o->out) / "session.palrec").string() : o->record;
    if (std::filesystem::exists(opt.record_path)) {
      // A recording left by an earlier session: recover it when it was interrupted, then
      // move it aside so that nothing already recorded is overwritten.
      std::string note;
      try {
        const RecoverResult rr = recover_recording(opt.record_path);
        if (!rr.was_complete)
          note = "recovered an interrupted recording (" + std::to_string(rr.duration) + " s kept, " +
                 std::to_string(rr.dropped_bytes) + " torn bytes dropped: " + rr.reason + ")";
      } catch (const RecordingError& e) {
        note = std::string("an unreadable earlier recording is kept as it is: ") + e.what();
      }
      std::string aside;
      for (int i = 1;; ++i) {
        aside = opt.record_path.substr(0, opt.record_path.size() - (opt.record_path.size() > 7 &&
                opt.record_path.substr(opt.record_path.size() - 7) == ".palrec" ? 7 : 0)) +
                (note.empty() ? "-" : "-recovered-") + std::to_string(i) + ".palrec";
        if (!std::filesystem::exists(aside)) break;
      }
      std::filesystem::rename(opt.record_path, aside);
      if (!note.empty()) std::fprintf(stderr, "session: %s -> %s\n", note.c_str(), aside.c_str());
    }
    opt.record_settings = {{"command", "session"}, {"scenario_arg", o->scenario}, {"device_config_path", o->config}};
    SessionResult r = run_session(s, opt);
    write_fingers_csv(out.path("fingers.csv"), r.samples);
    {
      std::ofstream js(out.path("loop.json"));
      js << r.loop.dump(2) << "\n";
      if (!js) throw std::runtime_error(out.path("loop.json") + ": write failed");
    }
    out.commit();
    if (!o->quiet) {
      const auto& h = r.loop["haptic"];
      std::fprintf(stderr,
                   "session: haptic %.1f Hz, jitter p50 %.1f / p99 %.1f / max %.1f us, %llu overruns (%s); "
                   "simulation %.0f steps/s at %.0f %% of real time (dt up to %.2f ms); largest force %.2f N -> %s\n",
                   h["rate_hz"].get<double>(), h["jitter_us"]["p50"].get<double>(), h["jitter_us"]["p99"].get<double>(),
                   h["jitter_us"]["max"].get<double>(), (unsigned long long)h["overruns"].get<std::uint64_t>(),
                   h["scheduling"].get<std::string>().c_str(), r.loop["simulation"]["step_rate_hz"].get<double>(),
                   100 * r.loop["simulation"]["pace"].get<double>(), r.loop["simulation"]["dt_ms_limit"].get<double>(),
                   r.loop["forces"]["largest_sent_n"].get<double>(), o->out.c_str());
    }
    return r.ok ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
