#include "review/workstation_recorder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace palpation::app::review {

using live::CommandKind;
using live::CommandRecord;
using live::DeviceConfig;
using live::Event;
using live::StepSample;
using live::TickSample;
using live::Workstation;
using live::device_config_to_json;
using store::RecordedStep;
using store::RecordingError;
using store::RecordingWriter;
using store::RecoverResult;
using store::recover_recording;

using nlohmann::json;

json recorded_scenario_json(const sim::Scenario& s0, int fingers) {
  sim::Scenario s = s0;
  sim::FingerPath proto = s.fingers.empty() ? sim::FingerPath{} : s.fingers.front();
  if (proto.keys.size() > 2) proto.keys.resize(2);
  proto.interpolation = sim::PathInterpolation::Linear;  // a placeholder: the ticks are the path
  if (proto.keys.empty()) proto.keys = {{0.0, 0.0, 0.0, 0.2}, {1.0, 0.0, 0.0, 0.2}};
  s.fingers.assign(std::size_t(fingers), proto);
  return json::parse(sim::scenario_to_json(s));
}

WorkstationRecorder::WorkstationRecorder(Workstation& ws, const std::string& path, json settings)
    : ws_(ws), scenario_(ws.options().scenario), alive_(std::make_shared<bool>(true)) {
  const auto& o = ws.options();
  const DeviceConfig& cfg = ws.device_config();
  json header;
  header["scenario"] = recorded_scenario_json(o.scenario, kFingers);
  header["scenario_source"] = o.scenario.source;
  header["device_config"] = device_config_to_json(cfg);
  header["session"] = {{"kind", "workstation"},
                       {"device", o.device},
                       {"device_fingers", "thumb, index, middle, ring, little"},
                       {"sim_dt", "realtime"},
                       {"sim_max_dt", o.sim_max_dt},
                       {"coupling", cfg.loop.virtual_coupling ? "virtual" : "direct"},
                       {"backend", o.scenario.backend},
                       {"steps_recorded", true},
                       // Element indices in "young" changes are the model's (sim::Model);
                       // recordings without this name the mesh's own order (Model::mesh_tet).
                       {"element_numbering", "model"},
                       {"program", std::string("palpation-trainer ") + PALPATION_VERSION + " (" + PALPATION_GIT_COMMIT + ")"}};
  header["settings"] = settings.is_object() ? settings : json::object();
  writer_ = std::make_unique<RecordingWriter>(path, std::move(header), kFingers);
  for (auto& v : x_) v.setZero();
  for (auto& v : f_) v.setZero();

  std::weak_ptr<bool> alive = alive_;
  ws_.add_tick_listener([this, alive](const TickSample& s) {
    if (alive.lock()) on_tick(s);
  });
  ws_.add_step_listener([this, alive](const StepSample& s) {
    if (!alive.lock()) return;
    RecordedStep st;
    st.t = s.t;
    st.h = s.h;
    st.commands_applied = s.commands_applied;
    st.fingers.resize(kFingers);
    for (int d = 0; d < kFingers; ++d) {
      auto& fi = st.fingers[std::size_t(d)];
      fi.active = s.in[d].active;
      fi.radius = s.in[d].radius;
      fi.x = s.in[d].position;
      fi.v = s.in[d].velocity;
      fi.f = s.force[d];
      if (!fi.x.allFinite()) fi.x.setZero();
      if (!fi.v.allFinite()) fi.v.setZero();
      if (!fi.f.allFinite()) fi.f.setZero();
    }
    writer_->add_step(st);
    // The force scale the step's contact models went to the device with (chosen when the
    // patient loaded, live/force_mapping.h), recorded when it changes: replay sends the
    // re-simulated forces through the same scale.
    if (s.mapping.scale != force_scale_) {
      force_scale_ = s.mapping.scale;
      writer_->add_event(s.t, "session", {{"event", "force_scale"},
                                          {"scale", s.mapping.scale},
                                          {"rule", live::force_scale_rule_name(s.mapping.rule)},
                                          {"deep_press_n", s.mapping.deep_press_n},
                                          {"device_limit_n", s.mapping.device_limit_n}});
    }
  });
  ws_.add_event_listener([this, alive](const Event& e) {
    if (!alive.lock()) return;
    emit_tick();
    // The kind and its arguments as data, the English line beside them (live/event.h).
    writer_->add_event(e.t, "instructor", {{"event", live::event_kind_name(e.kind)}, {"text", e.text()}, {"args", live::event_args_json(e)}});
  });
  ws_.add_command_listener([this, alive](const CommandRecord& c) {
    if (!alive.lock()) return;
    emit_tick();
    json d{{"command", live::command_kind_name(c.kind)}, {"index", c.index}, {"text", c.event ? c.event->text() : std::string()}};
    if (c.event) {
      d["event"] = live::event_kind_name(c.event->kind);
      d["args"] = live::event_args_json(*c.event);
    }
    if (c.kind == CommandKind::Young) {
      json ch = json::array();
      for (const auto& [e, E] : c.young) ch.push_back({e, E});
      d["changes"] = std::move(ch);
    } else if (c.kind == CommandKind::Params) {
      sim::Scenario s = scenario_;
      s.params = c.params;
      d["scenario"] = recorded_scenario_json(s, 1);
    } else if (c.kind == CommandKind::Patient) {
      scenario_ = c.scenario;
      d["scenario"] = recorded_scenario_json(c.scenario, 1);
      d["source"] = c.scenario.source;
    }
    writer_->add_event(ws_.now_s(), "parameter", std::move(d));
  });
  writer_->add_event(0.0, "session", {{"event", "start"}});
  lock_fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (lock_fd_ >= 0) ::flock(lock_fd_, LOCK_EX | LOCK_NB);
}

