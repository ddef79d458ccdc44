#pragma once
// --set name=value,name=value of atlas-localmap-eval's modes: overrides of the line EKF's
// options by their field names (range_sigma, model_sigma, ..., min_points and corner_points as
// integers).

#include <string>

#include "core/localmap/localmap_options.h"

namespace atlas::localmap_eval {

// Applies `spec` ("" changes nothing) to `o`; returns "" when every item is a known name with a
// number and the result is valid (LocalMapOptions::Validate), else what is wrong (a bad item
// lists the names).
std::string ApplyOverrides(const std::string& spec, LocalMapOptions& o);

}  // namespace atlas::localmap_eval
