#include "tools/view/view_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas::view {
namespace {

// atlas-view's command line `args` (after the tool's name): the options read, the exit status
// (-1: serve) and what was printed.
struct Parsed {
  ViewOptions options;
  int status = -1;
  std::string out, err;
};

Parsed Parse(std::vector<std::string> args) {
  args.insert(args.begin(), "atlas-view");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  Parsed p;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  p.status =
      ParseViewCommandLine(static_cast<int>(argv.size()), argv.data(), &p.options).value_or(-1);
  p.out = testing::internal::GetCapturedStdout();
  p.err = testing::internal::GetCapturedStderr();
  return p;
}

TEST(ViewOptions, DefaultsListenEverywhereOn8080) {
  const Parsed p = Parse({});
  EXPECT_EQ(p.status, -1) << p.err;
  EXPECT_EQ(p.options.address, "0.0.0.0");
  EXPECT_EQ(p.options.port, 8080);
  EXPECT_EQ(p.options.channels.graph, "ATLAS_GRAPH");
  EXPECT_DOUBLE_EQ(p.options.rate_hz, 4.0);
  EXPECT_EQ(p.options.max_clients, 4);
  EXPECT_EQ(p.options.max_frames, 1000);
  EXPECT_DOUBLE_EQ(p.options.status_every_s, 60.0);
}

TEST(ViewOptions, ReadsEveryOption) {
  const Parsed p = Parse({"--address", "::1", "--port=0", "--lcm-url", "memq://", "--channel",
                          "health=ROBOT_HEALTH", "--channel=pose=ROBOT_POSE", "--rate", "0.5",
                          "--max-clients", "2", "--max-frames=7", "--status-every", "0"});
  ASSERT_EQ(p.status, -1) << p.err;
  EXPECT_EQ(p.options.address, "::1");
  EXPECT_EQ(p.options.port, 0);
  EXPECT_EQ(p.options.lcm_url, "memq://");
  EXPECT_EQ(p.options.channels.health, "ROBOT_HEALTH");
  EXPECT_EQ(p.options.channels.pose, "ROBOT_POSE");
  EXPECT_EQ(p.options.channels.graph, "ATLAS_GRAPH");
  EXPECT_DOUBLE_EQ(p.options.rate_hz, 0.5);
  EXPECT_EQ(p.options.max_clients, 2);
  EXPECT_EQ(p.options.max_frames, 7);
  EXPECT_DOUBLE_EQ(p.options.status_every_s, 0.0);
}

TEST(ViewOptions, HelpAndVersionExitZero) {
  const Parsed help = Parse({"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("Usage: atlas-view [options]\n", 0), 0u) << help.out;
  for (const char* part : {"--channel ROLE=NAME", "--max-frames N", "default 1000", "Exit status"})
    EXPECT_NE(help.out.find(part), std::string::npos) << part << "\n" << help.out;
  EXPECT_EQ(Parse({"-h"}).status, 0);
  const Parsed version = Parse({"--port", "x", "--version"});
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out.rfind("atlas-view ", 0), 0u) << version.out;
}

// Exit 2, "atlas-view: <what>" and the pointer to --help.
void ExpectRefused(const std::vector<std::string>& args, const std::string& what) {
  const Parsed p = Parse(args);
  EXPECT_EQ(p.status, 2) << what;
  EXPECT_EQ(p.err, "atlas-view: " + what + "\nTry 'atlas-view --help'.\n");
}

TEST(ViewOptions, RefusesBadValuesNamingThem) {
  ExpectRefused({"--bogus"}, "unknown option '--bogus'");
  ExpectRefused({"extra"}, "unexpected argument 'extra'");
  ExpectRefused({"--port"}, "--port needs a value");
  ExpectRefused({"--port", "65536"}, "--port must be an integer in [0, 65535], got '65536'");
  ExpectRefused({"--port", "80x"}, "--port must be an integer in [0, 65535], got '80x'");
  ExpectRefused({"--address", "robot.local"},
                "--address must be an IPv4 or IPv6 address, got 'robot.local'");
  ExpectRefused({"--rate", "11"}, "--rate must be a number in [0.1, 10], got '11'");
  ExpectRefused({"--rate", "0"}, "--rate must be a number in [0.1, 10], got '0'");
  ExpectRefused({"--max-clients", "0"}, "--max-clients must be an integer in [1, 64], got '0'");
  ExpectRefused({"--max-frames", "100001"},
                "--max-frames must be an integer in [1, 100000], got '100001'");
  ExpectRefused({"--lcm-url", ""}, "--lcm-url needs a URL, got ''");
  ExpectRefused({"--channel", "POSE"}, "--channel needs ROLE=NAME, got 'POSE'");
  ExpectRefused({"--channel", "odometry=X"},
                "--channel: unknown role 'odometry' (pose, local_map, graph, hypotheses, health)");
  ExpectRefused({"--channel", "pose=A B"},
                "--channel pose: a name is 1 to 63 printable characters without spaces, got 'A B'");
  ExpectRefused({"--channel", "pose="},
                "--channel pose: a name is 1 to 63 printable characters without spaces, got ''");
  ExpectRefused({"--channel", "pose=ATLAS_GRAPH"},
                "--channel: two roles share the channel 'ATLAS_GRAPH'");
}

}  // namespace
}  // namespace atlas::view
