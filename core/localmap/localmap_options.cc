#include "core/localmap/localmap_options.h"

#include <cmath>

namespace atlas {
namespace {

bool In(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }
bool Probability(double p) { return std::isfinite(p) && p > 0.0 && p < 1.0; }

}  // namespace

std::string LineExtractionOptions::Validate() const {
  if (!In(range_sigma, 0.0, 1.0)) return "extraction.range_sigma must be in [0, 1] m";
  if (!In(range_sigma_per_m, 0.0, 0.1)) return "extraction.range_sigma_per_m must be in [0, 0.1]";
  if (!In(model_sigma, 0.0, 1.0)) return "extraction.model_sigma must be in [0, 1] m";
  if (range_sigma <= 0.0 && range_sigma_per_m <= 0.0 && model_sigma <= 0.0)
    return "extraction: range_sigma, range_sigma_per_m and model_sigma cannot all be 0";
  if (!In(min_rho_sigma, 0.0, 10.0)) return "extraction.min_rho_sigma must be in [0, 10] m";
  if (!In(min_alpha_sigma, 0.0, 1.0)) return "extraction.min_alpha_sigma must be in [0, 1] rad";
  if (!In(split_distance, 1e-4, 10.0)) return "extraction.split_distance must be in [1e-4, 10] m";
  if (!In(max_gap, 1e-3, 100.0)) return "extraction.max_gap must be in [1e-3, 100] m";
  if (min_points < 3 || min_points > 10000) return "extraction.min_points must be in [3, 10000]";
  if (corner_points < 0 || corner_points > 100)
    return "extraction.corner_points must be in [0, 100]";
  if (!In(min_length, 0.0, 100.0)) return "extraction.min_length must be in [0, 100] m";
  if (!In(min_range, 0.0, 100.0)) return "extraction.min_range must be in [0, 100] m";
  if (!(fit_gate > 0.0 && fit_gate <= 1.0)) return "extraction.fit_gate must be in (0, 1]";
  if (max_lines < 1 || max_lines > 256) return "extraction.max_lines must be in [1, 256]";
  return "";
}

std::string OdometryNoiseOptions::Validate() const {
  if (!In(track_width, 0.01, 10.0)) return "odometry.track_width must be in [0.01, 10] m";
  if (!In(wheel_var_per_m, 0.0, 1.0)) return "odometry.wheel_var_per_m must be in [0, 1]";
  if (!In(xy_var_per_m, 0.0, 1.0)) return "odometry.xy_var_per_m must be in [0, 1]";
  if (!In(xy_var_per_rad, 0.0, 1.0)) return "odometry.xy_var_per_rad must be in [0, 1]";
  if (!In(theta_var_per_m, 0.0, 1.0)) return "odometry.theta_var_per_m must be in [0, 1]";
  if (!In(theta_var_per_rad, 0.0, 1.0)) return "odometry.theta_var_per_rad must be in [0, 1]";
  if (!In(wheel_scale_sigma, 0.0, 0.5)) return "odometry.wheel_scale_sigma must be in [0, 0.5]";
  if (!In(track_width_sigma, 0.0, 0.5)) return "odometry.track_width_sigma must be in [0, 0.5]";
  return "";
}

std::string AssociationOptions::Validate() const {
  if (!Probability(individual_gate)) return "association.individual_gate must be in (0, 1)";
  if (!Probability(joint_gate)) return "association.joint_gate must be in (0, 1)";
  if (!Probability(new_feature_gate)) return "association.new_feature_gate must be in (0, 1)";
  if (new_feature_gate < individual_gate)
    return "association.new_feature_gate must be >= association.individual_gate";
  if (recovery_min_pairings < 1) return "association.recovery_min_pairings must be at least 1";
  if (recovery_gate != 0.0 && (!Probability(recovery_gate) || recovery_gate < individual_gate ||
                               recovery_gate < joint_gate))
    return "association.recovery_gate must be 0 (off) or in (0, 1) and >= the individual and "
           "joint gates";
  if (!In(max_extent_gap, 0.0, 1e6)) return "association.max_extent_gap must be >= 0 m";
  if (node_budget < 1 || node_budget > 1000000)
    return "association.node_budget must be in [1, 1000000]";
  if (!In(ambiguity_margin, 0.0, 1e6)) return "association.ambiguity_margin must be >= 0";
  if (!In(new_feature_min_length, 0.0, 100.0))
    return "association.new_feature_min_length must be in [0, 100] m";
  if (!In(duplicate_rho, 0.0, 100.0)) return "association.duplicate_rho must be in [0, 100] m";
  if (!In(duplicate_alpha, 0.0, 3.2)) return "association.duplicate_alpha must be in [0, pi] rad";
  return "";
}

std::string QualityOptions::Validate() const {
  if (!In(alpha, 0.0, 1.0)) return "quality.alpha must be in [0, 1]";
  if (!In(max_sigma_x, 1e-9, 1e6) || !In(max_sigma_y, 1e-9, 1e6) || !In(max_sigma_theta, 1e-9, 1e6))
    return "quality.max_sigma_x, max_sigma_y, max_sigma_theta must be > 0";
  if (window < 1 || window > 64) return "quality.window must be in [1, 64] scans";
  return "";
}

std::string BootstrapOptions::Validate() const {
  if (min_matches < 2 || min_matches > 1000) return "bootstrap.min_matches must be in [2, 1000]";
  if (!In(min_angle_between, 0.0, 1.5707963))
    return "bootstrap.min_angle_between must be in [0, pi/2]";
  if (!Probability(residual_gate)) return "bootstrap.residual_gate must be in (0, 1)";
  if (iterations < 1 || iterations > 100) return "bootstrap.iterations must be in [1, 100]";
  return "";
}

std::string LocalMapOptions::Validate() const {
  if (capacity < 0 || capacity > 10000) return "capacity must be in [0, 10000] features";
  for (const std::string& e : {extraction.Validate(), odometry.Validate(), association.Validate(),
                               quality.Validate(), bootstrap.Validate()}) {
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace atlas
