#include "core/grid/grid_options.h"

#include <cmath>

namespace atlas {
namespace {

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }
bool Probability(double p) { return p > 0.0 && p < 1.0; }

}  // namespace

std::string ProbabilityGridOptions::Validate() const {
  if (!(resolution >= 0.005 && resolution <= 1.0)) return "grid: resolution must be 0.005 to 1 m";
  if (max_cells < 16 || max_cells > 8192) return "grid: max_cells must be 16 to 8192";
  if (initial_cells < 8 || initial_cells > max_cells)
    return "grid: initial_cells must be 8 to max_cells";
  if (!Probability(min_probability) || !Probability(max_probability) ||
      !(min_probability < 0.5 && max_probability > 0.5))
    return "grid: need 0 < min_probability < 0.5 < max_probability < 1";
  if (!(hit_probability > 0.5 && hit_probability < 1.0))
    return "grid: hit_probability must be in (0.5, 1)";
  if (!(miss_probability > 0.0 && miss_probability < 0.5))
    return "grid: miss_probability must be in (0, 0.5)";
  return "";
}

std::string RangeScanOptions::Validate() const {
  if (!(min_range >= 0.0) || !(max_range > min_range) || !std::isfinite(max_range))
    return "grid range: need 0 <= min_range < max_range (finite)";
  if (!(no_return_free_range >= 0.0) || !(no_return_free_range <= max_range))
    return "grid range: no_return_free_range must be 0 to max_range";
  if (!(min_incidence >= 0.0 && min_incidence < 1.5))
    return "grid range: min_incidence must be 0 to 1.5 rad";
  return "";
}

std::string ScanAlignmentOptions::Validate() const {
  if (!(linear_window >= 0.0 && linear_window <= 2.0))
    return "grid alignment: linear_window must be 0 to 2 m";
  if (!(angular_window >= 0.0 && angular_window <= 1.0))
    return "grid alignment: angular_window must be 0 to 1 rad";
  if (!(min_angular_step > 0.0 && min_angular_step <= 0.1))
    return "grid alignment: min_angular_step must be in (0, 0.1] rad";
  if (max_iterations < 1 || max_iterations > 100)
    return "grid alignment: max_iterations must be 1 to 100";
  if (!Positive(convergence_step)) return "grid alignment: convergence_step must be > 0";
  if (min_points < 3) return "grid alignment: min_points must be 3 or more";
  if (!(min_score >= 0.0 && min_score < 1.0)) return "grid alignment: min_score must be in [0, 1)";
  if (!(degenerate_ratio > 0.0 && degenerate_ratio < 1.0))
    return "grid alignment: degenerate_ratio must be in (0, 1)";
  if (!Positive(normal_radius)) return "grid alignment: normal_radius must be > 0";
  if (!Positive(unconstrained_sigma)) return "grid alignment: unconstrained_sigma must be > 0";
  if (!Positive(min_residual_sigma)) return "grid alignment: min_residual_sigma must be > 0";
  return "";
}

std::string BranchAndBoundOptions::Validate() const {
  if (depth < 1 || depth > 12) return "grid search: depth must be 1 to 12";
  if (!(linear_window >= 0.0 && linear_window <= 50.0))
    return "grid search: linear_window must be 0 to 50 m";
  if (!(angular_window >= 0.0 && angular_window <= 3.15))
    return "grid search: angular_window must be 0 to pi";
  if (!(min_score >= 0.0 && min_score <= 1.0)) return "grid search: min_score must be in [0, 1]";
  if (!(peak_distance >= 0.0) || !std::isfinite(peak_distance))
    return "grid search: peak_distance must be 0 or more";
  if (!(peak_angle >= 0.0) || !std::isfinite(peak_angle))
    return "grid search: peak_angle must be 0 or more";
  if (!(rival_margin >= 0.0 && rival_margin <= 1.0))
    return "grid search: rival_margin must be in [0, 1]";
  return "";
}

std::string GridOptions::Validate() const {
  for (const std::string& e :
       {grid.Validate(), range.Validate(), alignment.Validate(), search.Validate()}) {
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace atlas
