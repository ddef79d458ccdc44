#pragma once
// Summary statistics of a set of non-negative errors, as the SLAM benchmarks report them
// (Kümmerle et al., "On measuring the accuracy of SLAM algorithms", 2009): mean and standard
// deviation of the errors and of the squared errors, plus RMSE and maximum.

#include <cstdint>
#include <span>

namespace atlas::eval {

struct ErrorStats {
  int64_t count = 0;
  double mean = 0.0;
  double stddev = 0.0;  // population standard deviation (divides by count)
  double mean_squared = 0.0;
  double stddev_squared = 0.0;
  double rmse = 0.0;  // sqrt(mean_squared)
  double max = 0.0;
};

// All zero for an empty set.
ErrorStats Summarize(std::span<const double> errors);

}  // namespace atlas::eval
