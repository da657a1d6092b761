// Built-in scenarios: the paper's Fig. 6 experiment, a Hertz indentation, an idle scene.
#include <cmath>

#include "phantom.h"
#include "scenario.h"
#include "tissue_layers.h"

namespace palpation::sim {

namespace {

// The paper's Fig. 6: the index finger pushes and releases along z periodically while
// the hand sweeps along x over the tumour, left to right and back, twice.
// Pushes follow the skin (z of the dome at the current x) so every push reaches the same
// depth below the surface; the sweep spans 6 cm centred on the tumour. Layered: the same
// breast as skin, fat and glandular tissue (breast_layers), the tumour in the gland.
Scenario paper_sweep(bool tumour, bool layered = false) {
  Scenario s;
  s.source = std::string(layered ? "paper-sweep-layered" : "paper-sweep") + (tumour ? "" : "-no-tumour");
  if (layered) s.layers = breast_layers();
  s.patient.phantom = "breast";
  s.patient.resolution = "paper";
  s.patient.edge = *resolution_edge("breast", "paper");
  s.young_modulus = 19000.0;  // Krouskop (paper 4.1)
  s.poisson_ratio = 0.45;
  s.density = 1000.0;
  // Without the tumour the same region keeps the tissue's modulus: the mesh (refined
  // around the tumour) is identical, so the two sweeps differ only in stiffness.
  Inclusion inc;
  inc.shape = "sphere";
  // Centre 2 cm below the skin at the apex (top 5 mm under it). The paper puts it "on
  // the x axis"; with the chest wall on z = 0 that is a half ball against the fixed base,
  // which no push of the sweep can feel (tumour/no-tumour 1.004, docs/simulation.md).
  inc.center = Eigen::Vector3d(0.125, 0.0, 0.045);
  inc.radii = Eigen::Vector3d::Constant(0.015);
  inc.young_modulus = tumour ? 107000.0 : s.young_modulus;
  inc.poisson_ratio = 0.45;
  s.inclusions.push_back(inc);
  s.params.solver.dt = 0.001;
  s.params.contact.stiffness = 5000.0;  // N/m per fingertip cross-section of contact (params.h)
  s.params.contact.damping = 5.0;
  s.params.contact.force_filter_hz = 100.0;

  const BreastShape breast;
  const double x0 = 0.095, x1 = 0.155;  // sweep range, m (3 cm either side of the tumour)
  const double pass_time = 6.0;         // s per pass
  const double push_period = 0.4;       // s (x advances 4 mm per push)
  const double depth = 0.018;           // m below the skin at the deepest point (deep palpation)
  const double clearance = 0.003;       // m above the skin between pushes
  const double radius = 0.008;          // index fingertip
  const int passes = 4;                 // L->R, R->L, twice
  const double key_dt = 0.02;           // keyframe spacing, s
  FingerPath fp;
  fp.radius = radius;
  // The keys sample a smooth motion (a steady sweep, the cosine push): followed as a
  // monotone cubic, the finger's velocity is continuous as a hand's, not a jump every
  // 20 ms, and its turns (the top of a push, the end of a pass) are where the keys turn.
  fp.interpolation = PathInterpolation::MonotoneCubic;
  const double total = passes * pass_time;
  const int nkeys = static_cast<int>(std::lround(total / key_dt));
  for (int k = 0; k <= nkeys; ++k) {
    const double t = k * key_dt;
    const int pass = std::min(passes - 1, static_cast<int>(t / pass_time));
    const double u = (t - pass * pass_time) / pass_time;
    const double x = (pass % 2 == 0) ? x0 + u * (x1 - x0) : x1 - u * (x1 - x0);
    // Push profile: 0 (up) -> 1 (deepest) -> 0, smooth (1 - cos)/2 per period.
    const double phase = std::fmod(t, push_period) / push_period;
    const double press = 0.5 * (1.0 - std::cos(2.0 * M_PI * phase));
    const double skin = breast.surface_z(x, 0.0);
    const double z = skin + radius + clearance - press * (clearance + depth);
    fp.keys.push_back({t, x, 0.0, z});
  }
  s.fingers.push_back(fp);
  s.duration = total;
  return s;
}

// A rigid sphere (R = 1 cm) pressed slowly 1 mm (d/R = 0.1) into a 10 x 10 x 5 cm block,
// graded toward the contact. Hertz: F = 4/3 E/(1-nu^2) sqrt(R) d^1.5.
Scenario hertz() {
  Scenario s;
  s.source = "hertz";
  s.patient.phantom = "box";
  s.patient.size = Eigen::Vector3d(0.1, 0.1, 0.05);
  s.patient.grading = 2.0;
  s.patient.resolution = "paper";
  s.patient.edge = *resolution_edge("box", "paper");
  s.young_modulus = 19000.0;
  s.poisson_ratio = 0.45;
  s.params.contact.stiffness = 200000.0;  // stiff penalty: penetration ~5 um << 1 mm
  s.params.contact.damping = 5.0;
  const double R = 0.01, top = 0.05, d = 0.001;
  FingerPath fp;
  fp.radius = R;
  fp.keys = {{0.0, 0.0, 0.0, top + R + 0.0005}, {0.5, 0.0, 0.0, top + R}, {2.5, 0.0, 0.0, top + R - d}, {3.0, 0.0, 0.0, top + R - d}};
  s.fingers.push_back(fp);
  s.duration = 3.0;
  return s;
}

// No contact at all: the body at rest, for the idle-step benchmark.
Scenario idle() {
  Scenario s = paper_sweep(true);
  s.source = "idle";
  s.fingers.front().keys = {{0.0, 0.3, 0.0, 0.3}};
  s.duration = 1.0;
  return s;
}

}  // namespace

std::vector<std::string> builtin_scenario_names() {
  return {"paper-sweep", "paper-sweep-no-tumour", "paper-sweep-layered", "paper-sweep-layered-no-tumour", "hertz", "idle"};
}

Scenario builtin_scenario(const std::string& name) {
  if (name == "paper-sweep") return paper_sweep(true);
  if (name == "paper-sweep-no-tumour") return paper_sweep(false);
  if (name == "paper-sweep-layered") return paper_sweep(true, true);
  if (name == "paper-sweep-layered-no-tumour") return paper_sweep(false, true);
  if (name == "hertz") return hertz();
  if (name == "idle") return idle();
  std::string list;
  for (const auto& n : builtin_scenario_names()) list += (list.empty() ? "" : ", ") + n;
  throw ScenarioError("scenario: unknown built-in \"" + name + "\" (" + list + ")");
}

}  // namespace palpation::sim
