#pragma once
// The "--key value" options of the evaluation tools' modes; their values are checked by
// core/common/parse_number.h (NumberArgument, IntegerArgument, SeedArgument).

#include <concepts>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/common/parse_number.h"

namespace atlas::eval {

// Options of the form "--key value" from argv[first..] (the evaluation tools' modes). A key not
// in `known`, or one without a value, sets `error` (naming it) and stops parsing.
struct ToolOptions {
  std::map<std::string, std::string> values;
  std::string error;
};
ToolOptions ParseToolOptions(int argc, char** argv, int first,
                             const std::vector<std::string>& known);
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

}  // namespace atlas::eval
