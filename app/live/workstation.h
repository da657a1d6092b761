// The workstation's real-time composition (design.md section 3), Qt-free so that the GUI
// (ui/), the recorder and tests drive the same object:
//
//   device::SimulatedHand (scripted hand, looped | mouse targets)
//        ^ forces        | poses
//   haptic thread (1 kHz, app/live/haptic_thread.h, device::HapticLoop)
//        | poses (triple buffer)        ^ contact models (triple buffer)
//   simulation thread: queued commands -> newest poses -> Backend::step -> publish
//        | RenderSnapshot (triple buffer, ~30 Hz)   | StepSample (SPSC ring, every step)
//   GUI thread: Workstation::poll() drains the rings, hands TickSample / StepSample /
//   Event to its listeners (plots, status bar, a recorder), reads the newest snapshot.
//
// Telemetry interface for consumers (plots, the session recorder):
//   - add_tick_listener(fn): every haptic tick that poll() drains, per present device
//     finger, in the world frame (t in s since start(), position m, force on the finger N).
//     Delivered on the thread that calls poll() (the GUI thread), in time order; nothing
//     is dropped unless the 32k-tick ring overflows between polls (counted: dropped()).
//   - add_step_listener(fn): every simulation step (time, step ms, CG iterations, contacts).
//   - add_event_listener(fn) / events(): instructor and system events (patient loaded,
//     material change, tumour added/painted, mode change, divergence reset), time-stamped,
//     as data (live/event.h: a kind and its arguments; the English line from event_text).
// The tumour document (live/tumour_document.h, tumours()) is the GUI's copy of the
// patient's moduli and tumour list: set_element_young changes it and queues the change.
// Changes (materials, parameters, patient) are queued with post() and applied on the
// simulation thread between steps; a patient swap first fades the forces to zero.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "live/device_config.h"
#include "live/event.h"
#include "live/force_mapping.h"
#include "live/tumour_document.h"
#include "hand_script.h"
#include "haptic_device.h"
#include "haptic_loop.h"
#include "params.h"
#include "scenario.h"
#include "simulated_hand.h"
#include "spsc_ring.h"
#include "triple_buffer.h"

namespace palpation::device {
class HandHiroEmulator;
}

namespace palpation::sim {
class Simulation;
struct Model;
}

namespace palpation::app::train {
struct SkinMap;
}

