#include "tools/view/view_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace atlas::view {
namespace {

template <typename Message>
void FeedStored(ViewState& s, const std::string& channel, const Message& m, Time at) {
  std::vector<uint8_t> b(static_cast<size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  ASSERT_EQ(s.Ingest(channel, b.data(), b.size(), at), IngestResult::kStored) << channel;
}

atlasd::atlas_edge_t EdgeOf(int32_t from, int32_t to, double x, double y, double theta,
                           int8_t kind) {
  atlasd::atlas_edge_t e{};
  e.frame_from = from;
  e.frame_to = to;
  e.x = x;
  e.y = y;
  e.theta = theta;
  e.covariance[0] = e.covariance[4] = 0.01;
  e.covariance[8] = 0.001;
  e.kind = kind;
  e.origin = kind;
  return e;
}

// Frames 0 - 1 - 2: frame 1 at (1, 0, 90 deg) in frame 0 (Genesis), frame 2 at (1, 0, 0) in
// frame 1 (map-matching). Frame 1's map holds one line from (0, 0) to (2, 0).
void FeedGraph(ViewState& s, Time at) {
  atlasd::atlas_graph_t g{};
  g.dominant_frame_id = 0;
  g.num_frames = 3;
  for (int i = 0; i < 3; ++i) {
    atlasd::atlas_frame_t f{};
    f.id = i;
    g.frames.push_back(f);
  }
  g.edges.push_back(EdgeOf(0, 1, 1, 0, std::numbers::pi / 2, atlasd::atlas_edge_t::KIND_GENESIS));
  g.edges.push_back(EdgeOf(1, 2, 1, 0, 0, atlasd::atlas_edge_t::KIND_MAP_MATCH));
  g.num_edges = 2;
  FeedStored(s, "ATLAS_GRAPH", g, at);
  atlasd::local_map_t m{};
  m.frame_id = 1;
  m.capacity = 30;
  atlasd::line_segment_t l{};
  l.x1 = 2;
  m.lines.push_back(l);
  m.num_lines = 1;
  FeedStored(s, "ATLAS_LOCAL_MAP", m, at);
}

atlasd::pose_t PoseIn(int32_t frame, double x, double y, double theta) {
  atlasd::pose_t p{};
  p.frame_id = frame;
  p.x = x;
  p.y = y;
  p.theta = theta;
  p.covariance[0] = 4;
  p.covariance[4] = 1;
  p.covariance[8] = 0.01;
  p.q = 0.9;
  return p;
}

bool Has(const std::string& json, const std::string& part) {
  return json.find(part) != std::string::npos;
}

TEST(JsonString, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(JsonString("plain"), "\"plain\"");
  EXPECT_EQ(JsonString("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(JsonString(std::string("x\n\t\x01\x7f", 5)), "\"x\\u000a\\u0009\\u0001\\u007f\"");
  EXPECT_EQ(JsonString("caf\xc3\xa9"), "\"caf\xc3\xa9\"");  // UTF-8 as it is
}

TEST(CovarianceEllipse, AxesAreScaledSquareRootsOfTheEigenvalues) {
  const Ellipse e = CovarianceEllipse(4, 0, 1, 1);
  EXPECT_NEAR(e.a, 2, 1e-12);
  EXPECT_NEAR(e.b, 1, 1e-12);
  EXPECT_NEAR(std::sin(e.angle), 0, 1e-12);  // along x
  // The same covariance turned by 45 degrees.
  const Ellipse r = CovarianceEllipse(2.5, 1.5, 2.5, kEllipse95);
  EXPECT_NEAR(r.a, 2 * kEllipse95, 1e-12);
  EXPECT_NEAR(r.b, 1 * kEllipse95, 1e-12);
  EXPECT_NEAR(std::tan(r.angle), 1, 1e-9);
  EXPECT_TRUE(std::isnan(CovarianceEllipse(NAN, 0, 1, 1).a));
}

TEST(BuildViewJson, NothingReceivedYet) {
  ViewState s(ViewChannels{}, 10);
  const std::string j = BuildViewJson(s, FromSeconds(1), 100);
  EXPECT_TRUE(Has(j, "\"source\":-1")) << j;
  EXPECT_TRUE(Has(j, "\"frames\":[]")) << j;
  EXPECT_TRUE(Has(j, "\"pose\":null")) << j;
  EXPECT_TRUE(Has(j, "\"health\":null")) << j;
  EXPECT_EQ(j.front(), '{');
  EXPECT_EQ(j.back(), '}');
}

TEST(BuildViewJson, PlacesFramesLinesPoseAndHypothesesByTheProjection) {
  ViewState s(ViewChannels{}, 10);
  FeedGraph(s, FromSeconds(10));
  FeedStored(s, "ATLAS_POSE", PoseIn(0, 0.5, 0, 0), FromSeconds(10.5));
  atlasd::hypotheses_t hs{};
  atlasd::hypothesis_t h{};
  h.id = 42;
  h.frame_id = 1;
  h.state = atlasd::hypothesis_t::STATE_JUVENILE;
  h.q = 0.25;
  h.x = 1;
  h.covariance[0] = 4;
  h.covariance[4] = 1;
  hs.hypotheses.push_back(h);
  hs.num_hypotheses = 1;
  FeedStored(s, "ATLAS_HYPOTHESES", hs, FromSeconds(10));

  const std::string j = BuildViewJson(s, FromSeconds(11), 100);
  EXPECT_TRUE(Has(j, "\"source\":0,")) << j;
  EXPECT_TRUE(Has(j, "\"frames_total\":3,\"frames_drawn\":3")) << j;
  EXPECT_TRUE(Has(j, "{\"id\":0,\"x\":0,\"y\":0,\"th\":0,\"hops\":0,")) << j;
  EXPECT_TRUE(Has(j, "{\"id\":1,\"x\":1,\"y\":0,\"th\":1.5708,\"hops\":1,")) << j;
  EXPECT_TRUE(Has(j, "{\"id\":2,\"x\":1,\"y\":1,\"th\":1.5708,\"hops\":2,")) << j;
  // Frame 1's line (0, 0)-(2, 0), turned by 90 degrees and moved to (1, 0).
  EXPECT_TRUE(Has(j, "\"lines\":[[1,0,1,2]]")) << j;
  EXPECT_TRUE(Has(j, "{\"a\":0,\"b\":1,\"kind\":\"genesis\"}")) << j;
  EXPECT_TRUE(Has(j, "{\"a\":1,\"b\":2,\"kind\":\"map-match\"}")) << j;
  // The pose, in the dominant frame, its ellipse along x: 95 % of sigma 2 m and 1 m.
  EXPECT_TRUE(Has(j,
                  "\"pose\":{\"frame\":0,\"q\":0.9,\"placed\":true,\"age_s\":0.5,\"x\":0.5,"
                  "\"y\":0,\"th\":0,\"ell\":[4.895,2.448,"))
      << j;
  // The hypothesis at (1, 0) in frame 1 is at (1, 1) here, its ellipse turned along y.
  EXPECT_TRUE(Has(j,
                  "{\"id\":42,\"frame\":1,\"state\":\"juvenile\",\"q\":0.25,\"steps\":0,"
                  "\"placed\":true,\"x\":1,\"y\":1,\"th\":1.5708,\"ell\":[4.895,2.448,"))
      << j;
  EXPECT_TRUE(Has(j, "\"map\":{\"frame\":1,\"lines\":1,\"capacity\":30,\"remembered\":1,")) << j;
}

TEST(BuildViewJson, ProjectsFromThePosesFrame) {
  ViewState s(ViewChannels{}, 10);
  FeedGraph(s, FromSeconds(10));
  FeedStored(s, "ATLAS_POSE", PoseIn(1, 0, 0, 0), FromSeconds(10));
  const std::string j = BuildViewJson(s, FromSeconds(11), 100);
  EXPECT_TRUE(Has(j, "\"source\":1,")) << j;
  // Frame 0 seen from frame 1: the inverse of (1, 0, 90 deg).
  EXPECT_TRUE(Has(j, "{\"id\":0,\"x\":0,\"y\":1,\"th\":-1.5708,")) << j;
  EXPECT_TRUE(Has(j, "\"lines\":[[0,0,2,0]]")) << j;
}

TEST(BuildViewJson, DrawsAtMostMaxFramesAndOnlyTheirEdges) {
  ViewState s(ViewChannels{}, 10);
  FeedGraph(s, FromSeconds(10));
  FeedStored(s, "ATLAS_POSE", PoseIn(2, 0, 0, 0), FromSeconds(10));
  const std::string j = BuildViewJson(s, FromSeconds(11), 2);
  EXPECT_TRUE(Has(j, "\"frames_total\":3,\"frames_drawn\":2")) << j;
  EXPECT_FALSE(Has(j, "{\"id\":0,")) << j;
  EXPECT_TRUE(Has(j, "\"edges\":[{\"a\":1,\"b\":2,\"kind\":\"map-match\"}]")) << j;
}

TEST(BuildViewJson, APoseInAFrameTheGraphDoesNotHaveYetIsNotPlaced) {
  ViewState s(ViewChannels{}, 10);
  FeedGraph(s, FromSeconds(10));
  FeedStored(s, "ATLAS_POSE", PoseIn(3, 0, 0, 0), FromSeconds(10));
  const std::string j = BuildViewJson(s, FromSeconds(11), 100);
  EXPECT_TRUE(Has(j, "\"source\":0,")) << j;  // the graph's dominant frame
  EXPECT_TRUE(Has(j, "\"pose\":{\"frame\":3,\"q\":0.9,\"placed\":false,\"age_s\":1}")) << j;
}

TEST(BuildViewJson, AGraphThatIsNotOneIsNamedAndNotDrawn) {
  ViewState s(ViewChannels{}, 10);
  atlasd::atlas_graph_t g{};
  g.num_frames = 2;
  g.frames.resize(2);
  g.edges.push_back(EdgeOf(0, 5, 1, 0, 0, atlasd::atlas_edge_t::KIND_GENESIS));
  g.num_edges = 1;
  FeedStored(s, "ATLAS_GRAPH", g, FromSeconds(1));
  const std::string j = BuildViewJson(s, FromSeconds(1), 100);
  EXPECT_TRUE(Has(j, "\"graph_error\":\"edge 1 (0 -> 5) names a frame that does not exist\"")) << j;
  EXPECT_TRUE(Has(j, "\"frames\":[]")) << j;
}

TEST(BuildViewJson, HealthPanelWithEachDriversStateAndLastError) {
  ViewState s(ViewChannels{}, 10);
  atlasd::health_t h{};
  h.status = "mapping: 3 frames";
  h.version = "0.1.0";
  atlasd::driver_health_t laser{}, odometry{};
  laser.name = "laser";
  laser.device = "/dev/sick";
  laser.state = atlasd::driver_health_t::STATE_RECONNECTING;
  laser.last_error = "bad \"CRC\"\nthen silence";
  laser.bad_crc = 3;
  odometry.name = "odometry";
  odometry.state = atlasd::driver_health_t::STATE_RUNNING;
  odometry.message_rate_hz = 50;
  h.drivers = {laser, odometry};
  h.num_drivers = 2;
  FeedStored(s, "ATLAS_HEALTH", h, FromSeconds(1));
  const std::string j = BuildViewJson(s, FromSeconds(3), 100);
  EXPECT_TRUE(Has(j, "\"status\":\"mapping: 3 frames\",\"version\":\"0.1.0\"")) << j;
  EXPECT_TRUE(Has(j, "{\"name\":\"laser\",\"device\":\"/dev/sick\",\"state\":\"reconnecting\","))
      << j;
  EXPECT_TRUE(Has(j, "\"errors\":3,")) << j;
  EXPECT_TRUE(Has(j, "\"last_error\":\"bad \\\"CRC\\\"\\u000athen silence\"")) << j;
  EXPECT_TRUE(
      Has(j, "{\"name\":\"odometry\",\"device\":\"\",\"state\":\"running\",\"rate_hz\":50,"))
      << j;
  EXPECT_TRUE(Has(j, "\"age_s\":2,\"drivers\"")) << j;
}

TEST(BuildViewJson, NumbersThatAreNotFiniteAreNull) {
  ViewState s(ViewChannels{}, 10);
  FeedGraph(s, FromSeconds(1));
  FeedStored(s, "ATLAS_POSE", PoseIn(0, NAN, INFINITY, 0), FromSeconds(1));
  const std::string j = BuildViewJson(s, FromSeconds(1), 100);
  EXPECT_TRUE(Has(j, "\"x\":null,\"y\":null,")) << j;
  EXPECT_FALSE(Has(j, "nan")) << j;
  EXPECT_FALSE(Has(j, "inf")) << j;
}

TEST(StateNames, EveryCodeHasAName) {
  EXPECT_STREQ(DriverStateName(atlasd::driver_health_t::STATE_FAILED), "failed");
  EXPECT_STREQ(DriverStateName(99), "unknown");
  EXPECT_STREQ(HypothesisStateName(atlasd::hypothesis_t::STATE_DOMINANT), "dominant");
  EXPECT_STREQ(EdgeKindCodeName(atlasd::atlas_edge_t::KIND_REFINED), "refined");
  EXPECT_STREQ(EdgeKindCodeName(-1), "unknown");
}

}  // namespace
}  // namespace atlas::view
