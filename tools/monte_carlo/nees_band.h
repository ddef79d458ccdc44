#pragma once
// NEES consistency over seeded Monte Carlo runs (Bar-Shalom, Li, Kirubarajan, "Estimation with
// Applications to Tracking and Navigation", 5.4.2): at each step the NEES averaged over the
// runs, against the two-sided 95 % band of that average for a consistent filter.

#include <vector>

namespace atlas::mc {

// The 95 % band of the average of `runs` independent chi-square(`dof`) values:
// [chi2_0.025(dof * runs), chi2_0.975(dof * runs)] / runs.
struct NeesBand {
  double lo = 0.0, hi = 0.0;
};
NeesBand MeanNeesBand(int dof, int runs);

// A run's NEES at a step where it has none (say, no ground truth for its frame).
inline constexpr double kNoNees = -1.0;

// Per step, the NEES averaged over the runs (`per_run[r][k]`), for the steps every run has (the
// shortest run). `known[k]` is false where a run has kNoNees, and `mean[k]` then means nothing.
struct StepMeans {
  std::vector<double> mean;
  std::vector<bool> known;
};
StepMeans MeanPerStep(const std::vector<std::vector<double>>& per_run);

// The known steps' averages against `band`.
struct BandSummary {
  int steps = 0;    // known steps
  int inside = 0;   // average within [lo, hi]
  int below = 0;    // average at most hi
  double mean = 0;  // mean of the averages (0 without known steps)
  double max = 0;   // largest average (0 without known steps)
  double InsidePercent() const { return steps ? 100.0 * inside / steps : 0.0; }
  double BelowPercent() const { return steps ? 100.0 * below / steps : 0.0; }
};
BandSummary SummarizeInBand(const StepMeans& means, const NeesBand& band);

}  // namespace atlas::mc
