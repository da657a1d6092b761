#include "store/recorded_scenario.h"

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

}  // namespace palpation::app::store
