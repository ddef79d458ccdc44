#include "tools/view/view_json.h"

#include <Eigen/Eigenvalues>
#include <charconv>
#include <cmath>
#include <vector>

#include "core/atlas/dijkstra_projection.h"
#include "core/eval/atlas_relations.h"

namespace atlas::view {

const char* DriverStateName(int8_t state) {
  switch (state) {
    case atlasd::driver_health_t::STATE_STOPPED:
      return "stopped";
    case atlasd::driver_health_t::STATE_CONNECTING:
      return "connecting";
    case atlasd::driver_health_t::STATE_RUNNING:
      return "running";
    case atlasd::driver_health_t::STATE_STALLED:
      return "stalled";
    case atlasd::driver_health_t::STATE_RECONNECTING:
      return "reconnecting";
    case atlasd::driver_health_t::STATE_FAILED:
      return "failed";
  }
  return "unknown";
}

const char* HypothesisStateName(int8_t state) {
  switch (state) {
    case atlasd::hypothesis_t::STATE_JUVENILE:
      return "juvenile";
    case atlasd::hypothesis_t::STATE_MATURE:
      return "mature";
    case atlasd::hypothesis_t::STATE_DOMINANT:
      return "dominant";
    case atlasd::hypothesis_t::STATE_RETIRED:
      return "retired";
  }
  return "unknown";
}

const char* EdgeKindCodeName(int8_t kind) {
  if (kind < 0 || kind > 2) return "unknown";
  return EdgeKindName(static_cast<EdgeKind>(kind));
}

Ellipse CovarianceEllipse(double sxx, double sxy, double syy, double scale) {
  Eigen::Matrix2d c;
  c << sxx, sxy, sxy, syy;
  if (!c.allFinite()) {
    const double nan = std::nan("");
    return {nan, nan, nan};
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c);
  const Eigen::Vector2d v = es.eigenvalues();  // ascending
  const Eigen::Vector2d major = es.eigenvectors().col(1);
  return {scale * std::sqrt(std::max(v(1), 0.0)), scale * std::sqrt(std::max(v(0), 0.0)),
          std::atan2(major.y(), major.x())};
}

std::string JsonString(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  for (char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\u00";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += ch;
    }
  }
  out += '"';
  return out;
}

namespace {

// A JSON object or array written field by field: commas are placed by the writer.
class Json {
 public:
  Json& Key(const char* key) {
    Comma();
    out_ += '"';
    out_ += key;
    out_ += "\":";
    after_key_ = true;
    return *this;
  }
  // A number with at most `decimals` decimals, trailing zeros removed; null when not finite.
  Json& Num(double v, int decimals = 3) {
    Comma();
    if (!std::isfinite(v)) {
      out_ += "null";
      return *this;
    }
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::fixed, decimals);
    if (ec != std::errc()) {
      out_ += "null";
      return *this;
    }
    std::string_view s(buf, static_cast<size_t>(end - buf));
    if (s.find('.') != std::string_view::npos) {
      while (s.back() == '0') s.remove_suffix(1);
      if (s.back() == '.') s.remove_suffix(1);
    }
    if (s == "-0") s = "0";
    out_ += s;
    return *this;
  }
  Json& Int(int64_t v) {
    Comma();
    out_ += std::to_string(v);
    return *this;
  }
  Json& Bool(bool v) {
    Comma();
    out_ += v ? "true" : "false";
    return *this;
  }
  Json& Str(std::string_view v) {
    Comma();
    out_ += JsonString(v);
    return *this;
  }
  Json& Null() {
    Comma();
    out_ += "null";
    return *this;
  }
  Json& Open(char bracket) {
    Comma();
    out_ += bracket;
    first_ = true;
    return *this;
  }
  Json& Close(char bracket) {
    out_ += bracket;
    first_ = false;
    return *this;
  }
  Json& Ellipse(const view::Ellipse& e) {
    Open('[').Num(e.a).Num(e.b).Num(e.angle, 4).Close(']');
    return *this;
  }
  std::string Take() { return std::move(out_); }

 private:
  void Comma() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (!first_) out_ += ',';
    first_ = false;
  }
  std::string out_;
  bool first_ = true;
  bool after_key_ = false;
};

Mat3 CovarianceOf(const double (&c)[9]) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(c);
}

view::Ellipse EllipseOf(const Mat3& cov) {
  return CovarianceEllipse(cov(0, 0), cov(0, 1), cov(1, 1), kEllipse95);
}

