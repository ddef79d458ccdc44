#pragma once
// Command-line helpers shared by the tools: a whole argument as a number or an integer with a
// range check and a message naming the option, and the "--key value" options of the evaluation
// tools' modes.

#include <concepts>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace atlas::eval {

// A whole command-line argument as a finite number.
bool ParseArgumentNumber(const char* s, double& out);

// A whole command-line argument as a decimal integer: digits with an optional leading '-'
// (std::from_chars; no '+', spaces, fraction or exponent: "1.5" and "1e3" are refused). False
// also when it does not fit the type.
bool ParseArgumentInteger(const char* s, int64_t& out);
bool ParseArgumentInteger(const char* s, uint64_t& out);

// `value` of `option` as a number (or an integer) in [lo, hi] into `out`; else false with
// `error` = "OPTION must be a number (an integer) in [LO, HI], got 'VALUE'". `out` is unchanged
// on error.
bool NumberArgument(std::string_view option, const char* value, double lo, double hi, double& out,
                    std::string& error);
bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi,
                     int64_t& out, std::string& error);
// A random seed: any integer in [0, 18446744073709551615].
bool SeedArgument(std::string_view option, const char* value, uint64_t& out, std::string& error);

// An integer option into a narrower type; [lo, hi] must lie within the type.
template <std::integral Int>
bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi, Int& out,
                     std::string& error) requires(!std::same_as<Int, int64_t>) {
  static_assert(sizeof(Int) < sizeof(int64_t) || std::is_signed_v<Int>);
  int64_t v = 0;
  if (!IntegerArgument(option, value, lo, hi, v, error)) return false;
  if (v < static_cast<int64_t>(std::numeric_limits<Int>::min()) ||
      v > static_cast<int64_t>(std::numeric_limits<Int>::max())) {
    error = std::string(option) + ": " + value + " does not fit";
    return false;
  }
  out = static_cast<Int>(v);
  return true;
}

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
// The same for an integer option (ParseArgumentInteger) and for a seed (SeedArgument).
template <std::integral Int>
bool GetIntegerOption(const ToolOptions& options, const std::string& key, int64_t lo, int64_t hi,
                      Int& out, std::string& error) {
  auto it = options.values.find(key);
  return it == options.values.end() || IntegerArgument(key, it->second.c_str(), lo, hi, out, error);
}
bool GetSeedOption(const ToolOptions& options, const std::string& key, uint64_t& out,
                   std::string& error);

}  // namespace atlas::eval
