// atlas-pose-latency: an LCM subscriber that measures, for every ATLAS_POSE it receives, the
// time from the scan's arrival stamp (the laser driver's CLOCK_MONOTONIC time of the read() that
// completed the telegram, published in pose_t.utime as microseconds since the epoch and turned
// back with this process's EpochClock) to the message's arrival in this process (the monotonic
// clock, read in the handler). See --help.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <vector>

#include "atlasd/pose_t.hpp"
#include "core/common/time.h"
#include "daemon/lcm_out/epoch_clock.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    R"(Subscribes to ATLAS_POSE (LCM_DEFAULT_URL) for S seconds or until SIGINT/SIGTERM,
and prints the latency of each pose: from the laser driver's arrival stamp of the scan
(pose_t.utime, microseconds since the epoch, turned back into CLOCK_MONOTONIC with the offset
between the clocks read at start) to the pose's receipt here (CLOCK_MONOTONIC), as
  poses=N median_us=.. p90_us=.. p99_us=.. max_us=..
Dead-reckoning poses (published without a scan, utime = odometry time) are counted apart and
left out. The first N poses are skipped (start-up). atlasd must run on this machine (one
monotonic clock).)";

constexpr const char* kFooter =
    R"(Exit 0; 1 when no pose was measured or LCM cannot be opened; 2 on a usage
error (an unknown option, a missing value, a value that is not a number in its range).
)";

volatile sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

struct Collector {
  atlas::EpochClock epoch = atlas::EpochClock::Capture();
  std::vector<double> latency_us;
  int64_t last_utime = -1;
  long skipped = 0, warmup = 20;
  int repeated = 0;
  void Handle(const lcm::ReceiveBuffer*, const std::string&, const atlasd::pose_t* p) {
    const int64_t now_us = atlas::Now().time_since_epoch().count() / 1000;
    if (p->utime == last_utime) {  // the same stamp again: not a new scan
      ++repeated;
      return;
    }
    last_utime = p->utime;
    if (skipped < warmup) {
      ++skipped;
      return;
    }
    latency_us.push_back(static_cast<double>(now_us - epoch.ToMonotonic(p->utime)));
  }
};

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60;
  std::string channel = "ATLAS_POSE";
  Collector c;
  atlas::cli::CommandLine command_line(
      "atlas-pose-latency", {"atlas-pose-latency [--seconds S] [--channel NAME] [--warmup N]"},
      kDescription, kFooter);
  CLI::App& app = command_line.app();
  atlas::cli::AddNumber(app, "--seconds", "S", 0.001, 86400, &seconds,
                        "how long to listen, 0.001 to 86400 (default 60)");
  atlas::cli::AddText(app, "--channel", "NAME", &channel, "the pose channel (default ATLAS_POSE)");
  atlas::cli::AddInteger(app, "--warmup", "N", 0, 1000000, &c.warmup,
                         "poses skipped at the start, an integer 0 to 1000000 (default 20)");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  lcm::LCM lcm;
  if (!lcm.good()) {
    std::fprintf(stderr,
                 "atlas-pose-latency: cannot open LCM (LCM_DEFAULT_URL, multicast route)\n");
    return 1;
  }
  lcm.subscribe(channel, &Collector::Handle, &c);
  signal(SIGINT, OnSignal);
  signal(SIGTERM, OnSignal);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!g_stop && std::chrono::steady_clock::now() < end) lcm.handleTimeout(100);
  const std::vector<double>& v = c.latency_us;
  std::printf("poses=%zu median_us=%.1f p90_us=%.1f p99_us=%.1f max_us=%.1f repeated_stamps=%d\n",
              v.size(), Quantile(v, 0.5), Quantile(v, 0.9), Quantile(v, 0.99),
              v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()), c.repeated);
  return v.empty() ? 1 : 0;
}
