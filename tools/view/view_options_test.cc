#include "tools/view/view_options.h"

#include <gtest/gtest.h>

#include <vector>

namespace atlas::view {
namespace {

ViewArguments Parse(std::vector<const char*> args) {
  args.insert(args.begin(), "atlas-view");
  return ParseViewArguments(static_cast<int>(args.size()), args.data());
}

TEST(ViewOptions, DefaultsListenEverywhereOn8080) {
  const ViewArguments a = Parse({});
  EXPECT_TRUE(a.error.empty());
  EXPECT_EQ(a.options.address, "0.0.0.0");
  EXPECT_EQ(a.options.port, 8080);
  EXPECT_EQ(a.options.channels.graph, "ATLAS_GRAPH");
  EXPECT_DOUBLE_EQ(a.options.rate_hz, 4.0);
}

TEST(ViewOptions, ReadsEveryOption) {
  const ViewArguments a = Parse({"--address", "::1", "--port", "0", "--lcm-url", "memq://",
                                 "--channel", "health=ROBOT_HEALTH", "--rate", "0.5",
                                 "--max-clients", "2", "--max-frames", "7", "--status-every", "0"});
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.options.address, "::1");
  EXPECT_EQ(a.options.port, 0);
  EXPECT_EQ(a.options.lcm_url, "memq://");
  EXPECT_EQ(a.options.channels.health, "ROBOT_HEALTH");
  EXPECT_EQ(a.options.channels.pose, "ATLAS_POSE");
  EXPECT_DOUBLE_EQ(a.options.rate_hz, 0.5);
  EXPECT_EQ(a.options.max_clients, 2);
  EXPECT_EQ(a.options.max_frames, 7);
  EXPECT_DOUBLE_EQ(a.options.status_every_s, 0.0);
}

TEST(ViewOptions, HelpAndVersion) {
  EXPECT_TRUE(Parse({"--help"}).help);
  EXPECT_TRUE(Parse({"-h"}).help);
  EXPECT_TRUE(Parse({"--version"}).version);
}

TEST(ViewOptions, RefusesBadValuesNamingThem) {
  EXPECT_NE(Parse({"--bogus"}).error.find("unknown argument"), std::string::npos);
  EXPECT_NE(Parse({"--port"}).error.find("needs a value"), std::string::npos);
  EXPECT_NE(Parse({"--port", "65536"}).error.find("--port"), std::string::npos);
  EXPECT_NE(Parse({"--port", "80x"}).error.find("--port"), std::string::npos);
  EXPECT_NE(Parse({"--address", "robot.local"}).error.find("IPv4 or IPv6"), std::string::npos);
  EXPECT_NE(Parse({"--rate", "11"}).error.find("--rate"), std::string::npos);
  EXPECT_NE(Parse({"--rate", "0"}).error.find("--rate"), std::string::npos);
  EXPECT_NE(Parse({"--max-clients", "0"}).error.find("--max-clients"), std::string::npos);
  EXPECT_NE(Parse({"--max-frames", "100001"}).error.find("--max-frames"), std::string::npos);
  EXPECT_NE(Parse({"--lcm-url", ""}).error.find("--lcm-url"), std::string::npos);
  EXPECT_NE(Parse({"--channel", "POSE"}).error.find("ROLE=NAME"), std::string::npos);
  EXPECT_NE(Parse({"--channel", "odometry=X"}).error.find("unknown role"), std::string::npos);
  EXPECT_NE(Parse({"--channel", "pose=A B"}).error.find("printable"), std::string::npos);
  EXPECT_NE(Parse({"--channel", "pose="}).error.find("printable"), std::string::npos);
  EXPECT_NE(Parse({"--channel", "pose=ATLAS_GRAPH"}).error.find("share"), std::string::npos);
}

}  // namespace
}  // namespace atlas::view
