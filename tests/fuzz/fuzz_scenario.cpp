// libFuzzer target: the scenario JSON parser (sim/scenario.cpp). Contract (design.md
// section 5): any input either parses into a scenario that passes validation and
// round-trips, or throws ScenarioError with a one-line message. Anything else (another
// exception type, a crash, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace palpation::sim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scenario s;
  try {
    s = parse_scenario(text, "fuzz.json");
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.rfind("fuzz.json: ", 0) != 0) std::abort();
    return 0;
  }
  // A valid scenario serialises and parses back to the same JSON.
  const std::string once = scenario_to_json(s);
  Scenario back;
  try {
    back = parse_scenario(once, "fuzz.json");
  } catch (const ScenarioError&) {
    std::abort();
  }
  if (scenario_to_json(back) != once) std::abort();
  // Sampling the finger paths anywhere is finite.
  for (const auto& f : s.fingers)
    for (double t : {-1.0, 0.0, 0.5 * s.duration, s.duration, 1e9}) {
      Eigen::Vector3d x, v;
      f.sample(t, x, v);
      if (!x.allFinite() || !v.allFinite()) std::abort();
    }
  return 0;
}
