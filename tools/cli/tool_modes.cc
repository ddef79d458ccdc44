#include "tools/cli/tool_modes.h"

#include <CLI/CLI.hpp>

#include "tools/cli/command_line.h"

namespace atlas::cli {

int RunToolMode(int argc, char** argv, const char* tool, const std::string& modes_help,
                const std::vector<ToolMode>& modes) {
  CommandLine command_line(tool, {std::string(tool) + " MODE [options]"}, modes_help);
  ToolOptions options;
  std::string names;
  for (const ToolMode& mode : modes) {
    CLI::App* sub = command_line.app().add_subcommand(mode.name, mode.description);
    sub->group("Modes");
    for (const ToolModeOption& option : mode.options) {
      AddValue(
          *sub, option.name, option.value_name,
          [&options, key = option.name](const std::string& v) {
            options.values[key] = v;
            return std::string();
          },
          option.help);
    }
    names += (names.empty() ? "" : ", ") + mode.name;
  }
  bool known = argc < 2 || argv[1][0] == '-';
  for (const ToolMode& mode : modes) known = known || argv[1] == mode.name;
  if (!known)
    return command_line.Usage("unknown MODE '" + std::string(argv[1]) + "' (" + names + ")");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  for (const ToolMode& mode : modes) {
    if (command_line.app().got_subcommand(mode.name)) return mode.run(options);
  }
  return command_line.Usage("no MODE given (" + names + ")");
}

}  // namespace atlas::cli
