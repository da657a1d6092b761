// Writes the binary seeds of the fuzz corpora (tests/fuzz/corpus/): encoded HandHIRO
// state/command packets and small .pmesh files. The JSON seeds are the built-in
// scenarios (palpation scenario NAME) and hand-written edge cases.
//   make_seeds CORPUS_DIR
#include <cstdio>
#include <string>

#include "handhiro_protocol.h"
#include "mesh.h"
#include "model_cache.h"
#include "store/recording.h"
#include "scenario.h"

namespace pr = palpation::device::protocol;

static void write(const std::string& path, const void* data, std::size_t n) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) { std::perror(path.c_str()); return; }
  std::fwrite(data, 1, n, f);
  std::fclose(f);
}

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "tests/fuzz/corpus";
  std::uint8_t buf[pr::kMaxPacketSize];
  pr::StatePacket s;
  s.header.session = 7;
  s.header.sequence = 42;
  s.header.send_time_ns = 123456789;
  for (int f = 0; f < 5; ++f) {
    s.fingers[f].position = {0.01 * f, 0.02, 0.08};
    s.fingers[f].flags = pr::kFingerAttached | pr::kFingerPresent;
  }
  write(dir + "/protocol/state.bin", buf, pr::encode(s, buf, sizeof buf));
  s.finger_count = 2;
  s.status = pr::kStatusWatchdog;
  write(dir + "/protocol/state-2fingers.bin", buf, pr::encode(s, buf, sizeof buf));
  pr::CommandPacket c;
  c.header.type = pr::PacketType::Command;
  c.header.sequence = 9;
  c.flags = pr::kCommandEnable;
  c.fingers[0].force = {0.5, 0, 1.5};
  c.fingers[0].enabled = true;
  write(dir + "/protocol/command.bin", buf, pr::encode(c, buf, sizeof buf));

  using palpation::sim::make_box_mesh;
  auto box = make_box_mesh(Eigen::Vector3d(0.1, 0.1, 0.05), 1, 1, 1);
  palpation::sim::save_mesh_cache(dir + "/model_cache/box-1.pmesh", box, "seed");
  box = make_box_mesh(Eigen::Vector3d(0.1, 0.1, 0.05), 2, 2, 1);
  palpation::sim::save_mesh_cache(dir + "/model_cache/box-2.pmesh", box, "seed");

  for (const auto& name : palpation::sim::builtin_scenario_names()) {
    const std::string j = palpation::sim::scenario_to_json(palpation::sim::builtin_scenario(name));
    if (j.size() > 4096) continue;  // the paper sweeps (128 KB of keyframes) slow fuzzing down
    write(dir + "/scenario/" + name + ".json", j.data(), j.size());
  }
  {
    nlohmann::json header = {{"scenario", nlohmann::json::parse(palpation::sim::scenario_to_json(
                                              palpation::sim::builtin_scenario("hertz")))}};
    palpation::app::store::RecordingWriter w(dir + "/recording/short.prec", header, 1, 1);
    for (int i = 0; i < 40; ++i) {
      const Eigen::Vector3d x(0.001 * i, 0, 0.05), f(0, 0, 0.01 * i);
      w.add_tick(0.001 * (i + 1), &x, &f);
      if (i == 20) w.add_event(0.021, "mark", {{"note", "seed"}});
    }
    w.close();
  }
  // Version 2: a workstation recording with simulation steps (two fingers); version 3: the
  // same, its ticks and steps compressed.
  for (const std::uint32_t version : {2u, 3u}) {
    nlohmann::json header = {{"scenario", nlohmann::json::parse(palpation::sim::scenario_to_json(
                                              palpation::sim::builtin_scenario("hertz")))}};
    palpation::app::store::RecordingWriter w(
        dir + (version == 2 ? "/recording/steps.prec" : "/recording/steps-v3.prec"), header, 2, version);
    for (int i = 0; i < 12; ++i) {
      const Eigen::Vector3d x[2] = {{0.001 * i, 0, 0.05}, {0, 0.01, 0.06}}, f[2] = {{0, 0, 0.01 * i}, {0, 0, 0}};
      w.add_tick(0.001 * (i + 1), x, f);
      if (i % 4 == 0) {
        palpation::app::store::RecordedStep st;
        st.t = 0.001 * (i + 1);
        st.h = 0.004;
        st.commands_applied = std::uint64_t(i / 4);
        st.fingers.resize(2);
        st.fingers[0] = {true, 0.008, x[0], Eigen::Vector3d(0.1, 0, 0), f[0]};
        st.fingers[1] = {false, 0.008, x[1], Eigen::Vector3d::Zero(), f[1]};
        w.add_step(st);
      }
    }
    w.add_event(0.005, "parameter", {{"command", "young"}, {"index", 0}, {"changes", {{3, 40000.0}}}});
    w.close();
  }
  return 0;
}