// A pose given in a frame's coordinates, carried into the source frame by the frame's projected
// pose (the covariance rotated with it; the frame's own uncertainty is drawn at its origin).
struct Placed {
  Pose2 pose;
  Mat3 cov;
};
Placed Place(const Pose2& frame_in_source, double x, double y, double theta, const double (&c)[9]) {
  const Pose2 local{x, y, theta};
  const Mat3 j = ComposeJacobianB(frame_in_source);
  return {Compose(frame_in_source, local), j * CovarianceOf(c) * j.transpose()};
}

void WritePlaced(Json& j, const Placed& p) {
  j.Key("x").Num(p.pose.x).Key("y").Num(p.pose.y).Key("th").Num(p.pose.theta, 4);
  j.Key("ell").Ellipse(EllipseOf(p.cov));
}

double Age(Time now, Time at) { return ToSeconds(now - at); }

void WriteHealth(Json& j, const Received<atlasd::health_t>& r, Time now) {
  const atlasd::health_t& h = r.message;
  j.Open('{');
  j.Key("status").Str(h.status).Key("version").Str(h.version);
  j.Key("uptime_s").Num(static_cast<double>(h.uptime_us) * 1e-6, 1).Key("steps").Int(h.steps);
  j.Key("frames").Int(h.num_frames).Key("edges").Int(h.num_edges);
  j.Key("juvenile").Int(h.num_juvenile).Key("mature").Int(h.num_mature);
  j.Key("retired").Int(h.num_retired).Key("dominant_frame").Int(h.dominant_frame_id);
  j.Key("step_median_us").Num(h.step_time_median_us, 0);
  j.Key("step_p99_us").Num(h.step_time_p99_us, 0).Key("step_max_us").Num(h.step_time_max_us, 0);
  j.Key("budget_us").Num(h.step_budget_us, 0).Key("overruns").Int(h.overruns);
  j.Key("dropped_scans").Int(h.dropped_scans).Key("rss_bytes").Int(h.resident_memory_bytes);
  j.Key("store_errors").Int(h.store_errors).Key("age_s").Num(Age(now, r.at), 1);
  j.Key("drivers").Open('[');
  for (const atlasd::driver_health_t& d : h.drivers) {
    j.Open('{');
    j.Key("name").Str(d.name).Key("device").Str(d.device);
    j.Key("state").Str(DriverStateName(d.state)).Key("rate_hz").Num(d.message_rate_hz, 1);
    j.Key("messages").Int(d.messages).Key("queue").Int(d.queue_depth);
    j.Key("queue_capacity").Int(d.queue_capacity).Key("queue_drops").Int(d.queue_drops);
    j.Key("errors").Int(d.bad_crc + d.bad_length + d.bad_messages + d.truncated + d.error_frames);
    j.Key("reconnects").Int(d.reconnects).Key("last_error").Str(d.last_error);
    j.Key("device_status").Str(d.device_status);
    j.Close('}');
  }
  j.Close(']');
  j.Close('}');
}

}  // namespace

