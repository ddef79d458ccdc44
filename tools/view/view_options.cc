#include "tools/view/view_options.h"

#include <arpa/inet.h>

#include <cstring>
#include <string_view>

#include "core/common/parse_number.h"
#include "core/common/quote_for_message.h"

namespace atlas::view {

const char kViewHelp[] =
    R"(usage: atlas-view [--address ADDR] [--port PORT] [--lcm-url URL] [--channel ROLE=NAME]...
                  [--rate HZ] [--max-clients N] [--max-frames N] [--status-every S]

A small web server for watching atlasd live in a browser: it subscribes to atlasd's LCM
channels and serves one page (http://ADDR:PORT/) that draws the frames of the Dijkstra
projection from the dominant frame with their lines, the edges by kind, the robot's pose and
covariance ellipse, the hypotheses and a health panel (each driver's state and last error).
The page is pushed updates by server-sent events (/events); /snapshot.json is the same data
once. Read-only: nothing is ever sent to atlasd.

  --address ADDR     IPv4 or IPv6 address to listen on (default 0.0.0.0: every interface,
                     so that a laptop on the robot's network can watch; 127.0.0.1: this host)
  --port PORT        TCP port, 0 to 65535 (default 8080; 0: any free port, printed at start)
  --lcm-url URL      LCM provider (default: LCM_DEFAULT_URL, else LCM's default, as atlasd)
  --channel ROLE=NAME  a channel name other than atlasd's default; ROLE is pose, local_map,
                     graph, hypotheses or health (as in atlasd's [lcm.channels])
  --rate HZ          the most page updates per second, 0.1 to 10 (default 4)
  --max-clients N    event streams (browser tabs) at once, 1 to 64 (default 4); more get 503
  --max-frames N     frames drawn, nearest first, and frames whose lines are remembered,
                     1 to 100000 (default 1000)
  --status-every S   a status line on stderr every S seconds, 0 to 86400 (0: never; default 60)
  -h, --help         this text
  --version          the version

ATLAS_LOCAL_MAP carries the dominant frame's lines only: atlas-view remembers the last lines
of every frame it has seen dominant and draws them where the projection places that frame.
Runs until SIGINT or SIGTERM. Exit 0; 1 when the port cannot be bound or LCM cannot be
opened; 2 on a usage error.
)";

namespace {

bool ValidAddress(const std::string& a) {
  unsigned char buf[16];
  return inet_pton(AF_INET, a.c_str(), buf) == 1 || inet_pton(AF_INET6, a.c_str(), buf) == 1;
}

// atlasd's rule for channel names: 1 to 63 printable characters without spaces.
bool ValidChannel(std::string_view name) {
  if (name.empty() || name.size() > 63) return false;
  for (char c : name)
    if (c <= ' ' || c > '~') return false;
  return true;
}

std::string SetChannel(std::string_view spec, ViewChannels& channels) {
  const size_t eq = spec.find('=');
  if (eq == std::string_view::npos)
    return "--channel needs ROLE=NAME, got " + QuoteForMessage(spec);
  const std::string_view role = spec.substr(0, eq), name = spec.substr(eq + 1);
  std::string* slot = role == "pose"         ? &channels.pose
                      : role == "local_map"  ? &channels.local_map
                      : role == "graph"      ? &channels.graph
                      : role == "hypotheses" ? &channels.hypotheses
                      : role == "health"     ? &channels.health
                                             : nullptr;
  if (slot == nullptr)
    return "--channel: unknown role " + QuoteForMessage(role) +
           " (pose, local_map, graph, hypotheses, health)";
  if (!ValidChannel(name))
    return "--channel " + std::string(role) +
           ": a name is 1 to 63 printable characters without spaces, got " + QuoteForMessage(name);
  *slot = name;
  return {};
}

}  // namespace

ViewArguments ParseViewArguments(int argc, const char* const* argv) {
  ViewArguments r;
  ViewOptions& o = r.options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      r.help = true;
      return r;
    }
    if (a == "--version") {
      r.version = true;
      return r;
    }
    static constexpr const char* kWithValue[] = {"--address",    "--port",        "--lcm-url",
                                                 "--channel",    "--rate",        "--max-clients",
                                                 "--max-frames", "--status-every"};
    bool known = false;
    for (const char* k : kWithValue) known = known || a == k;
    if (!known) {
      r.error = "unknown argument " + QuoteForMessage(a);
      return r;
    }
    if (i + 1 >= argc) {
      r.error = a + " needs a value";
      return r;
    }
    const char* v = argv[++i];
    std::string& e = r.error;
    if (a == "--address") {
      if (!ValidAddress(v))
        e = "--address must be an IPv4 or IPv6 address, got " + QuoteForMessage(v);
      o.address = v;
    } else if (a == "--port") {
      IntegerArgument(a, v, 0, 65535, o.port, e);
    } else if (a == "--lcm-url") {
      if (*v == '\0') e = "--lcm-url needs a non-empty URL";
      o.lcm_url = v;
    } else if (a == "--channel") {
      e = SetChannel(v, o.channels);
    } else if (a == "--rate") {
      NumberArgument(a, v, 0.1, 10, o.rate_hz, e);
    } else if (a == "--max-clients") {
      IntegerArgument(a, v, 1, 64, o.max_clients, e);
    } else if (a == "--max-frames") {
      IntegerArgument(a, v, 1, 100000, o.max_frames, e);
    } else {
      NumberArgument(a, v, 0, 86400, o.status_every_s, e);
    }
    if (!e.empty()) return r;
  }
  const ViewChannels& c = o.channels;
  const std::string* names[] = {&c.pose, &c.local_map, &c.graph, &c.hypotheses, &c.health};
  for (size_t i = 0; i < std::size(names); ++i)
    for (size_t j = i + 1; j < std::size(names); ++j)
      if (*names[i] == *names[j]) {
        r.error = "--channel: two roles share the channel " + QuoteForMessage(*names[i]);
        return r;
      }
  return r;
}

}  // namespace atlas::view
