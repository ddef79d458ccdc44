#include "tools/cli/tool_options.h"

namespace atlas::cli {

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

}  // namespace atlas::cli
