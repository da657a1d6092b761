// handhiro-emulator: the robot side of the HandHIRO UDP protocol (docs/handhiro-protocol.md)
// with an emulated robot and operator, so that the whole chain runs without hardware.
// The operator's hand follows a scenario's finger paths or a recorded session
// (fingers.csv), starting at the first command received.
//
//   handhiro-emulator --scenario paper-sweep [--port 47001] [--config handhiro.json]
//   handhiro-emulator --recording out/fingers.csv --rigid-hand
//   handhiro-emulator --scenario paper-sweep --loop      # palpates until stopped
//   handhiro-emulator --print-config > resources/handhiro.json
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include <CLI/CLI.hpp>

#include "live/device_bridge.h"
#include "live/device_config.h"
#include "handhiro_emulator.h"
#include "live/haptic_thread.h"
#include "scenario.h"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }
}  // namespace

int main(int argc, char** argv) {
  using namespace palpation;
  namespace dv = palpation::device;
  CLI::App cli{"handhiro-emulator: the HandHIRO robot side of the UDP protocol, emulated (robot, magnet joints, operator)"};
  std::string scenario, recording, config, bind = "127.0.0.1";
  int port = -1, priority = 0;
  double duration = 0, idle_exit = 0;
  bool rigid = false, looped = false, quiet = false, print_config = false;
  auto* src = cli.add_option_group("hand", "What drives the operator's hand");
  src->add_option("--scenario", scenario, "Scenario JSON file or built-in name: its finger paths");
  src->add_option("--recording", recording, "A recorded session's fingers.csv");
  cli.add_option("--config", config, "Device configuration (default: built-in = resources/handhiro.json)");
  cli.add_option("--port", port, "UDP port to listen on (default: link.robot_port of the configuration)")->check(CLI::Range(0, 65535));
  cli.add_option("--bind", bind, "Address to listen on");
  cli.add_flag("--rigid-hand", rigid, "Fingertips follow the path exactly (default: compliant operator fingers)");
  cli.add_flag("--loop", looped, "The hand starts its path over at its end (default: it rests at the last point)");
  cli.add_option("--duration", duration, "Stop after this many seconds (default: run until SIGINT/SIGTERM)");
  cli.add_option("--exit-after-idle", idle_exit, "Stop when no command arrived for this many seconds after the first");
  cli.add_option("--priority", priority, "SCHED_FIFO priority of the 1 kHz thread (0: normal)")->check(CLI::Range(0, 99));
  cli.add_flag("--quiet", quiet, "No statistics on stderr");
  cli.add_flag("--print-config", print_config, "Print the built-in device configuration as JSON and exit");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.exit(e);
    return rc == 0 ? 0 : 2;
  }
  try {
    app::live::DeviceConfig cfg = config.empty() ? app::live::default_device_config() : app::live::load_device_config(config);
    if (print_config) {
      std::printf("%s\n", app::live::device_config_to_json(cfg).dump(2).c_str());
      return 0;
    }
    if (scenario.empty() == recording.empty()) {
      std::fprintf(stderr, "handhiro-emulator: give exactly one of --scenario and --recording\n");
      return 2;
    }
    dv::HandScript script;
    if (!scenario.empty()) {
      sim::Scenario s;
      bool builtin = false;
      for (const auto& n : sim::builtin_scenario_names())
        if (scenario == n || scenario == "builtin:" + n) {
          s = sim::builtin_scenario(n);
          builtin = true;
        }
      if (!builtin) s = sim::load_scenario(scenario);
      script = app::live::script_from_scenario(s, cfg.hand.registration, cfg.finger_map);
    } else {
      std::vector<std::vector<dv::PathKey>> rec;
      try {
        rec = dv::load_fingers_csv(recording);
      } catch (const std::runtime_error& e) {
        throw sim::ScenarioError(e.what());
      }
      for (std::size_t k = 0; k < rec.size(); ++k) {
        if (rec[k].empty()) continue;
        for (auto& key : rec[k]) key.p = cfg.hand.registration.to_device(key.p);
        script.set_path(cfg.finger_map[k], std::move(rec[k]));
      }
    }
    dv::EmulatorOptions eo;
    eo.bind_address = bind;
    eo.port = std::uint16_t(port >= 0 ? port : cfg.link.robot_port);
    eo.rigid_hand = rigid;
    eo.looped = looped;
    dv::HandHiroEmulator emu(cfg.hand, std::move(script), eo);
    std::string err;
    if (!emu.open(&err)) {
      std::fprintf(stderr, "handhiro-emulator: %s\n", err.c_str());
      return 1;
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    if (!quiet) std::fprintf(stderr, "handhiro-emulator: listening on %s:%u\n", bind.c_str(), unsigned(emu.port()));
    std::atomic<std::int64_t> last_cmd_ns{0};
    std::atomic<std::uint64_t> commands{0};
    app::live::PeriodicThread thread;
    thread.start(1000000, priority, [&](std::int64_t now, std::int64_t) {
      emu.tick(now);
      const auto c = emu.counters().commands;
      if (c != commands.load(std::memory_order_relaxed)) {
        commands.store(c, std::memory_order_relaxed);
        last_cmd_ns.store(now, std::memory_order_relaxed);
      }
    });
    const auto t0 = std::chrono::steady_clock::now();
    while (!g_stop) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (duration > 0 && el >= duration) break;
      const std::int64_t last = last_cmd_ns.load(std::memory_order_relaxed);
      if (idle_exit > 0 && last > 0 && double(dv::monotonic_ns() - last) * 1e-9 > idle_exit) break;
    }
    thread.stop();
    if (!quiet) {
      const auto& c = emu.counters();
      const auto& r = emu.robot().counters();
      std::fprintf(stderr,
                   "handhiro-emulator: %llu ticks, %llu commands (%llu lost, %llu duplicate, %llu late, %llu corrupt, "
                   "%llu non-finite refused, %llu above the limit), largest force %.3f N, %llu watchdog events, "
                   "%llu releases, %llu re-attaches (%s)\n",
                   (unsigned long long)c.ticks, (unsigned long long)c.commands, (unsigned long long)c.lost,
                   (unsigned long long)c.duplicates, (unsigned long long)c.late, (unsigned long long)c.corrupt,
                   (unsigned long long)c.refused_nonfinite, (unsigned long long)c.over_limit, c.max_force_received,
                   (unsigned long long)c.watchdog_events, (unsigned long long)r.releases, (unsigned long long)r.reattaches,
                   thread.realtime().policy.c_str());
    }
    return 0;
  } catch (const sim::ScenarioError& e) {
    std::fprintf(stderr, "handhiro-emulator: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "handhiro-emulator: error: %s\n", e.what());
    return 1;
  }
}
