// A scenario as a recording holds it: the header's, a patient change's, a parameter change's;
// and a recorded step's fingers as the simulation takes them again.
#pragma once

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "params.h"
#include "scenario.h"
#include "store/recording.h"

namespace palpation::app::store {

/// Parses a recorded scenario (sim::ScenarioError naming `where` on bad input). Programs
/// that chose the element by Poisson's ratio appeared after recordings that wrote
/// "tissue.element" only for the nodal-pressure element: a recorded tissue without the key
/// is the linear element, at any ratio, so an older recording re-simulates as it ran.
sim::Scenario parse_recorded_scenario(const nlohmann::json& scenario, const std::string& where);

/// What a recorded step gave the simulation, as its inputs again (position, velocity,
/// radius, active) for the first in.size() fingers: a replay and a review re-simulate it.
void recorded_inputs(const RecordedStep& step, std::span<sim::FingerInput> in);

}  // namespace palpation::app::store
