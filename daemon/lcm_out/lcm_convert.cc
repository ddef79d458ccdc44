#include "daemon/lcm_out/lcm_convert.h"

#include <algorithm>

#include "core/atlas/dijkstra_projection.h"

namespace atlas {
namespace {

void CopyCov3(const Mat3& m, double out[9]) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[3 * r + c] = m(r, c);
}

}  // namespace

int64_t ToUtime(Time t) { return t.time_since_epoch().count() / 1000; }
Time FromUtime(int64_t utime) { return Time(Duration(utime * 1000)); }

atlasd::pose_t ToPoseMessage(Time stamp, const DominantOutput& d) {
  atlasd::pose_t m{};
  m.utime = ToUtime(stamp);
  m.frame_id = d.valid ? d.frame : -1;
  m.x = d.pose.mean.x;
  m.y = d.pose.mean.y;
  m.theta = d.pose.mean.theta;
  CopyCov3(d.pose.cov, m.covariance);
  m.q = d.valid ? d.q : 0.0;
  m.hypothesis_id = d.valid ? d.hypothesis : -1;
  m.switched = d.valid && d.switched;
  return m;
}

atlasd::reference_pose_t ToReferencePoseMessage(Time stamp, const DominantOutput& d,
                                               FrameId reference,
                                               const std::optional<PlacedPose>& placed) {
  atlasd::reference_pose_t m{};
  m.utime = ToUtime(stamp);
  m.reference_frame_id = reference;
  m.frame_id = d.valid ? d.frame : -1;
  m.placed = placed.has_value();
  if (!placed) return m;
  m.x = placed->pose.mean.x;
  m.y = placed->pose.mean.y;
  m.theta = placed->pose.mean.theta;
  CopyCov3(placed->pose.cov, m.covariance);
  m.frame_x = placed->frame.mean.x;
  m.frame_y = placed->frame.mean.y;
  m.frame_theta = placed->frame.mean.theta;
  CopyCov3(placed->frame.cov, m.frame_covariance);
  m.hops = placed->hops;
  m.q = d.q;
  return m;
}

atlasd::atlas_graph_t ToGraphMessage(Time stamp, const Atlas& atlas, int max_projected) {
  const AtlasGraph& g = atlas.Graph();
  const DominantOutput d = atlas.Dominant();
  atlasd::atlas_graph_t m{};
  m.utime = ToUtime(stamp);
  m.step = atlas.StepCount();
  m.dominant_frame_id = d.valid ? d.frame : -1;
  Projection projection;
  if (d.valid && g.HasFrame(d.frame)) {
    ProjectionLimits limits;
    limits.max_frames = max_projected;
    projection = DijkstraProjection(g, d.frame, limits);
  }
  m.num_frames = g.FrameCount();
  m.frames.resize(m.num_frames);
  for (FrameId id = 0; id < g.FrameCount(); ++id) {
    const MapFrame& f = g.Frame(id);
    atlasd::atlas_frame_t& out = m.frames[id];
    out.id = id;
    out.num_features = f.map ? f.map->Complexity() : 0;
    out.created_step = f.created_step;
    out.degree = static_cast<int32_t>(f.edges.size());
    const ProjectedFrame* p = projection.Find(id);
    out.projected = p != nullptr;
    if (p != nullptr) {
      out.x = p->pose.mean.x;
      out.y = p->pose.mean.y;
      out.theta = p->pose.mean.theta;
    }
  }
  m.num_edges = g.EdgeCount();
  m.edges.resize(m.num_edges);
  for (int i = 0; i < g.EdgeCount(); ++i) {
    const AtlasEdge& e = g.Edge(i);
    atlasd::atlas_edge_t& out = m.edges[i];
    out.frame_from = e.a;
    out.frame_to = e.b;
    out.x = e.b_in_a.mean.x;
    out.y = e.b_in_a.mean.y;
    out.theta = e.b_in_a.mean.theta;
    CopyCov3(e.b_in_a.cov, out.covariance);
    out.kind = static_cast<int8_t>(e.kind);
    out.origin = static_cast<int8_t>(e.origin);
    out.refinements = e.refinements;
  }
  return m;
}

atlasd::hypotheses_t ToHypothesesMessage(Time stamp, const Atlas& atlas) {
  atlasd::hypotheses_t m{};
  m.utime = ToUtime(stamp);
  m.dominant_id = -1;
  for (const Hypothesis& h : atlas.Hypotheses()) {
    atlasd::hypothesis_t out{};
    out.id = h.id;
    out.frame_id = h.frame;
    switch (h.state) {
      case HypothesisState::kJuvenile:
        out.state = 0;
        break;
      case HypothesisState::kMature:
        out.state = h.dominant ? 2 : 1;
        break;
      case HypothesisState::kRetired:
        out.state = 3;
        break;
    }
    if (h.dominant) m.dominant_id = h.id;
    out.q = h.q;
    out.steps = h.steps;
    if (h.state != HypothesisState::kRetired) {
      const UncertainPose p = atlas.PoseOf(h);
      out.x = p.mean.x;
      out.y = p.mean.y;
      out.theta = p.mean.theta;
      CopyCov3(p.cov, out.covariance);
    }
    m.hypotheses.push_back(out);
  }
  m.num_hypotheses = static_cast<int32_t>(m.hypotheses.size());
  return m;
}

