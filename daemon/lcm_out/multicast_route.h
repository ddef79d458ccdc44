#pragma once
// Waiting for the multicast route LCM needs, as a missing device is waited for
// (docs/systemd.md, "Starting before the network").
//
// LCM's udpm provider cannot start without a route to its multicast group (lcm::LCM::good() is
// false), and a robot may boot before its network is up. Before opening LCM, atlasd polls the
// kernel's route to the group (a UDP connect(): no packet is sent) until there is one, saying
// why it waits, and stops waiting when asked to stop.

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "core/common/time.h"

namespace atlas {

// The IPv4 multicast group of an LCM URL "udpm://A.B.C.D:PORT?options", in host byte order;
// "udpm://" alone is LCM's default group, 239.255.76.67. nullopt for the providers that need no
// route (memq://, file://, tcpq://) and for a group that is not an IPv4 multicast address
// (LCM itself refuses it).
std::optional<uint32_t> LcmMulticastGroup(std::string_view url);

// 0 when the kernel has a route for a UDP datagram to `group` (host byte order) now, else the
// errno of the lookup: ENETUNREACH when there is no route.
int RouteErrorTo(uint32_t group);

enum class RouteWaitResult { kRouted, kNotNeeded, kStopped };

struct RouteWaitOptions {
  Duration poll_period = std::chrono::seconds(1);
  // The route lookup (RouteErrorTo); tests replace it.
  std::function<int(uint32_t group)> route_error = RouteErrorTo;
};

// Returns kNotNeeded at once when `url` needs no route, kRouted as soon as the route exists.
// Otherwise calls `waiting(error, waited)` after each failed lookup (waited: time since the
// first one) and `sleep(poll_period)`, which returns false to give up (a stop signal):
// kStopped.
RouteWaitResult WaitForMulticastRoute(
    std::string_view url, const RouteWaitOptions& options,
    const std::function<void(int error, Duration waited)>& waiting,
    const std::function<bool(Duration)>& sleep);

}  // namespace atlas
