#pragma once
// The mapper's part of atlasd's configuration (DaemonOptions, config/atlasd.toml) -> the options
// of core/mapper: the mapper's settings and the step loop's. Here, beside the file's schema, so
// that atlasd and the offline tools (atlas-replay --config) build the same mapper from one file
// without the daemon; the device readers' options are the daemon's (daemon/atlasd/
// daemon_setup.h). Unit conversions happen here: sigmas to variances, degrees to radians,
// seconds and milliseconds to Duration.

#include <string>
#include <vector>

#include "core/mapper/mapper_factory.h"
#include "core/mapper/step_loop.h"
#include "formats/config/daemon_options.h"

namespace atlas {

MapperSettings ToMapperSettings(const DaemonOptions& o);
// The transducer geometry sonar.ring names (drivers/p2os): for the maps and the sonar reader.
std::vector<SonarTransducer> SonarRingOf(SonarRing ring);
StepLoopOptions ToStepLoopOptions(const DaemonOptions& o);

// The mapper's and the step loop's Validate() on the options derived from `o`: empty when both
// accept them, else one line per problem ("atlas: ...", "loop: ..."). A DerivedCheck
// (config_loader.h) for the tools that run the mapper without devices.
std::string ValidateMapperOptions(const DaemonOptions& o);

}  // namespace atlas
