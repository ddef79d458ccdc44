#include "sim/reference_odometry.h"

#include <algorithm>
#include <cassert>

namespace atlas::carmen {

std::vector<CarmenEvent> EventsWithSynthesizedOdometry(const CarmenLog& log,
                                                       const WheelOdometryNoiseOptions& noise,
                                                       uint64_t seed) {
  assert(noise.Validate().empty());
  WheelOdometryModel model(noise, seed);
  std::vector<CarmenEvent> out;
  out.reserve(log.events.size() + log.reference.size());
  for (const ReferencePose& r : log.reference) {
    CarmenEvent e;
    e.line = r.line;
    e.message = "ODOM";
    e.log_timestamp = ToSeconds(r.truth.stamp);
    e.event = model.Step(r.truth);
    out.push_back(std::move(e));
  }
  const size_t n_odometry = out.size();
  out.insert(out.end(), log.events.begin(), log.events.end());
  // Both halves are time-ordered; merging keeps an odometry sample ahead of a scan on ties.
  std::inplace_merge(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n_odometry), out.end(),
                     [](const CarmenEvent& a, const CarmenEvent& b) {
                       return StampOf(a.event) < StampOf(b.event);
                     });
  return out;
}

}  // namespace atlas::carmen