namespace palpation::app::live {

namespace dv = palpation::device;
class SimulationLoop;
struct DeviceWiring;

/// The simulated hand's two modes: palpating on its own (a looped script) or following
/// the mouse.
using HandMode = dv::SimulatedHand::Mode;

/// What the GUI draws: the deformed nodes and the fingertips, world frame.
struct RenderSnapshot {
  std::uint64_t model_generation = 0;  // changes when a new patient was loaded
  std::uint64_t sequence = 0;          // simulation steps so far
  double sim_time = 0;                 // s
  std::vector<float> positions;        // (nnode x 3) m
  std::array<Eigen::Vector3d, dv::kMaxFingers> finger_position{};
  std::array<Eigen::Vector3d, dv::kMaxFingers> finger_force{};  // on the finger, N
  std::array<bool, dv::kMaxFingers> finger_active{};
  double finger_radius = 0.008;
  /// Von Mises stress at the nodes (nnode, Pa; sim/fem_stress.h), filled only while
  /// Workstation::set_stress_enabled(true), else empty.
  std::vector<float> von_mises;
};

struct TickSample {
  double t = 0;            // s since start()
  int finger = 0;          // device finger (dv::FingerId)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, m
  Eigen::Vector3d force = Eigen::Vector3d::Zero();     // sent to the device, world, N
  bool attached = false;
};

struct StepSample {
  double t = 0;             // s since start() (wall clock)
  double sim_time = 0;      // s
  float step_ms = 0;
  int cg_iterations = 0;
  int contacts = 0;
  // What the step was given and gave (the recorder's steps: a review re-simulates
  // the session from these exactly).
  double h = 0;                                          // s, this step's dt
  std::uint64_t commands_applied = 0;                    // queued commands applied before it
  std::array<sim::FingerInput, dv::kMaxFingers> in{};    // device fingers, world
  std::array<Eigen::Vector3d, dv::kMaxFingers> force{};  // on the finger, simulated N (zero after a reset)
  /// The force scale the step's contact models went to the device with (the device got
  /// mapping.scale x force; live/force_mapping.h).
  ForceMapping mapping;
};

/// What a posted command changes: element moduli, solver/contact parameters, the patient.
enum class CommandKind { Young, Params, Patient };
/// The kind's name in recordings: "young", "params", "patient".
const char* command_kind_name(CommandKind k);

/// A change posted through set_element_young / set_params / load_patient, as data (for
/// the recorder): `index` is its place among all posted commands (the count applied
/// before a step says which ones that step saw).
struct CommandRecord {
  std::uint64_t index = 0;
  CommandKind kind = CommandKind::Young;
  std::vector<std::pair<int, double>> young;         // Young: element, Pa
  sim::SimParams params;                             // Params
  sim::Scenario scenario;                            // Patient
  std::optional<Event> event;                        // the event logged with it (Young: when described)
};

/// The commands' effects, shared with the review's re-simulation (app/review/review_session.h).
void apply_element_young(sim::Simulation& s, const std::vector<std::pair<int, double>>& changes);
void apply_params(sim::Simulation& s, const sim::SimParams& p);

/// Geometry of the loaded patient that the GUI needs (picking, painting): a copy, never
/// changed after loading.
struct PatientGeometry {
  std::uint64_t generation = 0;
  std::vector<Eigen::Vector3d> rest;            // (nnode) m
  std::vector<std::array<int, 4>> tets;         // (ntet)
  std::vector<std::array<int, 3>> surface;      // (nsurf) outward
  std::vector<Eigen::Vector3d> centroid;        // (ntet) rest centroid, m
  std::vector<double> young;                    // (ntet) Pa at load time
  double tissue_young = 19000;                  // Pa, bulk tissue (the scenario's reference)
  /// (ntet) Pa: each element's tissue without tumours (sim::Model::tissue_young: its
  /// layer's in a layered breast); empty: tissue_young everywhere.
  std::vector<double> base_young;
  double base_of(int e) const {
    return e >= 0 && std::size_t(e) < base_young.size() ? base_young[std::size_t(e)] : tissue_young;
  }
  /// base_young, or tissue_young for every element when it is empty.
  std::vector<double> base_moduli() const {
    return base_young.size() == tets.size() ? base_young : std::vector<double>(tets.size(), tissue_young);
  }
  double tissue_poisson = 0.45;
  /// The skin (boundary off the chest wall) with its thickness: coverage and scoring.
  std::shared_ptr<const train::SkinMap> skin;
  std::string backend, device_name;
};

/// The PatientGeometry of a built simulation (its model, scenario tissue and backend): the
/// live workstation's and the review's 3-D view read the same. Non-const: the backend's
/// name is read through sim::Simulation::backend().
std::shared_ptr<PatientGeometry> make_patient_geometry(sim::Simulation& simulation, std::uint64_t generation);

/// The simulation thread's state.
enum class SimState { Stopped, Loading, Running, Swapping, Error };
/// In English: "stopped", "loading", "running", "swapping", "error".
const char* sim_state_name(SimState s);

/// Live figures (GUI thread, updated by poll()).
struct LiveStats {
  double step_rate_hz = 0, haptic_rate_hz = 0, step_ms = 0, jitter_us = 0;
  // Simulated seconds a wall second over the same window (1: the tissue keeps real time;
  // below where no dt fits, live/step_pacer.h), and the steps' mean dt (ms).
  double pace = 0, dt_ms = 0;
  int cg_iterations = 0;
  bool connected = false;
  std::array<bool, dv::kMaxFingers> attached{};
  std::array<double, dv::kMaxFingers> force_n{};
  std::uint64_t dropped = 0;
  SimState state = SimState::Stopped;
  std::string error;              // Error: why (English, as the simulation said it)
  std::string backend;            // the backend stepping now ("cpu" after a fallback)
  int fallbacks = 0;              // backend errors survived by falling back to the CPU
  int divergences = 0;            // divergence resets (body put back to rest)
  std::string safety_note;        // the newest of those, one line ("" when none)
  bool recovering = false;        // forces held/blended after a fallback or reset
  ForceMapping force_mapping;     // the current patient's force scale (simulated -> device)
};

struct WorkstationOptions {
  sim::Scenario scenario;              // patient, tissue, inclusions, solver; fingers unused
  /// "simulated": device::SimulatedHand (scripted hand or mouse); "emulator": the HandHIRO
  /// protocol over loopback UDP to an in-process handhiro-emulator driven by the same
  /// scripted hand; "handhiro": the UDP link to a robot at robot_address:robot_port.
  std::string device = "simulated";
  std::string robot_address;           // empty: the device configuration's
  int robot_port = 0;                  // 0: the device configuration's
  DeviceConfig config = default_device_config();
  int haptic_priority = 80;            // SCHED_FIFO where allowed
  double snapshot_hz = 40;             // render snapshots per second (at most; the view draws one frame per snapshot)
  double sim_max_dt = 0.01;            // s, cap of the real-time dt
  /// After a backend error (CPU fallback) or a divergence reset the body restarts at
  /// rest: the last good contact models are held while the new body settles around the
  /// fingers (at least recover_hold_s, and until the new forces have changed by less than
  /// 100 % + 0.5 N per second for 0.1 s of simulated time, at most recover_hold_max_s), then
  /// blended linearly into the new ones over recover_blend_s (0, 0 and 0: the new forces
  /// at once). Settling is judged on the forces, not the clock: a slow or loaded machine
  /// steps fewer times per second and needs longer to settle the new body.
  double recover_hold_s = 0.3;
  double recover_hold_max_s = 3.0;
  double recover_blend_s = 0.5;
  /// The two-step minimum on the force sent to the haptic loop (app/live/sim_fingers.h,
  /// guard_force_spike): no release chatter or contact-onset overshoot at real-time dt.
  bool spike_guard = true;
};

/// The default patient: the paper's breast and tumour at the coarse resolution (about
/// 1,000 nodes: real time on a 2-core CPU).
sim::Scenario default_workstation_scenario();
/// A hand palpating on its own: the index finger does the paper's sweep (looped), the
/// other four follow above the skin like a hand (device frame).
dv::HandScript default_hand_script(const DeviceConfig& cfg);

class Workstation {
 public:
  /// Throws std::runtime_error when the device cannot be opened (bad address, port in use).
  explicit Workstation(WorkstationOptions opt);
  ~Workstation();
  Workstation(const Workstation&) = delete;
  Workstation& operator=(const Workstation&) = delete;

