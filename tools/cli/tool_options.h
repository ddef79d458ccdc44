#pragma once
// The option values of one mode of an evaluation tool ("atlas-sonar-eval mc --runs 5"), as read
// by RunToolMode (tool_modes.h), and their checks as numbers (core/common/parse_number.h:
// NumberArgument, IntegerArgument, SeedArgument), made by the mode that takes them.

#include <concepts>
#include <cstdint>
#include <map>
#include <string>

#include "core/common/parse_number.h"

namespace atlas::cli {

// The options given, by name ("--runs" -> "5"); an option not given has no entry.
struct ToolOptions {
  std::map<std::string, std::string> values;
};
// Reads option `key` as a number in [lo, hi] into `out`; true when absent (out unchanged) or
// valid, else false with `error` naming the key, the range and the value given.
bool GetNumberOption(const ToolOptions& options, const std::string& key, double lo, double hi,
                     double& out, std::string& error);
// The same for an integer option (IntegerArgument) and for a seed (SeedArgument).
template <std::integral Int>
bool GetIntegerOption(const ToolOptions& options, const std::string& key, int64_t lo, int64_t hi,
                      Int& out, std::string& error) {
  auto it = options.values.find(key);
  return it == options.values.end() || IntegerArgument(key, it->second.c_str(), lo, hi, out, error);
}
bool GetSeedOption(const ToolOptions& options, const std::string& key, uint64_t& out,
                   std::string& error);

}  // namespace atlas::cli
