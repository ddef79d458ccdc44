#include "core/sonar/sonar_options.h"

namespace atlas {
namespace {

bool Prob(double p) { return p > 0.0 && p < 1.0; }

}  // namespace

std::string SonarModelOptions::Validate() const {
  if (!(range_sigma > 0.0) || !(range_sigma_per_m >= 0.0) || !(model_sigma >= 0.0))
    return "model.range_sigma: must be > 0 (range_sigma_per_m, model_sigma >= 0)";
  if (!(cone_scale >= 0.5 && cone_scale <= 3.0)) return "model.cone_scale: must be in [0.5, 3]";
  if (!(max_range_fraction > 0.0 && max_range_fraction <= 1.0))
    return "model.max_range_fraction: must be in (0, 1]";
  if (!(min_range >= 0.0)) return "model.min_range: must be >= 0";
  if (!(edge_incidence >= 0.0 && edge_incidence < 1.2))
    return "model.edge_incidence: must be in [0, 1.2) rad";
  return "";
}

std::string SonarUpdateOptions::Validate() const {
  if (!Prob(gate) || !Prob(loose_gate) || loose_gate < gate)
    return "update.gate: gate and loose_gate must be in (0, 1), loose_gate >= gate";
  if (!(max_extent_gap >= 0.0)) return "update.max_extent_gap: must be >= 0";
  if (!(ambiguity_margin >= 0.0)) return "update.ambiguity_margin: must be >= 0";
  if (!(behind_sigmas > 0.0)) return "update.behind_sigmas: must be > 0";
  if (!(duplicate_alpha >= 0.0 && duplicate_rho >= 0.0))
    return "update.duplicate_alpha: duplicate thresholds must be >= 0";
  return "";
}

std::string SonarInitOptions::Validate() const {
  if (max_returns < 2 || max_returns > 4096) return "init.max_returns: must be in [2, 4096]";
  if (max_vantage < 2 || max_vantage > 4096) return "init.max_vantage: must be in [2, 4096]";
  if (!(window_m > 0.0)) return "init.window_m: must be > 0";
  if (iterations < 1 || iterations > 100000) return "init.iterations: must be in [1, 100000]";
  if (!(min_pair_baseline >= 0.0) || !(min_baseline >= 0.0))
    return "init.min_baseline: baselines must be >= 0";
  if (!(inlier_sigmas > 0.0)) return "init.inlier_sigmas: must be > 0";
  if (min_support < 2 || min_vantage < 2) return "init.min_support: supports must be >= 2";
  if (!(rival_alpha > 0.0 && rival_rho > 0.0)) return "init.rival_alpha: must be > 0";
  if (!(rival_overlap > 0.0 && rival_overlap <= 1.0) || !(rival_ratio > 0.0 && rival_ratio <= 1.0))
    return "init.rival_overlap: overlap and ratio must be in (0, 1]";
  if (!(min_extent_ratio >= 0.0)) return "init.min_extent_ratio: must be >= 0";
  if (max_new_per_decision < 1) return "init.max_new_per_decision: must be >= 1";
  if (!(min_rho_sigma >= 0.0 && min_alpha_sigma >= 0.0)) return "init.min_rho_sigma: must be >= 0";
  return "";
}

std::string SonarLocalMapOptions::Validate() const {
  if (ring.size() > 64) return "ring: at most 64 transducers";
  for (const SonarTransducer& t : ring) {
    if (!(t.beam_width > 0.0 && t.beam_width < 3.14) || !(t.max_range > 0.0))
      return "ring: beam_width must be in (0, pi) and max_range > 0";
  }
  std::string e = line_map.Validate();
  if (e.empty()) e = model.Validate();
  if (e.empty()) e = update.Validate();
  if (e.empty()) e = init.Validate();
  return e;
}

}  // namespace atlas
