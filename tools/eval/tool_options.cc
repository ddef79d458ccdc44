#include "tools/eval/tool_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/common/parse_number.h"

namespace atlas::eval {
namespace {

std::string Shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

}  // namespace

bool ParseArgumentNumber(const char* s, double& out) { return ParseNumber(s, &out); }
bool ParseArgumentInteger(const char* s, int64_t& out) { return ParseInteger(s, &out); }
bool ParseArgumentInteger(const char* s, uint64_t& out) { return ParseInteger(s, &out); }

bool NumberArgument(std::string_view option, const char* value, double lo, double hi, double& out,
                    std::string& error) {
  double v = 0.0;
  if (!ParseArgumentNumber(value, v) || v < lo || v > hi) {
    error = std::string(option) + " must be a number in [" + Shortest(lo) + ", " + Shortest(hi) +
            "], got '" + value + "'";
    return false;
  }
  out = v;
  return true;
}

bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi,
                     int64_t& out, std::string& error) {
  int64_t v = 0;
  if (!ParseArgumentInteger(value, v) || v < lo || v > hi) {
    error = std::string(option) + " must be an integer in [" + std::to_string(lo) + ", " +
            std::to_string(hi) + "], got '" + value + "'";
    return false;
  }
  out = v;
  return true;
}

bool SeedArgument(std::string_view option, const char* value, uint64_t& out, std::string& error) {
  if (!ParseArgumentInteger(value, out)) {
    error = std::string(option) + " must be an integer in [0, " +
            std::to_string(std::numeric_limits<uint64_t>::max()) + "], got '" + value + "'";
    return false;
  }
  return true;
}

ToolOptions ParseToolOptions(int argc, char** argv, int first,
                             const std::vector<std::string>& known) {
  ToolOptions a;
  for (int i = first; i < argc; ++i) {
    const std::string k = argv[i];
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      a.error = "unknown option '" + k + "'";
      return a;
    }
    if (i + 1 >= argc) {
      a.error = "option '" + k + "' needs a value";
      return a;
    }
    a.values[k] = argv[++i];
  }
  return a;
}

bool GetNumberOption(const ToolOptions& options, const std::string& key, double lo, double hi,
                     double& out, std::string& error) {
  auto it = options.values.find(key);
  return it == options.values.end() || NumberArgument(key, it->second.c_str(), lo, hi, out, error);
}

bool GetSeedOption(const ToolOptions& options, const std::string& key, uint64_t& out,
                   std::string& error) {
  auto it = options.values.find(key);
  return it == options.values.end() || SeedArgument(key, it->second.c_str(), out, error);
}

}  // namespace atlas::eval
