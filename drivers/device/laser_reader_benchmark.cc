// Latency of the laser path: from the write() of a whole LMS 0xB0 telegram to the pty (so the
// figure includes the write call: an upper bound on "from the last byte written") to the decoded
// LaserScan popped from the reader's queue by a consumer polling it (as the step loop does). 10,000
// scans of 361 beams; reports median and p99.
//
//   build-devio/bin/atlas_device_benchmark --benchmark_filter=LaserTelegramToQueue
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "drivers/device/laser_reader.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/serial/pseudo_terminal.h"
#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

namespace atlas {
namespace {

void BM_LaserTelegramToQueue(benchmark::State& state) {
  PseudoTerminal pty;
  std::string error;
  if (!pty.Create("", &error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  LaserReaderOptions o;
  o.device = pty.slave_path();
  o.baud = 9600;  // a pty has no line rate; skip the switch
  o.probe_rates = {9600};
  o.reconnect.realtime_priority = static_cast<int>(state.range(0));
  LaserReader reader(o);
  reader.Start();
  if (!fake::AnswerLmsStartUp(pty, std::chrono::seconds(5))) {
    state.SkipWithError("the reader did not start");
    return;
  }
  while (reader.Health().state != DriverState::kRunning) std::this_thread::yield();

  LaserScan scan;
  scan.angle_min = -1.5707964f;
  scan.angle_increment = 0.0087266f;
  scan.ranges.resize(361);
  for (size_t i = 0; i < scan.ranges.size(); ++i)
    scan.ranges[i] = (i % 17 == 0) ? kNoReturn : 0.5f + 0.01f * static_cast<float>(i);
  const std::vector<uint8_t> telegram =
      *sick::EncodeMeasuredValues(scan, sick::Unit::kCentimetre, 0x10);

  std::vector<double> latencies_us;
  latencies_us.reserve(static_cast<size_t>(state.max_iterations));
  LaserScan out;
  int lost = 0;
  for (auto _ : state) {
    // Stamped before write(): the figure includes the write call itself (an upper bound on
    // "from the last byte written"), and cannot be fooled by a preemption after write().
    const Time written = Now();
    pty.WriteAll(telegram.data(), telegram.size());
    const Time give_up = written + std::chrono::milliseconds(200);
    bool got = false;
    while (!(got = reader.Pop(&out)) && Now() < give_up) {
    }
    const Time popped = Now();
    if (!got) {
      ++lost;
      state.SetIterationTime(0.2);
      continue;
    }
    const double us = ToSeconds(popped - written) * 1e6;
    latencies_us.push_back(us);
    state.SetIterationTime(us * 1e-6);
  }
  reader.Stop();
  std::sort(latencies_us.begin(), latencies_us.end());
  auto pct = [&](double p) {
    return latencies_us.empty()
               ? 0.0
               : latencies_us[std::min(
                     latencies_us.size() - 1,
                     static_cast<size_t>(p * static_cast<double>(latencies_us.size())))];
  };
  state.counters["median_us"] = pct(0.5);
  state.counters["p99_us"] = pct(0.99);
  state.counters["max_us"] = latencies_us.empty() ? 0.0 : latencies_us.back();
  state.counters["scans"] = static_cast<double>(latencies_us.size());
  state.counters["lost"] = lost;
  state.counters["bad_crc"] = static_cast<double>(reader.Health().bad_crc);
}
// Argument: the reader thread's SCHED_FIFO priority (0 = normal scheduling).
BENCHMARK(BM_LaserTelegramToQueue)
    ->Arg(0)
    ->Arg(20)
    ->Iterations(10000)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
