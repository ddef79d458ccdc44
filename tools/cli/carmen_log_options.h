#pragma once
// The options of reading a CARMEN log (logs/carmen/carmen_log.h), one group shared by
// atlas-replay and atlas-carmen: the same names, help and ranges.

#include <string>

#include "logs/carmen/carmen_log.h"
#include "tools/cli/command_line.h"

namespace atlas::cli {

// Adds, in the help group `group`: --log-max-range M, --skip-bad-lines, --corrected (sets
// `*corrected`; the tool sets the line-order clock and the reference trajectory from it) and
// --line-period S, each into `options`.
void AddCarmenLogOptions(CLI::App& app, const std::string& group, carmen::CarmenLogOptions* options,
                         bool* corrected);

}  // namespace atlas::cli
