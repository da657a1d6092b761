// palpation case generate --seed N --out FILE.json [--ranges RANGES.json] [--resolution R] [--answer]
// Generated exam cases (train/case_generator.h, docs/training.md "Cases and curricula").
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/cli.h"
#include "json_reader.h"
#include "train/case_generator.h"

namespace palpation::app::cli {

CommandAction add_case_command(CLI::App& app) {
  auto* sub = app.add_subcommand("case", "Generated exam cases: a breast with hidden tumours from a seed");
  sub->require_subcommand(1);
  struct Opts {
    std::string seed, out, ranges, resolution;
    bool answer = false;
  };
  auto o = std::make_shared<Opts>();
  auto* gen = sub->add_subcommand("generate", "Write the case of a seed as a scenario (JSON) that `palpation run` accepts");
  gen->add_option("--seed", o->seed, "Seed (a whole number >= 0): the same seed and ranges give the same case")->required();
  gen->add_option("--out", o->out, "Scenario file to write")->required();
  gen->add_option("--ranges", o->ranges, "JSON file of ranges (tumours, diameter, depth, hardness, base_radius, height, "
                                         "ellipsoid_fraction, tissue_young_modulus, resolution); default: docs/training.md");
  gen->add_option("--resolution", o->resolution, "Mesh resolution level: coarse, paper, fine, xfine (overrides the ranges')");
  gen->add_flag("--answer", o->answer, "Also print the tumours (for the instructor; never show it to the trainee)");

  return [o]() -> int {
    // Digits only: a "-1" must not wrap around to the largest seed.
    std::uint64_t seed = 0;
    {
      const bool digits = !o->seed.empty() && o->seed.size() <= 20 &&
                          o->seed.find_first_not_of("0123456789") == std::string::npos;
      errno = 0;
      if (digits) seed = std::strtoull(o->seed.c_str(), nullptr, 10);
      if (!digits || errno == ERANGE)
        throw sim::ScenarioError("--seed: must be a whole number from 0 to 18446744073709551615, got \"" + o->seed + "\"");
    }
    train::CaseRanges ranges;
    if (!o->ranges.empty()) {
      std::ifstream in(o->ranges, std::ios::binary);
      if (!in) throw sim::ScenarioError(o->ranges + ": (file): cannot be read");
      std::stringstream ss;
      ss << in.rdbuf();
      const sim::JsonReader rd(o->ranges, true);
      ranges = train::ranges_from_json(rd.parse(ss.str()), o->ranges, "");
    }
    if (!o->resolution.empty()) {
      if (!sim::resolution_edge("breast", o->resolution))
        throw sim::ScenarioError("--resolution: unknown level \"" + o->resolution + "\" (coarse, paper, fine, xfine)");
      ranges.resolution = o->resolution;
    }
    const train::GeneratedCase c = train::generate_case(seed, ranges, o->ranges.empty() ? "--seed" : o->ranges);
    // Staged: a temporary file renamed into place, so nothing is written half.
    namespace fs = std::filesystem;
    {
      std::ofstream f(o->out + ".tmp", std::ios::binary);
      f << sim::scenario_to_json(c.scenario) << "\n";
      if (!f) throw sim::ScenarioError(o->out + ": cannot be written");
    }
    std::error_code ec;
    fs::rename(o->out + ".tmp", o->out, ec);
    if (ec) {
      fs::remove(o->out + ".tmp", ec);
      throw sim::ScenarioError(o->out + ": cannot be written (" + ec.message() + ")");
    }
    std::printf("%s: difficulty %d (%s) -> %s\n", c.name.c_str(), c.difficulty, train::difficulty_name(c.difficulty), o->out.c_str());
    if (o->answer) std::printf("%s\n", train::case_summary(c, true).dump(2).c_str());
    return kExitOk;
  };
}

}  // namespace palpation::app::cli
