#include "tools/cli/odometry_noise_options.h"

namespace atlas::cli {

void AddOdometryNoiseOptions(CLI::App& app, const std::string& group,
                             WheelOdometryNoiseOptions* noise) {
  const WheelOdometryNoiseOptions d;
  auto dflt = [](double v) { return " (default " + HelpNumber(v) + ")"; };
  AddNumber(app, "--track-width", "M", 0.05, 10, &noise->track_width_m,
            "nominal track width, metres" + dflt(d.track_width_m))
      .Group(group);
  AddValue(
      app, "--odometry-noise", "LEVEL",
      [noise](const std::string& v) -> std::string {
        if (SetOdometryNoiseLevel(v, noise)) return "";
        return "--odometry-noise must be one of default or realistic, got '" + v + "'";
      },
      "default | realistic (below)")
      .Group(group);
  AddNumber(app, "--wheel-noise", "V", 0, 1, &noise->wheel_noise_per_m,
            "wheel distance variance per metre rolled, m^2/m" + dflt(d.wheel_noise_per_m))
      .Group(group);
  AddNumber(app, "--left-scale-error", "E", -0.5, 0.5, &noise->left_scale_error,
            "left wheel radius error, relative" + dflt(d.left_scale_error))
      .Group(group);
  AddNumber(app, "--right-scale-error", "E", -0.5, 0.5, &noise->right_scale_error,
            "right wheel radius error, relative" + dflt(d.right_scale_error))
      .Group(group);
  AddNumber(app, "--track-width-error", "E", -0.5, 0.5, &noise->track_width_error,
            "track width error, relative" + dflt(d.track_width_error))
      .Group(group);
}

}  // namespace atlas::cli
