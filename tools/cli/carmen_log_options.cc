#include "tools/cli/carmen_log_options.h"

namespace atlas::cli {

void AddCarmenLogOptions(CLI::App& app, const std::string& group, carmen::CarmenLogOptions* options,
                         bool* corrected) {
  AddNumber(app, "--log-max-range", "M", 0, 1e6, &options->max_range_m,
            "ranges >= M metres in the log are no-return (default: the line's own\n"
            "maximum, or 80 m for FLASER; aces-corrected clamps at 50)")
      .Group(group);
  AddFlag(app, "--skip-bad-lines", &options->skip_bad_lines,
          "count malformed log lines instead of stopping at the first")
      .Group(group);
  AddFlag(app, "--corrected", corrected,
          "a Radish \"corrected\" log: the line order is the clock and its poses are\n"
          "the reference trajectory, not odometry; wheel odometry is synthesised\n"
          "from them with seeded noise (the synthesised odometry options)")
      .Group(group);
  AddNumber(app, "--line-period", "S", 1e-6, 1, &options->line_period_s,
            "seconds per line for the line-order clock (default " +
                HelpNumber(carmen::CarmenLogOptions{}.line_period_s) + ")")
      .Group(group);
}

}  // namespace atlas::cli