atlasd::local_map_t ToLocalMapMessage(Time stamp, const Atlas& atlas) {
  atlasd::local_map_t m{};
  m.utime = ToUtime(stamp);
  m.frame_id = -1;
  const DominantOutput d = atlas.Dominant();
  const AtlasGraph& g = atlas.Graph();
  if (!d.valid || !g.HasFrame(d.frame) || !g.Frame(d.frame).map) return m;
  const LocalMap& map = *g.Frame(d.frame).map;
  m.frame_id = d.frame;
  m.capacity = map.Capacity();
  m.robot_x = d.pose.mean.x;
  m.robot_y = d.pose.mean.y;
  m.robot_theta = d.pose.mean.theta;
  for (const MapLine& l : map.Lines()) {
    atlasd::line_segment_t s{};
    s.id = l.id;
    s.rho = l.rho;
    s.alpha = l.alpha;
    s.covariance[0] = l.cov(0, 0);
    s.covariance[1] = l.cov(0, 1);
    s.covariance[2] = l.cov(1, 0);
    s.covariance[3] = l.cov(1, 1);
    s.x0 = l.endpoint_a.x();
    s.y0 = l.endpoint_a.y();
    s.x1 = l.endpoint_b.x();
    s.y1 = l.endpoint_b.y();
    m.lines.push_back(s);
  }
  m.num_lines = static_cast<int32_t>(m.lines.size());
  return m;
}

int8_t ToDriverStateCode(DriverState s) {
  switch (s) {
    case DriverState::kStopped:
      return 0;
    case DriverState::kConnecting:
      return 1;
    case DriverState::kRunning:
      return 2;
    case DriverState::kStalled:
      return 3;
    case DriverState::kReconnecting:
      return 4;
    case DriverState::kFailed:
      return 5;
  }
  return 0;
}

atlasd::driver_health_t ToDriverHealthMessage(const std::string& name, const DriverHealth& h,
                                             int32_t queue_depth, int32_t queue_capacity) {
  atlasd::driver_health_t m{};
  m.name = name;
  m.device = h.device;
  m.state = ToDriverStateCode(h.state);
  m.queue_depth = queue_depth;
  m.queue_capacity = queue_capacity;
  m.queue_drops = static_cast<int64_t>(h.drops);
  m.bytes = static_cast<int64_t>(h.bytes);
  m.messages = static_cast<int64_t>(h.messages);
  m.bad_crc = static_cast<int64_t>(h.bad_crc);
  m.bad_length = static_cast<int64_t>(h.bad_length);
  m.garbage_bytes = static_cast<int64_t>(h.garbage_bytes);
  m.bad_messages = static_cast<int64_t>(h.bad_messages);
  m.truncated = static_cast<int64_t>(h.truncated);
  m.discontinuities = static_cast<int64_t>(h.discontinuities);
  m.error_frames = static_cast<int64_t>(h.error_frames);
  m.stalls = static_cast<int64_t>(h.stalls);
  m.disconnects = static_cast<int64_t>(h.disconnects);
  m.reconnects = static_cast<int64_t>(h.reconnects);
  m.connect_failures = static_cast<int64_t>(h.connect_failures);
  m.message_rate_hz = static_cast<float>(h.message_rate_hz);
  m.last_error = h.last_error;
  m.device_status = h.device_status;
  return m;
}

atlasd::laser_scan_t ToLaserMessage(const LaserScan& scan) {
  atlasd::laser_scan_t m{};
  m.utime = ToUtime(scan.stamp);
  m.angle_min = scan.angle_min;
  m.angle_increment = scan.angle_increment;
  m.max_range = scan.max_range;
  m.num_ranges = static_cast<int32_t>(scan.ranges.size());
  m.ranges = scan.ranges;
  m.sensor_x = scan.sensor_pose.x;
  m.sensor_y = scan.sensor_pose.y;
  m.sensor_theta = scan.sensor_pose.theta;
  return m;
}

LaserScan FromLaserMessage(const atlasd::laser_scan_t& m) {
  LaserScan s;
  s.stamp = FromUtime(m.utime);
  s.angle_min = m.angle_min;
  s.angle_increment = m.angle_increment;
  s.max_range = m.max_range;
  s.ranges = m.ranges;
  s.sensor_pose = Pose2{m.sensor_x, m.sensor_y, m.sensor_theta};
  return s;
}

atlasd::odometry_t ToOdometryMessage(const OdometrySample& sample) {
  atlasd::odometry_t m{};
  m.utime = ToUtime(sample.stamp);
  m.x = sample.pose.x;
  m.y = sample.pose.y;
  m.theta = sample.pose.theta;
  m.left_m = sample.left_m;
  m.right_m = sample.right_m;
  m.linear_velocity = sample.linear_velocity;
  m.angular_velocity = sample.angular_velocity;
  return m;
}

OdometrySample FromOdometryMessage(const atlasd::odometry_t& m) {
  OdometrySample s;
  s.stamp = FromUtime(m.utime);
  s.pose = Pose2{m.x, m.y, m.theta};
  s.left_m = m.left_m;
  s.right_m = m.right_m;
  s.linear_velocity = m.linear_velocity;
  s.angular_velocity = m.angular_velocity;
  return s;
}

atlasd::sonar_t ToSonarMessage(const SonarReading& reading) {
  atlasd::sonar_t m{};
  m.utime = ToUtime(reading.stamp);
  m.num_returns = static_cast<int32_t>(reading.returns.size());
  for (const SonarReturn& r : reading.returns) {
    m.transducer.push_back(static_cast<int16_t>(r.transducer));
    m.range.push_back(r.range);
  }
  return m;
}

SonarReading FromSonarMessage(const atlasd::sonar_t& m) {
  SonarReading s;
  s.stamp = FromUtime(m.utime);
  const size_t n = std::min(m.transducer.size(), m.range.size());
  for (size_t i = 0; i < n; ++i) s.returns.push_back(SonarReturn{m.transducer[i], m.range[i]});
  return s;
}

}  // namespace atlas