std::string BuildViewJson(const ViewState& state, Time now, int max_frames) {
  Json j;
  j.Open('{');

  // The projection from the dominant frame.
  AtlasGraph graph;
  std::string graph_error;
  int frame_count = 0;
  if (state.graph()) {
    const atlasd::atlas_graph_t& g = state.graph()->message;
    std::vector<eval::EdgeRow> rows;
    rows.reserve(g.edges.size());
    for (const atlasd::atlas_edge_t& e : g.edges) {
      eval::EdgeRow row;
      row.from = e.frame_from;
      row.to = e.frame_to;
      row.to_in_from = UncertainPose{Pose2{e.x, e.y, e.theta}, CovarianceOf(e.covariance)};
      rows.push_back(row);
    }
    graph_error = eval::BuildGraphFromEdges(g.num_frames, rows, &graph);
    if (graph_error.empty()) frame_count = g.num_frames;
  }
  FrameId source = kNoFrame;
  if (state.pose() && state.pose()->message.frame_id >= 0 &&
      state.pose()->message.frame_id < frame_count)
    source = state.pose()->message.frame_id;
  else if (state.graph() && state.graph()->message.dominant_frame_id >= 0 &&
           state.graph()->message.dominant_frame_id < frame_count)
    source = state.graph()->message.dominant_frame_id;
  else if (frame_count > 0)
    source = 0;
  Projection projection;
  if (source != kNoFrame) {
    ProjectionLimits limits;
    limits.max_frames = max_frames;
    projection = DijkstraProjection(graph, source, limits);
  }
  std::vector<const ProjectedFrame*> placed(static_cast<size_t>(frame_count), nullptr);
  for (const ProjectedFrame& f : projection.entries) placed[static_cast<size_t>(f.frame)] = &f;
  auto find = [&](int32_t frame) -> const ProjectedFrame* {
    return frame >= 0 && frame < frame_count ? placed[static_cast<size_t>(frame)] : nullptr;
  };

  j.Key("source").Int(source);
  j.Key("graph_age_s");
  if (state.graph())
    j.Num(Age(now, state.graph()->at), 2);
  else
    j.Null();
  j.Key("hypotheses_age_s");
  if (state.hypotheses())
    j.Num(Age(now, state.hypotheses()->at), 2);
  else
    j.Null();
  j.Key("frames_total").Int(frame_count);
  j.Key("frames_drawn").Int(static_cast<int64_t>(projection.entries.size()));
  if (!graph_error.empty()) j.Key("graph_error").Str(graph_error);
  j.Key("frames").Open('[');
  for (const ProjectedFrame& f : projection.entries) {
    j.Open('{');
    j.Key("id").Int(f.frame).Key("x").Num(f.pose.mean.x).Key("y").Num(f.pose.mean.y);
    j.Key("th").Num(f.pose.mean.theta, 4).Key("hops").Int(f.hops);
    j.Key("ell").Ellipse(EllipseOf(f.pose.cov));
    j.Key("lines").Open('[');
    if (auto it = state.maps().find(f.frame); it != state.maps().end()) {
      const RigidTransform t(f.pose.mean);
      for (const atlasd::line_segment_t& l : it->second.message.lines) {
        const Vec2 a = t.Apply(Vec2(l.x0, l.y0)), b = t.Apply(Vec2(l.x1, l.y1));
        j.Open('[').Num(a.x()).Num(a.y()).Num(b.x()).Num(b.y()).Close(']');
      }
    }
    j.Close(']');
    j.Close('}');
  }
  j.Close(']');

  j.Key("edges").Open('[');
  if (state.graph() && graph_error.empty()) {
    for (const atlasd::atlas_edge_t& e : state.graph()->message.edges) {
      if (find(e.frame_from) == nullptr || find(e.frame_to) == nullptr) continue;
      j.Open('{').Key("a").Int(e.frame_from).Key("b").Int(e.frame_to);
      j.Key("kind").Str(EdgeKindCodeName(e.kind)).Close('}');
    }
  }
  j.Close(']');

  j.Key("pose");
  if (state.pose() && state.pose()->message.frame_id >= 0) {
    const atlasd::pose_t& p = state.pose()->message;
    const ProjectedFrame* f = find(p.frame_id);
    j.Open('{').Key("frame").Int(p.frame_id).Key("q").Num(p.q, 4);
    j.Key("placed").Bool(f != nullptr).Key("age_s").Num(Age(now, state.pose()->at), 2);
    if (f != nullptr) WritePlaced(j, Place(f->pose.mean, p.x, p.y, p.theta, p.covariance));
    j.Close('}');
  } else {
    j.Null();
  }

  j.Key("hypotheses").Open('[');
  if (state.hypotheses()) {
    for (const atlasd::hypothesis_t& h : state.hypotheses()->message.hypotheses) {
      const ProjectedFrame* f = find(h.frame_id);
      j.Open('{').Key("id").Int(h.id).Key("frame").Int(h.frame_id);
      j.Key("state").Str(HypothesisStateName(h.state)).Key("q").Num(h.q, 4);
      j.Key("steps").Int(h.steps).Key("placed").Bool(f != nullptr);
      if (f != nullptr) WritePlaced(j, Place(f->pose.mean, h.x, h.y, h.theta, h.covariance));
      j.Close('}');
    }
  }
  j.Close(']');

  j.Key("map");
  if (const Received<atlasd::local_map_t>* m = state.latest_map()) {
    j.Open('{').Key("frame").Int(m->message.frame_id).Key("lines").Int(m->message.num_lines);
    j.Key("capacity")
        .Int(m->message.capacity)
        .Key("remembered")
        .Int(static_cast<int64_t>(state.maps().size()));
    j.Key("age_s").Num(Age(now, m->at), 2).Close('}');
  } else {
    j.Null();
  }

  j.Key("health");
  if (state.health())
    WriteHealth(j, *state.health(), now);
  else
    j.Null();

  j.Close('}');
  return j.Take();
}

}  // namespace atlas::view
