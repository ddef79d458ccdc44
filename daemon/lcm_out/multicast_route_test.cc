#include "daemon/lcm_out/multicast_route.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <vector>

namespace atlas {
namespace {

TEST(LcmMulticastGroup, ReadsTheGroupOfAnUdpmUrl) {
  EXPECT_EQ(LcmMulticastGroup("udpm://239.255.76.67:7667?ttl=0"), 0xEFFF4C43u);
  EXPECT_EQ(LcmMulticastGroup("udpm://224.1.2.3:1234"), 0xE0010203u);
  EXPECT_EQ(LcmMulticastGroup("udpm://239.0.0.9?ttl=1"), 0xEF000009u);
  EXPECT_EQ(LcmMulticastGroup("udpm://"), 0xEFFF4C43u);
  EXPECT_EQ(LcmMulticastGroup("udpm://:7667?ttl=1"), 0xEFFF4C43u);
}

TEST(LcmMulticastGroup, OtherProvidersAndBadGroupsNeedNoRoute) {
  EXPECT_EQ(LcmMulticastGroup("memq://"), std::nullopt);
  EXPECT_EQ(LcmMulticastGroup("file:///var/log/x.lcm"), std::nullopt);
  EXPECT_EQ(LcmMulticastGroup("tcpq://localhost:7700"), std::nullopt);
  EXPECT_EQ(LcmMulticastGroup("udpm://10.0.0.1:7667"), std::nullopt);  // not multicast
  EXPECT_EQ(LcmMulticastGroup("udpm://robot.local:7667"), std::nullopt);
}

TEST(RouteErrorTo, LoopbackIsAlwaysRouted) {
  // A unicast address through the same lookup: the host's own loopback always has a route.
  EXPECT_EQ(RouteErrorTo(0x7F000001), 0);
}

TEST(WaitForMulticastRoute, WaitsUntilTheRouteAppearsSayingWhy) {
  std::vector<int> answers = {ENETUNREACH, ENETUNREACH, 0};
  std::vector<uint32_t> asked;
  RouteWaitOptions o;
  o.poll_period = std::chrono::milliseconds(250);
  o.route_error = [&](uint32_t group) {
    asked.push_back(group);
    const int e = answers.front();
    answers.erase(answers.begin());
    return e;
  };
  std::vector<int> reported;
  std::vector<Duration> waited, slept;
  const RouteWaitResult r = WaitForMulticastRoute(
      "udpm://239.255.76.67:7667?ttl=1", o,
      [&](int e, Duration w) {
        reported.push_back(e);
        waited.push_back(w);
      },
      [&](Duration d) {
        slept.push_back(d);
        return true;
      });
  EXPECT_EQ(r, RouteWaitResult::kRouted);
  EXPECT_EQ(asked, (std::vector<uint32_t>{0xEFFF4C43u, 0xEFFF4C43u, 0xEFFF4C43u}));
  EXPECT_EQ(reported, (std::vector<int>{ENETUNREACH, ENETUNREACH}));
  EXPECT_EQ(slept, (std::vector<Duration>{o.poll_period, o.poll_period}));
  // The first report is at zero (atlasd says the reason on stderr then, once).
  ASSERT_EQ(waited.size(), 2u);
  EXPECT_EQ(waited[0], Duration::zero());
  EXPECT_GE(waited[1], Duration::zero());
}

TEST(WaitForMulticastRoute, StopsWhenToldTo) {
  RouteWaitOptions o;
  int lookups = 0;
  o.route_error = [&](uint32_t) {
    ++lookups;
    return ENETUNREACH;
  };
  int sleeps = 0;
  const RouteWaitResult r = WaitForMulticastRoute(
      "udpm://239.255.76.67:7667", o, [](int, Duration) {}, [&](Duration) { return ++sleeps < 3; });
  EXPECT_EQ(r, RouteWaitResult::kStopped);
  EXPECT_EQ(lookups, 3);
  EXPECT_EQ(sleeps, 3);
}

TEST(WaitForMulticastRoute, OtherProvidersDoNotWait) {
  RouteWaitOptions o;
  o.route_error = [](uint32_t) -> int {
    ADD_FAILURE() << "no lookup for memq://";
    return 0;
  };
  EXPECT_EQ(WaitForMulticastRoute(
                "memq://", o, [](int, Duration) { ADD_FAILURE(); },
                [](Duration) {
                  ADD_FAILURE();
                  return false;
                }),
            RouteWaitResult::kNotNeeded);
}

}  // namespace
}  // namespace atlas
