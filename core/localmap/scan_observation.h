#pragma once
// One laser scan as every local map of a step sees it: the scan and its robot-frame lines
// (ExtractRobotFrameLines, line_extraction.h), extracted at most once per extraction options.
//
// The Atlas steps every live hypothesis with the same scan (paper, Section III); the line maps
// of all hypotheses extract the same lines, so the observation extracts them on the first
// request and hands the same lines to later requests with equal options. A request with other
// options extracts again and replaces the kept lines. The lines are exactly those of
// ExtractRobotFrameLines(scan(), options): the cache never changes a result.
//
// A value type (copies carry the lines already extracted); not thread-safe (the first request
// writes the cache).

#include <optional>
#include <utility>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/localmap/line_model.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

class ScanObservation {
 public:
  ScanObservation() = default;
  explicit ScanObservation(LaserScan scan) : scan_(std::move(scan)) {}

  const LaserScan& scan() const { return scan_; }

  // ExtractRobotFrameLines(scan(), options); `options` must be valid. The reference stays valid
  // until a request with other options, or the observation's end.
  const std::vector<ObservedLine>& RobotFrameLines(const LineExtractionOptions& options) const;

 private:
  LaserScan scan_;
  mutable std::optional<LineExtractionOptions> extracted_with_;
  mutable std::vector<ObservedLine> lines_;
};

}  // namespace atlas
