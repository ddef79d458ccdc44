#include "tools/eval/tool_options.h"

#include <algorithm>

namespace atlas::eval {

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
