#include "tools/monte_carlo/nees_band.h"

#include <algorithm>

#include "core/localmap/jcbb.h"

namespace atlas::mc {

NeesBand MeanNeesBand(int dof, int runs) {
  return {ChiSquareQuantile(0.025, dof * runs) / runs, ChiSquareQuantile(0.975, dof * runs) / runs};
}

StepMeans MeanPerStep(const std::vector<std::vector<double>>& per_run) {
  StepMeans out;
  if (per_run.empty()) return out;
  size_t steps = per_run[0].size();
  for (const auto& r : per_run) steps = std::min(steps, r.size());
  const int n = static_cast<int>(per_run.size());
  out.mean.resize(steps);
  out.known.resize(steps);
  for (size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    bool known = true;
    for (const auto& r : per_run) {
      known = known && r[k] != kNoNees;
      sum += r[k];
    }
    out.mean[k] = sum / n;
    out.known[k] = known;
  }
  return out;
}

BandSummary SummarizeInBand(const StepMeans& means, const NeesBand& band) {
  BandSummary s;
  double sum = 0.0;
  for (size_t k = 0; k < means.mean.size(); ++k) {
    if (!means.known[k]) continue;
    const double avg = means.mean[k];
    ++s.steps;
    sum += avg;
    s.max = std::max(s.max, avg);
    s.inside += avg >= band.lo && avg <= band.hi ? 1 : 0;
    s.below += avg <= band.hi ? 1 : 0;
  }
  s.mean = s.steps ? sum / s.steps : 0.0;
  return s;
}

}  // namespace atlas::mc