  /// Starts the threads; the patient is built on the simulation thread (loading state).
  void start();
  void stop();
  bool running() const { return sim_thread_.joinable(); }

  /// GUI thread: drains telemetry into listeners and stats; true when a new snapshot
  /// is available (snapshot() then returns it).
  bool poll();
  const RenderSnapshot& snapshot() const { return snapshots_.read(); }
  const LiveStats& stats() const { return stats_; }
  /// Geometry of the current patient (nullptr while the first one loads).
  std::shared_ptr<const PatientGeometry> geometry() const;
  const WorkstationOptions& options() const { return opt_; }
  const DeviceConfig& device_config() const { return opt_.config; }
  /// The force scale between simulation and device of the current patient, chosen when
  /// it was loaded (live/force_mapping.h; the configured scale, else 1, before the first
  /// one). Any thread.
  ForceMapping force_mapping() const;

  // Commands: applied on the simulation thread between steps. ---------------------
  using Command = std::function<void(sim::Simulation&)>;
  void post(Command c);
  /// Sets the Young's modulus of elements (Pa; Poisson ratio unchanged) in the tumour
  /// document and queues it for the simulation; an instructor's edit is logged as a
  /// Material event. GUI thread.
  void set_element_young(std::vector<std::pair<int, double>> changes, const std::optional<MaterialEdit>& edit = {});
  void set_params(const sim::SimParams& p);
  /// Replaces the patient (forces fade to zero first, then the model is rebuilt).
  void load_patient(const sim::Scenario& s);
  /// Per-element moduli as the running simulation has them (copied after each applied
  /// material command); with the number of commands applied so far.
  std::vector<double> applied_young(std::uint64_t* applied = nullptr) const;
  std::uint64_t commands_posted() const { return posted_.load(); }
  std::uint64_t commands_applied() const { return applied_.load(); }
  /// The tumour document: the patient's moduli and tumour list as the GUI knows them,
  /// following each new patient at poll(). GUI thread.
  TumourDocument& tumours() { return tumours_; }
  const TumourDocument& tumours() const { return tumours_; }

