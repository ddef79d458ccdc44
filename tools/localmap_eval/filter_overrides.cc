#include "tools/localmap_eval/filter_overrides.h"

#include <cmath>
#include <map>

#include "core/common/parse_number.h"

namespace atlas::localmap_eval {

std::string ApplyOverrides(const std::string& spec, LocalMapOptions& o) {
  const std::map<std::string, double*> table = {
      {"range_sigma", &o.extraction.range_sigma},
      {"model_sigma", &o.extraction.model_sigma},
      {"min_rho_sigma", &o.extraction.min_rho_sigma},
      {"min_alpha_sigma", &o.extraction.min_alpha_sigma},
      {"split_distance", &o.extraction.split_distance},
      {"min_length", &o.extraction.min_length},
      {"max_gap", &o.extraction.max_gap},
      {"fit_gate", &o.extraction.fit_gate},
      {"duplicate_rho", &o.association.duplicate_rho},
      {"duplicate_alpha", &o.association.duplicate_alpha},
      {"wheel_scale_sigma", &o.odometry.wheel_scale_sigma},
      {"wheel_var_per_m", &o.odometry.wheel_var_per_m},
      {"xy_var_per_m", &o.odometry.xy_var_per_m},
      {"xy_var_per_rad", &o.odometry.xy_var_per_rad},
      {"theta_var_per_m", &o.odometry.theta_var_per_m},
      {"theta_var_per_rad", &o.odometry.theta_var_per_rad},
      {"individual_gate", &o.association.individual_gate},
      {"joint_gate", &o.association.joint_gate},
      {"max_extent_gap", &o.association.max_extent_gap},
      {"ambiguity_margin", &o.association.ambiguity_margin},
      {"new_feature_min_length", &o.association.new_feature_min_length},
      {"new_feature_gate", &o.association.new_feature_gate},
      {"recovery_gate", &o.association.recovery_gate},
  };
  const std::map<std::string, int*> int_table = {
      {"min_points", &o.extraction.min_points},
      {"corner_points", &o.extraction.corner_points},
  };
  size_t pos = 0;
  while (pos < spec.size()) {
    size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    const size_t eq = item.find('=');
    double v = 0.0;
    const std::string name = eq == std::string::npos ? item : item.substr(0, eq);
    const bool is_int = int_table.count(name) > 0;
    if (eq == std::string::npos || (!table.count(name) && !is_int) ||
        !ParseNumber(item.substr(eq + 1).c_str(), &v) ||
        (is_int && (v != std::floor(v) || std::abs(v) > 1e6))) {
      std::string names;
      for (const auto& [n, p] : table) names += " " + n;
      for (const auto& [n, p] : int_table) names += " " + n + " (integer)";
      return "--set: bad item '" + item + "' (want name=number; names:" + names + ")";
    }
    if (is_int) {
      *int_table.at(name) = static_cast<int>(v);
    } else {
      *table.at(name) = v;
    }
    pos = end + 1;
  }
  return o.Validate();
}

}  // namespace atlas::localmap_eval
