// What the workstation's patient and simulation choosers offer, for the GUI (which does
// not reach into sim/): the backends of this build, the built-in phantoms, resolution
// levels.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scenario.h"

namespace palpation::app::live {

/// The backends this build can step with ("auto", "cpu", "cuda" where built).
std::vector<std::string> available_backends();

/// A built-in phantom by its chooser name: "phantom:breast" (the default patient: the
/// paper's breast and tumour) or "phantom:box" (a 10 x 10 x 5 cm block, no tumour);
/// nothing for other names.
std::optional<sim::Scenario> phantom_patient(const std::string& name);

/// The target edge length (m) of a named resolution level ("coarse", "paper", "fine")
/// for a phantom ("breast", "box"); nothing when unknown.
std::optional<double> resolution_edge(const std::string& phantom, const std::string& level);

/// An exam case from a file (a scenario: `palpation case generate`, or any scenario file)
/// as the workstation's patient: its patient, tissue and tumours, at the phantom
/// resolution `level`, with the workstation's real-time solver settings and no finger
/// paths of its own. Throws sim::ScenarioError naming the file, field and reason.
sim::Scenario case_patient(const std::string& path, const std::string& level);
/// The same for a scenario already in memory (a generated case, train::generate_case);
/// `source` names it in messages and the recording.
sim::Scenario case_patient(const sim::Scenario& file, const std::string& source, const std::string& level);

/// The workstation's resolution level when none is asked for: "paper" where a usable GPU
/// steps the simulation (the paper mesh runs there at the haptic rate, 0.5-0.8 ms a step:
/// docs/benchmarks.md), else "coarse" (the finest a 2-core CPU steps in about 1 ms).
std::string default_resolution(bool gpu_usable);
/// The same for this machine (sim::cuda_available: the backend "auto" picks).
std::string default_resolution();

/// Sets a phantom patient's resolution level and its edge length. False, and `s`
/// unchanged, for a patient with its own mesh or an unknown level.
bool set_phantom_resolution(sim::Scenario& s, const std::string& level);

}  // namespace palpation::app::live