  // Device ---------------------------------------------------------------------------
  /// The simulated device (scripted hand / mouse targets). With "emulator" or "handhiro"
  /// it exists but the loop talks to the link instead.
  dv::SimulatedHand& device() { return *device_; }
  /// What the haptic loop talks to, in words.
  std::string device_description() const;
  bool simulated_device() const;
  /// The stress colour map: the simulation thread adds nodal von Mises stress to the
  /// render snapshots while on (0.36 ms per snapshot on the coarse breast, 3.7 ms on the
  /// paper mesh; docs/gui.md).
  void set_stress_enabled(bool on) { stress_enabled_.store(on, std::memory_order_release); }
  bool stress_enabled() const { return stress_enabled_.load(std::memory_order_acquire); }

  /// Mouse palpation: the index fingertip goes to `world` (m); others stay away.
  void set_mouse_finger(const Eigen::Vector3d& world, bool present);

  // Telemetry -------------------------------------------------------------------------
  void add_tick_listener(std::function<void(const TickSample&)> f) { tick_listeners_.push_back(std::move(f)); }
  void add_step_listener(std::function<void(const StepSample&)> f) { step_listeners_.push_back(std::move(f)); }
  void add_event_listener(std::function<void(const Event&)> f) { event_listeners_.push_back(std::move(f)); }
  /// Called on the posting thread (the GUI) when set_element_young / set_params /
  /// load_patient posts a command.
  void add_command_listener(std::function<void(const CommandRecord&)> f) { command_listeners_.push_back(std::move(f)); }
  /// Logs an event (any thread); its time is set here.
  void log_event(Event e);
  std::vector<Event> events() const;
  double now_s() const;

 private:
  void sim_main();
  void build(const sim::Scenario& s);

  WorkstationOptions opt_;
  std::unique_ptr<DeviceWiring> wiring_;           // what the haptic loop talks to
  std::unique_ptr<dv::SimulatedHand> own_hand_;    // the mouse's hand beside a link
  dv::SimulatedHand* device_ = nullptr;            // the simulated hand (wiring's or own)
  dv::TripleBuffer<dv::PoseFrame> poses_;
  dv::TripleBuffer<dv::ContactFrame> contacts_;
  dv::SpscRing<dv::TickRecord> ticks_{1 << 15};
  dv::SpscRing<StepSample> steps_{1 << 13};
  dv::TripleBuffer<RenderSnapshot> snapshots_;
  std::unique_ptr<dv::HapticLoop> loop_;
  struct Threads;
  std::unique_ptr<Threads> threads_;
  std::thread sim_thread_;
  std::atomic<bool> stop_{false};
  std::unique_ptr<sim::Simulation> sim_;

  mutable std::mutex mu_;  // guards the fields below (never taken by the haptic thread)
  std::vector<Command> queue_;
  std::vector<Event> events_, new_events_;
  std::shared_ptr<const PatientGeometry> geometry_;
  std::vector<double> applied_young_;
  std::atomic<std::uint64_t> posted_{0}, applied_{0};
  std::atomic<std::uint64_t> generation_{0};
  std::int64_t t0_ns_ = 0;
  std::string load_error_;
  bool swap_pending_ = false;        // simulation thread only
  std::atomic<SimState> sim_state_{SimState::Stopped};
  std::string backend_name_, safety_note_;            // guarded by mu_
  ForceMapping force_mapping_;                         // guarded by mu_
  std::atomic<int> fallbacks_{0}, divergences_{0};
  std::atomic<bool> stress_enabled_{false};
  std::unique_ptr<SimulationLoop> sim_loop_;  // the simulation thread's body

  // GUI-thread side
  LiveStats stats_;
  TumourDocument tumours_;
  std::vector<std::function<void(const TickSample&)>> tick_listeners_;
  std::vector<std::function<void(const StepSample&)>> step_listeners_;
  std::vector<std::function<void(const Event&)>> event_listeners_;
  std::vector<std::function<void(const CommandRecord&)>> command_listeners_;
  void notify_command(CommandRecord r);
  std::int64_t rate_window_ns_ = 0;
  std::uint64_t window_ticks_ = 0, window_steps_ = 0;
  double window_sim_s_ = 0;
  std::int64_t prev_tick_ns_ = 0;
  double window_jitter_ = 0;
};

}  // namespace palpation::app::live
