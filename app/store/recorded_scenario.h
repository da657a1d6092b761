// A scenario as a recording holds it: the header's, a patient change's, a parameter change's.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "scenario.h"

namespace palpation::app::store {

/// Parses a recorded scenario (sim::ScenarioError naming `where` on bad input). Programs
/// that chose the element by Poisson's ratio appeared after recordings that wrote
/// "tissue.element" only for the nodal-pressure element: a recorded tissue without the key
/// is the linear element, at any ratio, so an older recording re-simulates as it ran.
sim::Scenario parse_recorded_scenario(const nlohmann::json& scenario, const std::string& where);

}  // namespace palpation::app::store
