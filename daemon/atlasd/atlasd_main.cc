// atlasd: the real-time Atlas mapping daemon. See --help and docs/atlasd.md.
#include <sys/stat.h>

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "core/common/version.h"
#include "daemon/atlasd/atlas_export.h"
#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/live_daemon.h"
#include "daemon/atlasd/replay.h"
#include "daemon/notify/stderr_log.h"
#include "formats/config/config_loader.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    R"(The Atlas mapping daemon: reads the laser, odometry and sonar devices named in the
configuration, steps the atlas once per scan under a fixed budget, and publishes the pose,
local map, atlas graph, hypotheses and health on LCM (docs/atlasd.md, docs/lcm.md).)";

constexpr const char* kFooter =
    R"(signals: SIGTERM/SIGINT stop (STOPPING=1, exits within a second), SIGHUP reloads the
configuration file (what can change while running is applied, the rest is listed).
exit codes: 0 stopped cleanly, 1 could not start, 2 bad command line, 78 bad configuration.
)";

bool Exists(const char* path) {
  struct stat st;
  return stat(path, &st) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace cli = atlas::cli;
  atlas::LiveFlags flags;
  std::string replay, out, export_dir, check_config;
  cli::CommandLine command_line("atlasd",
                                {"atlasd [--config FILE] [options]", "atlasd --check-config FILE",
                                 "atlasd --replay LOGFILE --out DIR [--config FILE]",
                                 "atlasd --export-atlas DIR [--config FILE]"},
                                kDescription, kFooter);
  CLI::App& app = command_line.app();
  cli::AddText(app, "--config", "FILE", &flags.config_path,
               "configuration (default /etc/atlasd/atlasd.toml when it exists,\n"
               "else config/atlasd.toml in the working directory)");
  cli::AddText(app, "--check-config", "FILE", &check_config,
               "check a configuration file and exit: 0 when valid, 78 (EX_CONFIG)\n"
               "with every error (file:line:column: key: message) otherwise");
  cli::AddText(app, "--replay", "LOGFILE", &replay,
               "offline: run the same loop over the raw channels of an lcm-logger\n"
               "file (recorded with lcm.republish_raw = true) or over a CARMEN log\n"
               "instead of devices; the scans and/or sonar readings stepped are\n"
               "those localmap.sensors names, as live (give the session's\n"
               "configuration file)");
  cli::AddText(app, "-o,--out", "DIR", &out,
               "replay output: the files of atlas-replay (DIR/trajectory.tsv,\n"
               "graph.tsv, timing.tsv, ...; docs/formats.md, \"Replay output\")");
  cli::AddText(app, "--export-atlas", "DIR", &export_dir,
               "write the atlas saved in state.directory as DIR/graph.tsv and\n"
               "DIR/maps.tsv (atlas-replay's formats, for atlas-render --atlas) and exit");
  cli::AddNumber(app, "--health-every", "S", 0.001, 86400, &flags.health_line_period_s,
                 "print the health line on stderr every S seconds, 0.001 to 86400\n"
                 "(default: the health period, lcm.health_period_s)");
  cli::AddFlag(app, "--quiet", &flags.quiet, "no health line");
  cli::AddFlag(app, "--debug-stall-on-usr1", &flags.debug_stall_on_usr1,
               "test hook: SIGUSR1 stalls the loop thread for 5 s (the watchdog\n"
               "pings stop); never enable it in production");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (!check_config.empty())
    return atlas::CheckConfigCommand(check_config, atlas::ValidateDerivedOptions, std::cout,
                                     std::cerr);
  atlas::LogToStderr(atlas::LogPriority::kInfo, std::string("version ") + atlas::AtlasVersion());
  if (flags.config_path.empty())
    flags.config_path =
        Exists("/etc/atlasd/atlasd.toml") ? "/etc/atlasd/atlasd.toml" : "config/atlasd.toml";
  atlas::ConfigResult config =
      atlas::LoadConfigFile(flags.config_path, atlas::ValidateDerivedOptions);
  if (!config.ok()) {
    for (const auto& e : config.errors) atlas::LogToStderr(atlas::LogPriority::kErr, e.ToString());
    atlas::LogToStderr(atlas::LogPriority::kErr,
                       "configuration " + flags.config_path + " rejected (exit 78)");
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
