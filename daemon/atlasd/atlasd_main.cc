// atlasd: the real-time Atlas mapping daemon. See --help and docs/atlasd.md.
#include <sys/stat.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "core/common/parse_number.h"
#include "daemon/atlasd/atlas_export.h"
#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/live_daemon.h"
#include "daemon/atlasd/replay.h"
#include "formats/config/config_loader.h"

namespace {

constexpr const char* kHelp = R"(usage: atlasd [--config FILE] [options]
       atlasd --check-config FILE
       atlasd --replay LOGFILE --out DIR [--config FILE]
       atlasd --export-atlas DIR [--config FILE]

The Atlas mapping daemon: reads the laser, odometry and sonar devices named in the
configuration, steps the atlas once per scan under a fixed budget, and publishes the pose,
local map, atlas graph, hypotheses and health on LCM (docs/atlasd.md, docs/lcm.md).

options:
  --config FILE          configuration (default /etc/atlasd/atlasd.toml when it exists,
                         else config/atlasd.toml in the working directory)
  --check-config FILE    check a configuration file and exit: 0 when valid, 78 (EX_CONFIG)
                         with every error (file:line:column: key: message) otherwise
  --replay LOGFILE       offline: run the same loop over the raw channels of an lcm-logger
                         file (recorded with lcm.republish_raw = true) or over a CARMEN log
                         instead of devices; the scans and/or sonar readings stepped are
                         those localmap.sensors names, as live (give the session's
                         configuration file)
  --out DIR              replay output: the files of atlas-replay (DIR/trajectory.tsv,
                         graph.tsv, timing.tsv, ...; docs/formats.md, "Replay output")
  --export-atlas DIR     write the atlas saved in state.directory as DIR/graph.tsv and
                         DIR/maps.tsv (atlas-replay's formats, for atlas-render --atlas) and exit
  --health-every S       print the health line on stderr every S seconds, 0.001 to 86400
                         (default: the health period, lcm.health_period_s)
  --quiet                no health line
  --debug-stall-on-usr1  test hook: SIGUSR1 stalls the loop thread for 5 s (the watchdog
                         pings stop); never enable it in production
  -h, --help             this text

signals: SIGTERM/SIGINT stop (STOPPING=1, exits within a second), SIGHUP reloads the
configuration file (what can change while running is applied, the rest is listed).
exit codes: 0 stopped cleanly, 1 could not start, 2 bad command line, 78 bad configuration.
)";

int Usage(const std::string& what) {
  std::fprintf(stderr, "atlasd: %s (see atlasd --help)\n", what.c_str());
  return 2;
}

bool Exists(const char* path) {
  struct stat st;
  return stat(path, &st) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  atlas::LiveFlags flags;
  std::string replay, out, export_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](std::string* dst) {
      if (i + 1 >= argc) return false;
      *dst = argv[++i];
      return true;
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "--check-config") {
      std::string file;
      if (!value(&file)) return Usage("--check-config needs a FILE");
      return atlas::CheckConfigCommand(file, atlas::ValidateDerivedOptions, std::cout, std::cerr);
    } else if (a == "--config") {
      if (!value(&flags.config_path)) return Usage("--config needs a FILE");
    } else if (a == "--replay") {
      if (!value(&replay)) return Usage("--replay needs a LOGFILE");
    } else if (a == "--export-atlas") {
      if (!value(&export_dir)) return Usage("--export-atlas needs a DIR");
    } else if (a == "--out") {
      if (!value(&out)) return Usage("--out needs a DIR");
    } else if (a == "--health-every") {
      std::string v, error;
      if (!value(&v)) return Usage("--health-every needs a number of seconds");
      if (!atlas::NumberArgument(a, v.c_str(), 0.001, 86400, flags.health_line_period_s, error))
        return Usage(error);
    } else if (a == "--quiet") {
      flags.quiet = true;
    } else if (a == "--debug-stall-on-usr1") {
      flags.debug_stall_on_usr1 = true;
    } else {
      return Usage("unknown argument '" + a + "'");
    }
  }
  if (flags.config_path.empty())
    flags.config_path =
        Exists("/etc/atlasd/atlasd.toml") ? "/etc/atlasd/atlasd.toml" : "config/atlasd.toml";
  atlas::ConfigResult config =
      atlas::LoadConfigFile(flags.config_path, atlas::ValidateDerivedOptions);
  if (!config.ok()) {
    for (const auto& e : config.errors) std::fprintf(stderr, "%s\n", e.ToString().c_str());
    std::fprintf(stderr, "atlasd: configuration %s rejected (exit 78)\n",
                 flags.config_path.c_str());
    return atlas::kExitConfigError;
  }
  std::fprintf(stderr, "atlasd: configuration %s\n", flags.config_path.c_str());
  if (!export_dir.empty()) return atlas::ExportSavedAtlas(config.options, export_dir);
  if (!replay.empty()) {
    if (out.empty()) return Usage("--replay needs --out DIR");
    return atlas::RunReplay(config.options, replay, out);
  }
  if (!out.empty()) return Usage("--out is for --replay");
  return atlas::RunLiveDaemon(config.options, flags);
}
