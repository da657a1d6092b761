#include "store/recorded_scenario.h"

#include <limits>

namespace palpation::app::store {

sim::Scenario parse_recorded_scenario(const nlohmann::json& scenario, const std::string& where) {
  if (!scenario.is_object()) return sim::parse_scenario(scenario.dump(), where);  // its own message
  nlohmann::json s = scenario;
  nlohmann::json& tissue = s["tissue"];
  if (tissue.is_null()) tissue = nlohmann::json::object();
  if (tissue.is_object() && !tissue.contains("element")) tissue["element"] = "linear";
  return sim::parse_scenario(s.dump(), where);
}

void recorded_inputs(const RecordedStep& step, std::span<sim::FingerInput> in) {
  for (std::size_t k = 0; k < in.size() && k < step.fingers.size(); ++k) {
    const RecordedStep::Finger& fi = step.fingers[k];
    in[k].position = fi.x;
    in[k].velocity = fi.v;
    in[k].radius = fi.radius;
    in[k].active = fi.active;
  }
}

std::vector<std::pair<int, double>> recorded_young_changes(const nlohmann::json& event) {
  std::vector<std::pair<int, double>> out;
  if (!event.is_object() || !event.contains("changes") || !event["changes"].is_array()) return out;
  for (const auto& p : event["changes"])
    if (p.is_array() && p.size() == 2 && p[0].is_number_integer() && p[1].is_number()) {
      const long long e = p[0].get<long long>();
      out.emplace_back(e >= 0 && e <= std::numeric_limits<int>::max() ? int(e) : -1, p[1].get<double>());
    }
  return out;
}

bool young_in_mesh_order(const RecordingInfo& rec) {
  if (!rec.header.is_object() || !rec.header.contains("session")) return true;
  const nlohmann::json& session = rec.header["session"];
  return !(session.is_object() && session.value("element_numbering", "") == "model");
}

std::vector<std::pair<int, double>> young_in_model_order(const sim::Model& m,
                                                         std::span<const std::pair<int, double>> changes,
                                                         bool mesh_order) {
  std::vector<std::pair<int, double>> out(changes.begin(), changes.end());
  if (!mesh_order) return out;
  std::vector<int> to(m.mesh_tet.size(), -1);
  for (std::size_t e = 0; e < m.mesh_tet.size(); ++e) to[std::size_t(m.mesh_tet[e])] = int(e);
  for (auto& [e, E] : out)
    if (e >= 0 && std::size_t(e) < to.size()) e = to[std::size_t(e)];
  return out;
}

}  // namespace palpation::app::store
