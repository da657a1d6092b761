#include "live/device_config.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "json_reader.h"  // sim::ScenarioError: bad input -> exit code 2

namespace palpation::app::live {

using nlohmann::json;
namespace dv = palpation::device;

namespace {

json vec(const dv::Vec3& v) { return json::array({v.x, v.y, v.z}); }

json joint_json(const dv::JointSpec& j) {
  return json{{"offset", vec(j.offset)}, {"axis", vec(j.axis)}, {"limits", json::array({j.lower, j.upper})},
              {"max_torque", j.max_torque}};
}

// The device configuration's fields beside the common ones (sim/json_reader.h); keys
// starting with "_" are comments.
class Reader : public sim::JsonReader {
 public:
  explicit Reader(std::string source) : JsonReader(std::move(source), true) {}
  dv::Vec3 vec3(const json& v, const std::string& field) const { return triple<dv::Vec3>(v, field); }
  dv::Vec3 unit(const json& v, const std::string& field) const {
    dv::Vec3 a = vec3(v, field);
    const double n = dv::norm(a);
    if (!(n > 1e-9)) fail(field, "must be a non-zero axis");
    return a * (1.0 / n);
  }
  dv::JointSpec joint(const json& v, const std::string& field, dv::JointSpec j) const {
    only_keys(v, field, {"offset", "axis", "limits", "max_torque"});
    opt(v, "offset", field, [&](const json& x, const std::string& f) { j.offset = vec3(x, f); });
    opt(v, "axis", field, [&](const json& x, const std::string& f) { j.axis = unit(x, f); });
    opt(v, "limits", field, [&](const json& x, const std::string& f) {
      if (!x.is_array() || x.size() != 2) fail(f, "must be [lower, upper] in rad");
      j.lower = number(x[0], f + "[0]");
      j.upper = number(x[1], f + "[1]");
      if (!(j.lower < j.upper)) fail(f, "lower must be below upper");
    });
    opt(v, "max_torque", field, [&](const json& x, const std::string& f) { j.max_torque = positive(x, f); });
    return j;
  }
};

}  // namespace

DeviceConfig default_device_config() {
  DeviceConfig c;
  const auto& caps = c.hand.capabilities;
  c.loop.safety.max_force = caps.max_force;
  c.loop.safety.max_damping = caps.max_damping;
  c.loop.max_stiffness = caps.max_stiffness;
  c.link.timeout = 0.05;
  return c;
}

json device_config_to_json(const DeviceConfig& c) {
  const auto& h = c.hand;
  const auto& caps = h.capabilities;
  json j;
  j["_about"] =
      "HandHIRO (HIRO III) device configuration. Approximate, conservative defaults: the published force range, "
      "link lengths and magnet release force were not retrieved (see docs/handhiro-protocol.md). Units: m, s, N, "
      "rad, kg; device frame: x forward, y left, z up, origin at the arm base.";
  j["capabilities"] = {{"max_force", caps.max_force},
                       {"max_stiffness", caps.max_stiffness},
                       {"max_damping", caps.max_damping},
                       {"release_force", caps.release_force},
                       {"workspace_min", vec(caps.workspace_min)},
                       {"workspace_max", vec(caps.workspace_max)},
                       {"rate_hz", caps.rate_hz}};
  json arm = json::array();
  for (const auto& jt : h.arm) arm.push_back(joint_json(jt));
  j["arm"] = {{"joints", arm}, {"neutral", h.arm_neutral}, {"palm", vec(h.palm)}};
  static const char* names[dv::kMaxFingers] = {"thumb", "index", "middle", "ring", "little"};
  json fingers = json::array();
  for (int f = 0; f < dv::kMaxFingers; ++f) {
    const auto& s = h.fingers[f];
    json js = json::array();
    for (const auto& jt : s.joints) js.push_back(joint_json(jt));
    fingers.push_back({{"name", names[f]}, {"base", vec(s.base)}, {"base_yaw", s.base_yaw}, {"joints", js},
                       {"tip", vec(s.tip)}, {"neutral", s.neutral}});
  }
  j["fingers"] = fingers;
  j["magnet"] = {{"tip_mass", h.tip_mass},
                 {"reattach_delay", h.reattach_delay},
                 {"reattach_speed", h.reattach_speed},
                 {"reattach_distance", h.reattach_distance}};
  j["controller"] = {{"watchdog", h.robot_watchdog}, {"ramp", h.robot_ramp}};
  j["operator"] = {{"mass", h.user.mass}, {"stiffness", h.user.stiffness}, {"damping", h.user.damping}};
  json rot = json::array();
  for (int r = 0; r < 3; ++r) rot.push_back({h.registration.rotation(r, 0), h.registration.rotation(r, 1), h.registration.rotation(r, 2)});
  j["registration"] = {{"world_origin_in_device", vec(h.registration.origin)}, {"rotation", rot}};
  j["finger_map"] = c.finger_map;
  j["link"] = {{"robot_address", c.link.robot_address},
               {"robot_port", c.link.robot_port},
               {"bind_address", c.link.bind_address},
               {"bind_port", c.link.bind_port},
               {"timeout", c.link.timeout}};
  const auto& s = c.loop.safety;
  j["haptic_loop"] = {{"period", c.loop.period},
                      {"coupling", c.loop.virtual_coupling ? "virtual" : "direct"},
                      {"coupling_stiffness", c.loop.coupling_stiffness},
                      {"blend_max_ticks", c.loop.blend_max_ticks},
                      {"max_rate", s.max_rate},
                      {"stale_after", s.stale_after},
                      {"ramp_out", s.ramp_out},
                      {"ramp_in", s.ramp_in},
                      {"passivity", s.passivity},
                      {"passivity_highpass_hz", s.passivity_highpass_hz},
                      {"passivity_reserve", s.passivity_reserve},
                      {"passivity_threshold", s.passivity_threshold},
                      {"passivity_leak", s.passivity_leak}};
  const auto& fm = c.force_mapping;
  j["force_mapping"] = {{"scale", fm.scale > 0 ? json(fm.scale) : json("auto")},
                        {"deep_press_share", fm.deep_press_share},
                        {"deep_press_depth", fm.deep_press_depth}};
  return j;
}

DeviceConfig parse_device_config(const std::string& text, const std::string& source) {
  Reader r(source);
  json j = r.parse(text);
  DeviceConfig c = default_device_config();
  c.source = source;
  auto& h = c.hand;
  r.only_keys(j, "", {"capabilities", "arm", "fingers", "magnet", "controller", "operator", "registration", "finger_map",
                      "link", "haptic_loop", "force_mapping"});
  r.opt(j, "capabilities", "", [&](const json& o, const std::string& f) {
    auto& caps = h.capabilities;
    r.only_keys(o, f, {"max_force", "max_stiffness", "max_damping", "release_force", "workspace_min", "workspace_max", "rate_hz"});
    r.opt(o, "max_force", f, [&](const json& v, const std::string& g) { caps.max_force = r.positive(v, g); });
    r.opt(o, "max_stiffness", f, [&](const json& v, const std::string& g) { caps.max_stiffness = r.positive(v, g); });
    r.opt(o, "max_damping", f, [&](const json& v, const std::string& g) { caps.max_damping = r.non_negative(v, g); });
    r.opt(o, "release_force", f, [&](const json& v, const std::string& g) { caps.release_force = r.positive(v, g); });
    r.opt(o, "workspace_min", f, [&](const json& v, const std::string& g) { caps.workspace_min = r.vec3(v, g); });
    r.opt(o, "workspace_max", f, [&](const json& v, const std::string& g) { caps.workspace_max = r.vec3(v, g); });
    r.opt(o, "rate_hz", f, [&](const json& v, const std::string& g) { caps.rate_hz = r.positive(v, g); });
  });
  r.opt(j, "arm", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"joints", "neutral", "palm"});
    r.opt(o, "joints", f, [&](const json& v, const std::string& g) {
      if (!v.is_array() || v.size() != dv::kArmJoints) r.fail(g, "must be an array of 6 joints");
      for (int i = 0; i < dv::kArmJoints; ++i) h.arm[i] = r.joint(v[i], g + "[" + std::to_string(i) + "]", h.arm[i]);
    });
    r.opt(o, "neutral", f, [&](const json& v, const std::string& g) {
      if (!v.is_array() || v.size() != dv::kArmJoints) r.fail(g, "must be an array of 6 angles");
      for (int i = 0; i < dv::kArmJoints; ++i) h.arm_neutral[i] = r.number(v[i], g + "[" + std::to_string(i) + "]");
    });
    r.opt(o, "palm", f, [&](const json& v, const std::string& g) { h.palm = r.vec3(v, g); });
  });
  r.opt(j, "fingers", "", [&](const json& v, const std::string& f) {
    if (!v.is_array() || v.size() != dv::kMaxFingers) r.fail(f, "must be an array of 5 fingers (thumb, index, middle, ring, little)");
    for (int i = 0; i < dv::kMaxFingers; ++i) {
      const std::string g = f + "[" + std::to_string(i) + "]";
      auto& s = h.fingers[i];
      r.only_keys(v[i], g, {"name", "base", "base_yaw", "joints", "tip", "neutral"});
      r.opt(v[i], "base", g, [&](const json& x, const std::string& k) { s.base = r.vec3(x, k); });
      r.opt(v[i], "base_yaw", g, [&](const json& x, const std::string& k) { s.base_yaw = r.number(x, k); });
      r.opt(v[i], "tip", g, [&](const json& x, const std::string& k) { s.tip = r.vec3(x, k); });
      r.opt(v[i], "joints", g, [&](const json& x, const std::string& k) {
        if (!x.is_array() || x.size() != dv::kFingerJoints) r.fail(k, "must be an array of 3 joints");
        for (int q = 0; q < dv::kFingerJoints; ++q) s.joints[q] = r.joint(x[q], k + "[" + std::to_string(q) + "]", s.joints[q]);
      });
      r.opt(v[i], "neutral", g, [&](const json& x, const std::string& k) {
        if (!x.is_array() || x.size() != dv::kFingerJoints) r.fail(k, "must be an array of 3 angles");
        for (int q = 0; q < dv::kFingerJoints; ++q) s.neutral[q] = r.number(x[q], k + "[" + std::to_string(q) + "]");
      });
    }
  });
  r.opt(j, "magnet", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"tip_mass", "reattach_delay", "reattach_speed", "reattach_distance"});
    r.opt(o, "tip_mass", f, [&](const json& v, const std::string& g) { h.tip_mass = r.non_negative(v, g); });
    r.opt(o, "reattach_delay", f, [&](const json& v, const std::string& g) { h.reattach_delay = r.non_negative(v, g); });
    r.opt(o, "reattach_speed", f, [&](const json& v, const std::string& g) { h.reattach_speed = r.positive(v, g); });
    r.opt(o, "reattach_distance", f, [&](const json& v, const std::string& g) { h.reattach_distance = r.positive(v, g); });
  });
  r.opt(j, "controller", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"watchdog", "ramp"});
    r.opt(o, "watchdog", f, [&](const json& v, const std::string& g) { h.robot_watchdog = r.positive(v, g); });
    r.opt(o, "ramp", f, [&](const json& v, const std::string& g) { h.robot_ramp = r.non_negative(v, g); });
  });
  r.opt(j, "operator", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"mass", "stiffness", "damping"});
    r.opt(o, "mass", f, [&](const json& v, const std::string& g) { h.user.mass = r.positive(v, g); });
    r.opt(o, "stiffness", f, [&](const json& v, const std::string& g) { h.user.stiffness = r.positive(v, g); });
    r.opt(o, "damping", f, [&](const json& v, const std::string& g) { h.user.damping = r.non_negative(v, g); });
  });
  r.opt(j, "registration", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"world_origin_in_device", "rotation"});
    r.opt(o, "world_origin_in_device", f, [&](const json& v, const std::string& g) { h.registration.origin = r.vec3(v, g); });
    r.opt(o, "rotation", f, [&](const json& v, const std::string& g) {
      if (!v.is_array() || v.size() != 3) r.fail(g, "must be a 3 x 3 rotation matrix (rows)");
      dv::Mat3 m;
      for (int i = 0; i < 3; ++i) {
        const dv::Vec3 row = r.vec3(v[i], g + "[" + std::to_string(i) + "]");
        for (int k = 0; k < 3; ++k) m(i, k) = row[k];
      }
      const dv::Mat3 e = m * m.transposed();
      double err = 0;
      for (int i = 0; i < 9; ++i) err = std::max(err, std::fabs(e.m[i] - dv::Mat3::identity().m[i]));
      const double det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
      if (err > 1e-6 || det < 0) r.fail(g, "must be a proper rotation (orthonormal, det +1)");
      h.registration.rotation = m;
    });
  });
  r.opt(j, "finger_map", "", [&](const json& v, const std::string& f) {
    if (!v.is_array() || v.size() != dv::kMaxFingers) r.fail(f, "must list 5 device fingers (0 thumb .. 4 little)");
    std::set<int> seen;
    for (int i = 0; i < dv::kMaxFingers; ++i) {
      if (!v[i].is_number_integer() || v[i].get<int>() < 0 || v[i].get<int>() >= dv::kMaxFingers)
        r.fail(f + "[" + std::to_string(i) + "]", "must be an integer in [0, 4]");
      if (!seen.insert(v[i].get<int>()).second) r.fail(f, "each device finger at most once");
      c.finger_map[i] = v[i].get<int>();
    }
  });
  r.opt(j, "link", "", [&](const json& o, const std::string& f) {
    r.only_keys(o, f, {"robot_address", "robot_port", "bind_address", "bind_port", "timeout"});
    auto address = [&](const json& v, const std::string& g) {
      if (!v.is_string()) r.fail(g, "must be a string (IPv4 address)");
      std::uint32_t a = 0;
      if (!dv::parse_ipv4(v.get<std::string>(), a)) r.fail(g, "\"" + v.get<std::string>() + "\" is not an IPv4 address");
      return v.get<std::string>();
    };
    auto port = [&](const json& v, const std::string& g) {
      if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 65535) r.fail(g, "must be a port in [0, 65535]");
      return std::uint16_t(v.get<int>());
    };
    r.opt(o, "robot_address", f, [&](const json& v, const std::string& g) { c.link.robot_address = address(v, g); });
    r.opt(o, "bind_address", f, [&](const json& v, const std::string& g) { c.link.bind_address = address(v, g); });
    r.opt(o, "robot_port", f, [&](const json& v, const std::string& g) { c.link.robot_port = port(v, g); });
    r.opt(o, "bind_port", f, [&](const json& v, const std::string& g) { c.link.bind_port = port(v, g); });
    r.opt(o, "timeout", f, [&](const json& v, const std::string& g) { c.link.timeout = r.positive(v, g); });
  });
  r.opt(j, "haptic_loop", "", [&](const json& o, const std::string& f) {
    auto& s = c.loop.safety;
    r.only_keys(o, f, {"period", "coupling", "coupling_stiffness", "blend_max_ticks", "max_rate", "stale_after", "ramp_out", "ramp_in", "passivity",
                       "passivity_highpass_hz", "passivity_reserve", "passivity_threshold", "passivity_leak"});
    r.opt(o, "period", f, [&](const json& v, const std::string& g) {
      c.loop.period = r.positive(v, g);
      if (c.loop.period > 0.01) r.fail(g, "must be at most 0.01 s (100 Hz)");
    });
    r.opt(o, "coupling", f, [&](const json& v, const std::string& g) {
      if (!v.is_string() || (v.get<std::string>() != "virtual" && v.get<std::string>() != "direct"))
        r.fail(g, "must be \"virtual\" or \"direct\"");
      c.loop.virtual_coupling = v.get<std::string>() == "virtual";
    });
    r.opt(o, "coupling_stiffness", f, [&](const json& v, const std::string& g) {
      c.loop.coupling_stiffness = r.non_negative(v, g);
    });
    r.opt(o, "blend_max_ticks", f, [&](const json& v, const std::string& g) {
      if (!v.is_number_integer() || v.get<int>() < 1 || v.get<int>() > 1000) r.fail(g, "must be an integer in [1, 1000]");
      c.loop.blend_max_ticks = v.get<int>();
    });
    r.opt(o, "max_rate", f, [&](const json& v, const std::string& g) { s.max_rate = r.positive(v, g); });
    r.opt(o, "stale_after", f, [&](const json& v, const std::string& g) { s.stale_after = r.positive(v, g); });
    r.opt(o, "ramp_out", f, [&](const json& v, const std::string& g) { s.ramp_out = r.non_negative(v, g); });
    r.opt(o, "ramp_in", f, [&](const json& v, const std::string& g) { s.ramp_in = r.non_negative(v, g); });
    r.opt(o, "passivity", f, [&](const json& v, const std::string& g) {
      if (!v.is_boolean()) r.fail(g, "must be true or false");
      s.passivity = v.get<bool>();
    });
    r.opt(o, "passivity_highpass_hz", f, [&](const json& v, const std::string& g) { s.passivity_highpass_hz = r.positive(v, g); });
    r.opt(o, "passivity_reserve", f, [&](const json& v, const std::string& g) { s.passivity_reserve = r.non_negative(v, g); });
    r.opt(o, "passivity_threshold", f, [&](const json& v, const std::string& g) { s.passivity_threshold = r.non_negative(v, g); });
    r.opt(o, "passivity_leak", f, [&](const json& v, const std::string& g) { s.passivity_leak = r.positive(v, g); });
  });
  r.opt(j, "force_mapping", "", [&](const json& o, const std::string& f) {
    auto& fm = c.force_mapping;
    r.only_keys(o, f, {"scale", "deep_press_share", "deep_press_depth"});
    r.opt(o, "scale", f, [&](const json& v, const std::string& g) {
      if (v.is_string() && v.get<std::string>() == "auto") {
        fm.scale = 0;
        return;
      }
      if (!v.is_number()) r.fail(g, "must be \"auto\" or a number in (0, 1]");
      fm.scale = r.positive(v, g);
      if (fm.scale > 1) r.fail(g, "must be at most 1 (a scale only attenuates)");
    });
    r.opt(o, "deep_press_share", f, [&](const json& v, const std::string& g) {
      fm.deep_press_share = r.positive(v, g);
      if (fm.deep_press_share > 1) r.fail(g, "must be at most 1 (a share of the device's limit)");
    });
    r.opt(o, "deep_press_depth", f, [&](const json& v, const std::string& g) {
      fm.deep_press_depth = r.positive(v, g);
      if (fm.deep_press_depth >= 1) r.fail(g, "must be below 1 (a fraction of the tissue thickness)");
    });
  });
  // Limits of the loop follow the device.
  const auto& caps = h.capabilities;
  if (caps.release_force <= caps.max_force)
    r.fail("capabilities.release_force", "must exceed max_force (the magnet joint must hold the largest rendered force)");
  for (int k = 0; k < 3; ++k)
    if (!(caps.workspace_min[k] < caps.workspace_max[k])) r.fail("capabilities.workspace_min", "must be below workspace_max on every axis");
  c.loop.safety.max_force = caps.max_force;
  c.loop.safety.max_damping = caps.max_damping;
  c.loop.max_stiffness = caps.max_stiffness;
  return c;
}

DeviceConfig load_device_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw sim::ScenarioError(path + ": (file): cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_device_config(ss.str(), path);
}

}  // namespace palpation::app::live
