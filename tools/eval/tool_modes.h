#pragma once
// The one dispatch of the evaluation tools with modes ("atlas-sonar-eval mc --runs 5"): argv[1]
// names the mode, the rest are its "--key value" options (ToolOptions).

#include <string>
#include <vector>

#include "tools/eval/tool_options.h"

namespace atlas::eval {

struct ToolMode {
  const char* name;
  std::vector<std::string> keys;  // the options the mode takes
  int (*run)(const ToolOptions& options);
};

// No mode: `usage` on stderr, 2. "--help" or "-h": `usage` on stdout, 0. An unknown mode, or an
// option the mode does not take: "<tool>[ <mode>]: <what>" and `usage` on stderr, 2. Otherwise
// the mode's exit code.
int RunToolMode(int argc, char** argv, const char* tool, const char* usage,
                const std::vector<ToolMode>& modes);

}  // namespace atlas::eval
