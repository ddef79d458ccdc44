#include "tools/eval/tool_modes.h"

#include <cstdio>
#include <cstring>

#include "core/common/version.h"

namespace atlas::eval {

int RunToolMode(int argc, char** argv, const char* tool, const char* usage,
                const std::vector<ToolMode>& modes) {
  if (argc >= 2 && std::strcmp(argv[1], "--version") == 0) {
    std::fputs(VersionLine(tool).c_str(), stdout);
    return 0;
  }
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::fputs(usage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  for (const ToolMode& mode : modes) {
    if (std::strcmp(argv[1], mode.name) != 0) continue;
    const ToolOptions options = ParseToolOptions(argc, argv, 2, mode.keys);
    if (!options.error.empty()) {
      std::fprintf(stderr, "%s %s: %s\n%s", tool, mode.name, options.error.c_str(), usage);
      return 2;
    }
    return mode.run(options);
  }
  std::fprintf(stderr, "%s: unknown command '%s'\n%s", tool, argv[1], usage);
  return 2;
}

}  // namespace atlas::eval
