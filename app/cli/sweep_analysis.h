// Analysis of a palpation sweep (the paper's Fig. 6): the peak of fz over each push, and
// per pass (a monotonic run of the finger along x) the x where the largest push peak
// occurred.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "live/headless_run.h"

namespace palpation::app::cli {

using live::FingerSample;

struct PushPeak {
  double t, x, fz;   // time, finger x and fz at the peak of one push
  int pass;          // which pass it belongs to
};

struct PassPeak {
  int pass;
  double x, fz;      // x of the largest push peak in the pass, and that peak
  int direction;     // +1 left to right, -1 right to left
};

struct SweepAnalysis {
  std::vector<PushPeak> pushes;
  std::vector<PassPeak> passes;
  nlohmann::json to_json() const;
};

/// A push is a maximal run of ticks with fz above `threshold` times the largest fz;
/// passes split where the finger's x motion reverses.
SweepAnalysis analyze_sweep(const std::vector<FingerSample>& samples, int finger = 0, double threshold = 0.05);

/// Peak fz of the push nearest to x0 in each pass, for comparing two sweeps.
std::vector<double> peaks_near(const SweepAnalysis& a, double x0);

}  // namespace palpation::app::cli
