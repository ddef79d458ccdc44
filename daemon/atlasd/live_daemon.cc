#include "daemon/atlasd/live_daemon.h"

#include <pthread.h>
#include <signal.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/live_timing.h"
#include "daemon/atlasd/loop_thread.h"
#include "daemon/lcm_out/multicast_route.h"
#include "daemon/notify/service_notifier.h"
#include "formats/config/config_loader.h"

namespace atlas {
namespace {

// sysexits.h EX_SOFTWARE: the step loop stopped on an internal error (systemd restarts atlasd).
constexpr int kExitSoftware = 70;

// SIGHUP: the configuration file is loaded on the main thread and handed to the loop thread,
// which applies it between steps (reload.h); a file that does not load changes nothing.
void QueueReload(const std::string& config_path, LoopShared* shared) {
  ConfigResult r = LoadConfigFile(config_path, ValidateDerivedOptions);
  if (!r.ok()) {
    std::fprintf(stderr, "atlasd: reload refused, the running configuration stays:\n");
    for (const auto& e : r.errors) std::fprintf(stderr, "  %s\n", e.ToString().c_str());
    return;
  }
  std::lock_guard<std::mutex> lock(shared->mutex);
  shared->reloaded = r.options;
  shared->reload_pending = true;
}

}  // namespace

int RunLiveDaemon(const DaemonOptions& options, const LiveFlags& flags) {
  const Time start = Now();
  if (std::string e = ValidateDerivedOptions(options); !e.empty()) {
    std::fprintf(stderr, "atlasd: configuration rejected:\n%s", e.c_str());
    return kExitConfigError;
  }
  // Signals are handled by the main thread only (sigtimedwait); block them before any thread.
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  if (options.scheduling.mlockall && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    std::fprintf(stderr,
                 "atlasd: warning: scheduling.mlockall refused (%s); memory may be paged out "
                 "(raise LimitMEMLOCK or grant CAP_IPC_LOCK)\n",
                 std::strerror(errno));

  // A robot may boot before its network: wait (stoppable) for a route to the LCM group, as a
  // missing device is waited for, instead of failing the start.
  ServiceNotifier notifier;
  const RouteWaitResult route = WaitForMulticastRoute(
      options.lcm.url, RouteWaitOptions{},
      [&notifier](int error, Duration waited) {
        if (waited == Duration::zero())
          std::fprintf(stderr,
                       "atlasd: no route to lcm.url's multicast group (%s); waiting for one "
                       "(ip route add 224.0.0.0/4 dev IFACE, or the network's .network file)\n",
                       std::strerror(error));
        notifier.Status(std::string("waiting for a multicast route for LCM: ") +
                        std::strerror(error));
        notifier.ExtendTimeout(std::chrono::seconds(5));
      },
      [&signals](Duration period) {
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(period).count();
        const timespec t{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
        const int s = sigtimedwait(&signals, nullptr, &t);
        return s != SIGTERM && s != SIGINT;
      });
  if (route == RouteWaitResult::kStopped) return 0;

  LoopShared shared;
  LoopThread loop(options, flags, &shared);
  if (!loop.Start(start)) return 1;
  std::thread loop_thread([&loop] { loop.Run(); });

  const Time ready_deadline = start + SecondsToDuration(flags.ready_timeout_s);
  bool ready = false;
  const auto watchdog = ServiceNotifier::WatchdogInterval();
  const WatchdogTiming timing = WatchdogTimingFor(watchdog);
  Time last_ping{};
  std::string last_status;
  int exit_code = 0;
  for (;;) {
    timespec timeout{0, 50 * 1000 * 1000};
    siginfo_t info;
    const int sig = sigtimedwait(&signals, &info, &timeout);
    const Time now = Now();
    if (sig == SIGTERM || sig == SIGINT) break;
    if (shared.loop_failed.load(std::memory_order_acquire)) {
      std::fprintf(stderr,
                   "atlasd: exiting: the atlas is saved up to its last checkpoint (%.1f s or "
                   "less ago), from which the next start resumes\n",
                   options.state.save_period_s);
      exit_code = kExitSoftware;
      break;
    }
    if (sig == SIGHUP) QueueReload(flags.config_path, &shared);
    if (sig == SIGUSR1 && flags.debug_stall_on_usr1) {
      std::fprintf(stderr, "atlasd: SIGUSR1: stalling the loop for %.1f s (test hook)\n",
                   flags.stall_seconds);
      shared.stall_until_ns.store(
          (now + SecondsToDuration(flags.stall_seconds)).time_since_epoch().count());
    }
    if (!ready) {
      bool all = false;
      if (ReadyNow(shared.loop_running.load(), loop.Drivers(), now, ready_deadline, &all)) {
        ready = true;
        notifier.Ready();
        if (!all) std::fprintf(stderr, "atlasd: ready without every device (see health)\n");
      }
    }
    const bool healthy = HeartbeatFresh(now, shared.heartbeat_ns.load(std::memory_order_acquire),
                                        timing.heartbeat_max);
    if (ready && Due(now, last_ping, timing.ping_period)) {
      last_ping = now;
      std::string status;
      {
        std::lock_guard<std::mutex> lock(shared.mutex);
        status = shared.status;
      }
      if (!status.empty() && status != last_status) {
        notifier.Status(status);
        last_status = status;
      }
      if (healthy && watchdog.count() > 0) notifier.Watchdog();
      if (!healthy) {
        notifier.Status("loop stalled: no watchdog ping");
        last_status.clear();
      }
    }
  }
  notifier.Stopping();
  std::fprintf(stderr, "atlasd: stopping\n");
  shared.Stop();
  loop_thread.join();
  loop.Finish();
  return exit_code;
}

}  // namespace atlas
