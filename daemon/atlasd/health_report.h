#pragma once
// atlasd's health (docs/atlasd.md, "Outputs"): step-time statistics, overruns, queue depths
// and drops, driver states and counters, frame and hypothesis counts, resident memory, and the
// one-line summary that goes to systemd (STATUS=) and to stderr.

#include <string>
#include <vector>

#include "atlasd/health_t.hpp"
#include "core/mapper/step_loop.h"
#include "drivers/device/driver_health.h"

namespace atlas {

struct DriverEntry {
  std::string name;
  DriverHealth health;
  int queue_depth = 0;
  int queue_capacity = 0;
};

struct HealthInputs {
  Time now{};
  Time start{};
  const StepLoop* loop = nullptr;
  StepTimeSummary period;
  double step_budget_ms = 0;
  std::vector<DriverEntry> drivers;
  int64_t store_saved = 0, store_dropped = 0, store_errors = 0;
};

// VmRSS from /proc/self/statm, bytes; 0 when unreadable.
int64_t ResidentMemoryBytes();

atlasd::health_t MakeHealthMessage(const HealthInputs& in);

}  // namespace atlas
