#pragma once
// DaemonOptions (the configuration file) -> the options of the device readers atlasd runs; the
// mapper's and the step loop's come from formats/config/mapper_config.h, shared with the
// offline tools, so that live runs and replay agree.

#include "daemon/lcm_in/lcm_input.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"
#include "formats/config/daemon_options.h"
#include "formats/config/mapper_config.h"

namespace atlas {

LaserReaderOptions ToLaserReaderOptions(const DaemonOptions& o);
OdometryReaderOptions ToOdometryReaderOptions(const DaemonOptions& o);
SonarReaderOptions ToSonarReaderOptions(const DaemonOptions& o);
// input.source = "lcm": the subscriber's options (lcm.url, the [input] keys, the laser's mount,
// maximum range and queue capacities).
LcmInputOptions ToLcmInputOptions(const DaemonOptions& o);

// Every derived option set validated (the mapper's, ValidateMapperOptions, and those of the
// enabled readers or of the LCM input); empty when all are valid, else one line per problem.
std::string ValidateDerivedOptions(const DaemonOptions& o);

}  // namespace atlas
