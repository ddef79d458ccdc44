#pragma once
// The one dispatch of the evaluation tools with modes ("atlas-sonar-eval mc --runs 5"): argv[1]
// names the mode (a CLI11 subcommand), the rest are its "--key value" options (ToolOptions),
// read with command_line.h's conventions.

#include <string>
#include <vector>

#include "tools/cli/tool_options.h"

namespace atlas::cli {

// An option of a mode, with one value: its name ("--runs"), the value's name in the help ("N")
// and a one-line description that gives its default.
struct ToolModeOption {
  std::string name;
  std::string value_name;
  std::string help;
};

struct ToolMode {
  std::string name;
  std::string description;  // one line: what the mode does
  std::vector<ToolModeOption> options;
  int (*run)(const ToolOptions& options);
};

// `modes_help`: the modes and their options, printed by --help after "Usage: <tool> MODE
// [options]"; "<tool> MODE --help" prints the mode's description and options. --help, -h,
// --version: 0. No mode, an unknown mode, or an option the mode does not
// take (or without its value): "<tool>: <what>" and "Try '<tool> --help'." on stderr, 2.
// Otherwise the mode's exit code.
int RunToolMode(int argc, char** argv, const char* tool, const std::string& modes_help,
                const std::vector<ToolMode>& modes);

}  // namespace atlas::cli
