#include "tools/view/view_options.h"

#include <arpa/inet.h>

#include <string_view>

#include "core/common/quote_for_message.h"
#include "tools/cli/command_line.h"

namespace atlas::view {
namespace {

constexpr const char* kDescription =
    R"(A small web server for watching atlasd live in a browser: it subscribes to atlasd's LCM
channels and serves one page (http://ADDR:PORT/) that draws the frames of the Dijkstra
projection from the dominant frame with their lines, the edges by kind, the robot's pose and
covariance ellipse, the hypotheses and a health panel (each driver's state and last error).
The page is pushed updates by server-sent events (/events); /snapshot.json is the same data
once. Read-only: nothing is ever sent to atlasd.)";

constexpr const char* kFooter =
    R"(ATLAS_LOCAL_MAP carries the dominant frame's lines only: atlas-view remembers the last lines
of every frame it has seen dominant and draws them where the projection places that frame.
Runs until SIGINT or SIGTERM.

Exit status: 0 stopped, 1 the port cannot be bound or LCM cannot be opened, 2 bad command
line.
)";

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

std::optional<int> ParseViewCommandLine(int argc, char** argv, ViewOptions* options) {
  ViewOptions& o = *options;
  const ViewOptions defaults;
  cli::CommandLine command_line("atlas-view", {"atlas-view [options]"}, kDescription, kFooter);
  CLI::App& app = command_line.app();
  cli::AddValue(
      app, "--address", "ADDR",
      [&o](const std::string& v) {
        if (!ValidAddress(v))
          return "--address must be an IPv4 or IPv6 address, got " + QuoteForMessage(v);
        o.address = v;
        return std::string();
      },
      "IPv4 or IPv6 address to listen on (default " + defaults.address +
          ": every interface,\nso that a laptop on the robot's network can watch; 127.0.0.1: "
          "this host)");
  cli::AddInteger(app, "--port", "PORT", 0, 65535, &o.port,
                  "TCP port, 0 to 65535 (default " + std::to_string(defaults.port) +
                      "; 0: any free port, printed at start)");
  cli::AddText(app, "--lcm-url", "URL", &o.lcm_url,
               "LCM provider (default: LCM_DEFAULT_URL, else LCM's default, as atlasd)");
  cli::AddValue(
      app, "--channel", "ROLE=NAME",
      [&o](const std::string& v) { return SetChannel(v, o.channels); },
      "a channel name other than atlasd's default; ROLE is pose, local_map,\ngraph, hypotheses "
      "or health (as in atlasd's [lcm.channels]); repeatable")
      .Repeatable();  // every --channel given, not only the last
  cli::AddNumber(app, "--rate", "HZ", 0.1, 10, &o.rate_hz,
                 "the most page updates per second, 0.1 to 10 (default " +
                     cli::HelpNumber(defaults.rate_hz) + ")");
  cli::AddInteger(app, "--max-clients", "N", 1, 64, &o.max_clients,
                  "event streams (browser tabs) at once, 1 to 64 (default " +
                      std::to_string(defaults.max_clients) + "); more get 503");
  cli::AddInteger(app, "--max-frames", "N", 1, 100000, &o.max_frames,
                  "frames drawn, nearest first, and frames whose lines are remembered,\n1 to "
                  "100000 (default " +
                      std::to_string(defaults.max_frames) + ")");
  cli::AddNumber(app, "--status-every", "S", 0, 86400, &o.status_every_s,
                 "a status line on stderr every S seconds, 0 to 86400 (0: never; default " +
                     cli::HelpNumber(defaults.status_every_s) + ")");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return done;
  const ViewChannels& c = o.channels;
  const std::string* names[] = {&c.pose, &c.local_map, &c.graph, &c.hypotheses, &c.health};
  for (size_t i = 0; i < std::size(names); ++i)
    for (size_t j = i + 1; j < std::size(names); ++j)
      if (*names[i] == *names[j])
        return command_line.Usage("--channel: two roles share the channel " +
                                  QuoteForMessage(*names[i]));
  return std::nullopt;
}

}  // namespace atlas::view
