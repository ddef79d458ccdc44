#include "daemon/lcm_out/multicast_route.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <string>

namespace atlas {

namespace {
constexpr std::string_view kUdpm = "udpm://";
constexpr uint32_t kLcmDefaultGroup = 0xEFFF4C43;  // 239.255.76.67
}  // namespace

std::optional<uint32_t> LcmMulticastGroup(std::string_view url) {
  if (url.substr(0, kUdpm.size()) != kUdpm) return std::nullopt;
  std::string_view rest = url.substr(kUdpm.size());
  const std::string host(rest.substr(0, rest.find_first_of(":?")));
  if (host.empty()) return kLcmDefaultGroup;
  in_addr a{};
  if (inet_pton(AF_INET, host.c_str(), &a) != 1) return std::nullopt;
  const uint32_t group = ntohl(a.s_addr);
  if ((group >> 28) != 0xE) return std::nullopt;
  return group;
}

int RouteErrorTo(uint32_t group) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return errno;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(7667);
  to.sin_addr.s_addr = htonl(group);
  const int error = connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) == 0 ? 0 : errno;
  close(fd);
  return error;
}

RouteWaitResult WaitForMulticastRoute(
    std::string_view url, const RouteWaitOptions& options,
    const std::function<void(int error, Duration waited)>& waiting,
    const std::function<bool(Duration)>& sleep) {
  const std::optional<uint32_t> group = LcmMulticastGroup(url);
  if (!group) return RouteWaitResult::kNotNeeded;
  std::optional<Time> first;  // of the first failed lookup: its report says zero
  for (;;) {
    const int error = options.route_error(*group);
    if (error == 0) return RouteWaitResult::kRouted;
    const Time now = Now();
    if (!first) first = now;
    waiting(error, now - *first);
    if (!sleep(options.poll_period)) return RouteWaitResult::kStopped;
  }
}

}  // namespace atlas
