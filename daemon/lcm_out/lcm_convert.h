#pragma once
// Conversion between atlasd's plain structs and the LCM types of lcmtypes/ (docs/lcm.md). Pure
// functions: no LCM instance, no I/O; the publisher (daemon/atlasd) sends what these return, and
// the replay path (daemon/atlasd) turns logged raw messages back into sensor structs with the
// inverse functions, so that live and replay feed the loop the same data.
//
// Times are atlas::Time (monotonic, ns) in, microseconds (utime) out, on the same clock; the
// raw conversions round-trip exactly at microsecond resolution. AtlasPublisher makes the utime
// of what it sends microseconds since the epoch (epoch_clock.h); the From* functions read a
// recording's utime as its stamp (a replay runs on the recording's clock).

#include <cstdint>
#include <string>

#include "atlasd/atlas_graph_t.hpp"
#include "atlasd/driver_health_t.hpp"
#include "atlasd/hypotheses_t.hpp"
#include "atlasd/laser_scan_t.hpp"
#include "atlasd/local_map_t.hpp"
#include "atlasd/odometry_t.hpp"
#include "atlasd/pose_t.hpp"
#include "atlasd/reference_pose_t.hpp"
#include "atlasd/sonar_t.hpp"
#include "core/atlas/atlas.h"
#include "core/common/sensor_types.h"
#include "daemon/lcm_out/reference_placement.h"
#include "drivers/device/driver_health.h"

namespace atlas {

// utime: whole microseconds (ToUtime truncates, as Truncate(t, kUtimeResolution) does).
inline constexpr Duration kUtimeResolution = std::chrono::microseconds(1);
int64_t ToUtime(Time t);
Time FromUtime(int64_t utime);

// The dominant pose (pose_t); frame_id -1 and q 0 when `dominant.valid` is false.
atlasd::pose_t ToPoseMessage(Time stamp, const DominantOutput& dominant);

// The dominant pose in the reference frame (reference_pose_t): `placed` is what
// ReferencePlacement::Place(dominant) returned; placed false and zeros without it.
atlasd::reference_pose_t ToReferencePoseMessage(Time stamp, const DominantOutput& dominant,
                                               FrameId reference,
                                               const std::optional<PlacedPose>& placed);

// The whole graph. Frames reached by a Dijkstra projection from the dominant frame (at most
// `max_projected` frames, for display) carry their pose in the dominant frame.
atlasd::atlas_graph_t ToGraphMessage(Time stamp, const Atlas& atlas, int max_projected = 256);

// Every hypothesis, the dominant one as STATE_DOMINANT.
atlasd::hypotheses_t ToHypothesesMessage(Time stamp, const Atlas& atlas);

// The map of the dominant frame with the robot pose in it; frame_id -1 and no lines when there
// is no dominant hypothesis.
atlasd::local_map_t ToLocalMapMessage(Time stamp, const Atlas& atlas);

// One driver's health and its queue ("laser", "odometry", "sonar").
atlasd::driver_health_t ToDriverHealthMessage(const std::string& name, const DriverHealth& h,
                                             int32_t queue_depth, int32_t queue_capacity);
int8_t ToDriverStateCode(DriverState s);

// Raw sensor data, both ways.
atlasd::laser_scan_t ToLaserMessage(const LaserScan& scan);
LaserScan FromLaserMessage(const atlasd::laser_scan_t& m);
atlasd::odometry_t ToOdometryMessage(const OdometrySample& sample);
OdometrySample FromOdometryMessage(const atlasd::odometry_t& m);
atlasd::sonar_t ToSonarMessage(const SonarReading& reading);
SonarReading FromSonarMessage(const atlasd::sonar_t& m);

}  // namespace atlas
