#include "core/eval/error_stats.h"

#include <algorithm>
#include <cmath>

namespace atlas::eval {
namespace {

// Mean and population standard deviation, two passes for accuracy.
void MeanStd(std::span<const double> v, bool squared, double& mean, double& stddev) {
  const auto value = [squared](double e) { return squared ? e * e : e; };
  double sum = 0.0;
  for (double e : v) sum += value(e);
  mean = sum / static_cast<double>(v.size());
  double var = 0.0;
  for (double e : v) var += (value(e) - mean) * (value(e) - mean);
  stddev = std::sqrt(var / static_cast<double>(v.size()));
}

}  // namespace

ErrorStats Summarize(std::span<const double> errors) {
  ErrorStats s;
  if (errors.empty()) return s;
  s.count = static_cast<int64_t>(errors.size());
  MeanStd(errors, false, s.mean, s.stddev);
  MeanStd(errors, true, s.mean_squared, s.stddev_squared);
  s.rmse = std::sqrt(s.mean_squared);
  s.max = *std::max_element(errors.begin(), errors.end());
  return s;
}

}  // namespace atlas::eval
