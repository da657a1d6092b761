// A scenario as a recording holds it: the header's, a patient change's, a parameter change's;
// and a recorded step's fingers as the simulation takes them again.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "model.h"
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

/// A "young" parameter event's changes, [[element, Pa], ...]: the well-formed pairs, an
/// element index beyond int's range as -1 (outside every mesh, for the caller's range
/// check to skip).
std::vector<std::pair<int, double>> recorded_young_changes(const nlohmann::json& event);

/// Whether the recording's "young" changes (the instructor's element moduli) name
/// elements in the patient mesh's own order rather than the model's: a recording whose
/// header's session has no "element_numbering", made before build_model renumbered
/// meshes for locality (sim::Model::mesh_tet).
bool young_in_mesh_order(const RecordingInfo& rec);

/// `changes` (element, Pa) with their elements in m's numbering: taken through
/// m.mesh_tet where `mesh_order`, else as they are. An index outside the mesh stays
/// outside it, for the caller's range check to skip.
std::vector<std::pair<int, double>> young_in_model_order(const sim::Model& m,
                                                         std::span<const std::pair<int, double>> changes,
                                                         bool mesh_order);

}  // namespace palpation::app::store
