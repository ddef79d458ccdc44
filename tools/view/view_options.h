#pragma once
// atlas-view's options: its command line (--help; docs/atlas-view.md), read with the tools'
// convention (tools/cli/command_line.h) and validated once. Where the page is served, which of
// atlasd's LCM channels (docs/lcm.md) are read, and the fixed budgets that bound the server:
// event streams at once, page updates per second, frames drawn.

#include <optional>
#include <string>

#include "formats/config/daemon_options.h"

namespace atlas::view {

// atlasd's channel names and their defaults, as atlasd's [lcm.channels] (formats/config); the
// raw_* channels are not read.
using ViewChannels = LcmChannels;

struct ViewOptions {
  // An IPv4 or IPv6 address to listen on; all interfaces by default, so that a laptop on the
  // robot's network can watch (the page is read-only: no command reaches atlasd).
  std::string address = "0.0.0.0";
  int port = 8080;  // 0: any free port (printed at start)
  // LCM provider URL; empty: LCM_DEFAULT_URL, else LCM's default (atlasd's default too).
  std::string lcm_url;
  ViewChannels channels;
  double rate_hz = 4.0;  // the most page updates per second, 0.1 to 10
  int max_clients = 4;   // event streams (browser tabs) at once, 1 to 64
  // Frames drawn, the nearest (smallest projected uncertainty) first; also the number of frames
  // whose lines are remembered. 1 to 100000.
  int max_frames = 1000;
  double status_every_s = 60.0;  // a status line on stderr this often; 0: never
};

// Reads atlas-view's command line into `options`. nullopt: serve; otherwise the exit status
// (0 after --help or --version, 2 after a bad command line; printed as command_line.h says).
std::optional<int> ParseViewCommandLine(int argc, char** argv, ViewOptions* options);

}  // namespace atlas::view
