#include "live/device_factory.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <spawn.h>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>

#include "scenario.h"
#include "udp_socket.h"

extern char** environ;

namespace palpation::app::live {

namespace dv = palpation::device;

ChildProcess& ChildProcess::operator=(ChildProcess&& o) noexcept {
  if (this != &o) {
    end();
    pid_ = o.pid_;
    o.pid_ = -1;
  }
  return *this;
}

void ChildProcess::spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int rc = ::posix_spawn(&pid_, args[0].c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    pid_ = -1;
    throw std::runtime_error(args[0] + ": cannot start the emulator (" + std::strerror(rc) + ")");
  }
}

bool ChildProcess::alive() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

void ChildProcess::end() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  int status = 0;
  for (int i = 0; i < 300; ++i) {  // up to 3 s, then SIGKILL
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
}

namespace {
std::unique_ptr<dv::HandHiroLink> open_link(const DeviceConfig& cfg, const dv::LinkConfig& lc) {
  auto link = std::make_unique<dv::HandHiroLink>(cfg.hand.capabilities, lc);
  std::string err;
  if (!link->open(&err)) throw std::runtime_error("link: " + err);
  return link;
}
}  // namespace

DeviceWiring open_device(DeviceRequest r) {
  const auto& caps = r.config.hand.capabilities;
  DeviceWiring w;
  if (r.kind == "simulated" || r.kind == "scripted") {
    std::unique_ptr<dv::ScriptedDevice> d;
    if (r.kind == "simulated") {
      auto hand = std::make_unique<dv::SimulatedHand>(std::move(r.script), caps);
      w.hand = hand.get();
      d = std::move(hand);
      w.description = "simulated HandHIRO";
    } else {
      d = std::make_unique<dv::ScriptedDevice>(std::move(r.script), caps);
      w.description = "scripted hand";
    }
    w.scripted = d.get();
    w.device = std::move(d);
  } else if (r.kind == "replay") {
    std::unique_ptr<dv::ReplayDevice> d;
    try {
      d = std::make_unique<dv::ReplayDevice>(r.recording, r.config.hand.registration, r.config.finger_map, caps);
    } catch (const std::runtime_error& e) {
      throw sim::ScenarioError(e.what());
    }
    w.scripted = d.get();
    w.device = std::move(d);
    w.description = "replay of " + r.recording;
  } else if (r.kind == "emulator") {
    dv::LinkConfig lc = r.config.link;
    lc.robot_address = "127.0.0.1";
    lc.bind_address = "127.0.0.1";
    lc.bind_port = 0;
    std::string err;
    if (r.emulator_command.empty()) {
      dv::EmulatorOptions eo;
      eo.bind_address = "127.0.0.1";
      eo.port = 0;
      eo.rigid_hand = r.rigid_hand;
      eo.looped = r.looped;
      w.emulator = std::make_unique<dv::HandHiroEmulator>(r.config.hand, std::move(r.script), eo);
      if (!w.emulator->open(&err)) throw std::runtime_error("emulator: " + err);
      lc.robot_port = w.emulator->port();
      w.description = "HandHIRO emulator (UDP loopback)";
    } else {
      dv::UdpSocket probe;  // a free loopback port for the child
      if (!probe.open("127.0.0.1", 0, &err)) throw std::runtime_error("emulator: " + err);
      lc.robot_port = probe.local_port();
      probe.close();
      std::vector<std::string> args{r.emulator_command[0], "--port", std::to_string(lc.robot_port)};
      args.insert(args.end(), r.emulator_command.begin() + 1, r.emulator_command.end());
      if (r.looped) args.push_back("--loop");
      w.child.spawn(args);
      w.description = "HandHIRO emulator (child process, UDP loopback)";
    }
    auto link = open_link(r.config, lc);
    w.link = link.get();
    w.device = std::move(link);
  } else if (r.kind == "handhiro") {
    dv::LinkConfig lc = r.config.link;
    if (!r.robot_address.empty()) lc.robot_address = r.robot_address;
    if (r.robot_port > 0) lc.robot_port = std::uint16_t(r.robot_port);
    auto link = open_link(r.config, lc);
    w.link = link.get();
    w.device = std::move(link);
    w.description = "HandHIRO at " + lc.robot_address + ":" + std::to_string(lc.robot_port);
  } else {
    throw sim::ScenarioError("device: must be simulated, scripted, replay, emulator or handhiro, got \"" + r.kind + "\"");
  }
  return w;
}

}  // namespace palpation::app::live
