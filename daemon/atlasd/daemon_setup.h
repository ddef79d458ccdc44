#pragma once
// DaemonOptions (the configuration file) -> the options of each part atlasd runs: the device
// readers, the mapper and the step loop. One place, so that live runs and replay agree.

#include "core/mapper/mapper_factory.h"
#include "core/mapper/step_loop.h"
#include "daemon/config/daemon_options.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"

namespace atlas {

MapperSettings ToMapperSettings(const DaemonOptions& o);
StepLoopOptions ToStepLoopOptions(const DaemonOptions& o);
LaserReaderOptions ToLaserReaderOptions(const DaemonOptions& o);
OdometryReaderOptions ToOdometryReaderOptions(const DaemonOptions& o);
SonarReaderOptions ToSonarReaderOptions(const DaemonOptions& o);

// Every derived option set validated; empty when all are valid, else one line per problem.
std::string ValidateDerivedOptions(const DaemonOptions& o);

}  // namespace atlas
