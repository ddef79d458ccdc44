#include "core/localmap/scan_observation.h"

#include "core/localmap/line_extraction.h"

namespace atlas {

const std::vector<ObservedLine>& ScanObservation::RobotFrameLines(
    const LineExtractionOptions& options) const {
  if (extracted_with_ != options) {
    lines_ = ExtractRobotFrameLines(scan_, options);
    extracted_with_ = options;
  }
  return lines_;
}

}  // namespace atlas
