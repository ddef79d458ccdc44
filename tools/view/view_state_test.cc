#include "tools/view/view_state.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

namespace atlas::view {
namespace {

template <typename Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

template <typename Message>
IngestResult Feed(ViewState& s, const std::string& channel, const Message& m, Time at = {}) {
  const std::vector<uint8_t> b = Encode(m);
  return s.Ingest(channel, b.data(), b.size(), at);
}

atlasd::local_map_t MapOf(int32_t frame, int lines) {
  atlasd::local_map_t m{};
  m.frame_id = frame;
  m.capacity = 30;
  for (int i = 0; i < lines; ++i) {
    atlasd::line_segment_t l{};
    l.id = i;
    l.x1 = i + 1.0;
    m.lines.push_back(l);
  }
  m.num_lines = lines;
  return m;
}

// Through a real LCM (memq://, in process), as the server's LCM thread receives them.
TEST(ViewState, StoresWhatLcmDelivers) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  ViewState state(ViewChannels{}, 10);
  struct Sink {
    ViewState* state;
    std::vector<IngestResult> results;
    void Raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      results.push_back(state->Ingest(channel, rbuf->data, rbuf->data_size, FromSeconds(7)));
    }
  } sink{&state, {}};
  lcm.subscribe("ATLAS_.*", &Sink::Raw, &sink);

  atlasd::pose_t pose{};
  pose.frame_id = 3;
  pose.x = 1.5;
  pose.theta = -0.25;
  pose.covariance[0] = 0.01;
  pose.q = 0.875;
  lcm.publish("ATLAS_POSE", &pose);
  atlasd::health_t health{};
  health.status = "mapping";
  atlasd::driver_health_t laser{};
  laser.name = "laser";
  laser.state = atlasd::driver_health_t::STATE_STALLED;
  laser.last_error = "no telegram for 2.0 s";
  health.drivers.push_back(laser);
  health.num_drivers = 1;
  lcm.publish("ATLAS_HEALTH", &health);
  lcm.publish("ATLAS_RAW_LASER", "x", 1);  // not one of ours
  while (lcm.handleTimeout(0) > 0) {
  }

  ASSERT_EQ(sink.results.size(), 3u);
  EXPECT_EQ(sink.results[0], IngestResult::kStored);
  EXPECT_EQ(sink.results[1], IngestResult::kStored);
  EXPECT_EQ(sink.results[2], IngestResult::kUnknownChannel);
  ASSERT_TRUE(state.pose());
  EXPECT_EQ(state.pose()->message.frame_id, 3);
  EXPECT_DOUBLE_EQ(state.pose()->message.x, 1.5);
  EXPECT_DOUBLE_EQ(state.pose()->message.theta, -0.25);
  EXPECT_DOUBLE_EQ(state.pose()->message.q, 0.875);
  EXPECT_EQ(state.pose()->at, FromSeconds(7));
  ASSERT_TRUE(state.health());
  ASSERT_EQ(state.health()->message.drivers.size(), 1u);
  EXPECT_EQ(state.health()->message.drivers[0].last_error, "no telegram for 2.0 s");
  EXPECT_EQ(state.version(), 2u);
  EXPECT_EQ(state.rejected(), 1);
}

TEST(ViewState, RefusesTheWrongTypeAndCutMessagesWithoutChangingAnything) {
  ViewState state(ViewChannels{}, 10);
  atlasd::health_t health{};
  EXPECT_EQ(Feed(state, "ATLAS_POSE", health), IngestResult::kUndecodable);
  atlasd::pose_t pose{};
  std::vector<uint8_t> b = Encode(pose);
  EXPECT_EQ(state.Ingest("ATLAS_POSE", b.data(), b.size() - 1, {}), IngestResult::kUndecodable);
  b.push_back(0);
  EXPECT_EQ(state.Ingest("ATLAS_POSE", b.data(), b.size(), {}), IngestResult::kUndecodable);
  EXPECT_EQ(state.Ingest("ATLAS_POSE", b.data(), kMaxMessageBytes + 1, {}),
            IngestResult::kTooLarge);
  EXPECT_FALSE(state.pose());
  EXPECT_EQ(state.version(), 0u);
  EXPECT_EQ(state.rejected(), 4);
}

TEST(ViewState, ChannelNamesAreConfigurable) {
  ViewChannels c;
  c.pose = "ROBOT2_POSE";
  ViewState state(c, 10);
  atlasd::pose_t pose{};
  EXPECT_EQ(Feed(state, "ATLAS_POSE", pose), IngestResult::kUnknownChannel);
  EXPECT_EQ(Feed(state, "ROBOT2_POSE", pose), IngestResult::kStored);
}

TEST(ViewState, RemembersTheLinesOfEveryFrameSeenDominantWithinItsBound) {
  ViewState state(ViewChannels{}, 2);
  EXPECT_EQ(Feed(state, "ATLAS_LOCAL_MAP", MapOf(0, 3), FromSeconds(1)), IngestResult::kStored);
  EXPECT_EQ(Feed(state, "ATLAS_LOCAL_MAP", MapOf(1, 4), FromSeconds(2)), IngestResult::kStored);
  EXPECT_EQ(Feed(state, "ATLAS_LOCAL_MAP", MapOf(0, 5), FromSeconds(3)), IngestResult::kStored);
  ASSERT_EQ(state.maps().size(), 2u);
  EXPECT_EQ(state.maps().at(0).message.lines.size(), 5u);  // the latest of frame 0
  // A third frame: frame 1, refreshed longest ago, is forgotten.
  EXPECT_EQ(Feed(state, "ATLAS_LOCAL_MAP", MapOf(2, 1), FromSeconds(4)), IngestResult::kStored);
  EXPECT_EQ(state.maps().size(), 2u);
  EXPECT_TRUE(state.maps().contains(0));
  EXPECT_FALSE(state.maps().contains(1));
  EXPECT_EQ(state.forgotten_maps(), 1);
  ASSERT_NE(state.latest_map(), nullptr);
  EXPECT_EQ(state.latest_map()->message.frame_id, 2);
  // No dominant hypothesis (frame -1): nothing to remember.
  EXPECT_EQ(Feed(state, "ATLAS_LOCAL_MAP", MapOf(-1, 0), FromSeconds(5)), IngestResult::kStored);
  EXPECT_EQ(state.maps().size(), 2u);
  EXPECT_EQ(state.latest_map()->message.frame_id, 2);
}

}  // namespace
}  // namespace atlas::view