WorkstationRecorder::~WorkstationRecorder() {
  *alive_ = false;
  alive_.reset();
  close();
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void WorkstationRecorder::on_tick(const TickSample& s) {
  if (s.finger < 0 || s.finger >= kFingers) return;
  if (pending_ && s.t != tick_t_) emit_tick();
  if (!pending_) {
    for (auto& f : f_) f.setZero();  // fingers not attached this tick push nothing
    tick_t_ = s.t;
    pending_ = true;
  }
  x_[std::size_t(s.finger)] = s.position.allFinite() ? s.position : x_[std::size_t(s.finger)];
  f_[std::size_t(s.finger)] = s.force.allFinite() ? s.force : Eigen::Vector3d::Zero();
}

void WorkstationRecorder::emit_tick() {
  if (!pending_) return;
  pending_ = false;
  if (tick_t_ <= last_t_ && writer_->ticks() > 0) return;  // times must increase
  last_t_ = tick_t_;
  writer_->add_tick(tick_t_, x_.data(), f_.data());
}

int WorkstationRecorder::add_mark(const Eigen::Vector3d& p, const std::string& note, double confidence) {
  emit_tick();
  ++marks_;
  json d{{"mark", marks_}, {"position", {p.x(), p.y(), p.z()}}, {"confidence", confidence}};
  if (!note.empty()) d["note"] = note;
  writer_->add_event(ws_.now_s(), "mark", std::move(d));
  return marks_;
}

void WorkstationRecorder::add_event(const std::string& kind, json data) {
  emit_tick();
  writer_->add_event(ws_.now_s(), kind, std::move(data));
}

void WorkstationRecorder::flush() {
  emit_tick();
  writer_->flush();
}

void WorkstationRecorder::close() {
  if (!writer_) return;
  emit_tick();
  writer_->add_event(ws_.now_s(), "session", {{"event", "end"}});
  writer_->close({{"marks", marks_}});
}

std::vector<std::string> recover_interrupted_recordings(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> said;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return said;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file() || e.path().extension() != ".palrec") continue;
    const std::string p = e.path().string();
    const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    if (free) {
      try {
        const RecoverResult r = recover_recording(p);
        if (!r.was_complete) {
          char buf[128];
          std::snprintf(buf, sizeof buf, ": recovered %zu ticks (%.1f s), %llu bytes of torn tail dropped", r.ticks, r.duration,
                        static_cast<unsigned long long>(r.dropped_bytes));
          said.push_back(p + buf);
        }
      } catch (const RecordingError& err) {
        said.push_back(std::string(err.what()) + " (left as it is)");
      }
    }
    ::close(fd);
  }
  return said;
}

}  // namespace palpation::app::review
