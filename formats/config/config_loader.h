#pragma once
// Reads atlasd's TOML configuration file into DaemonOptions.
//
// Contract:
// - A key absent from the file keeps its default (daemon_options.h).
// - Unknown keys or sections, wrong types, values out of range and broken cross-field rules are
//   errors. Every error names the key (dotted: "laser.baud") and the file, line and column of
//   the offending key or value. All errors are collected, not only the first. With a
//   DerivedCheck (below), what the modules refuse is an error too.
// - A file that is not valid TOML gives one error at the position the parser stopped.
// - A path that does not name a regular file (a directory, a device), or a file that cannot be
//   opened or read to its end, gives one error without position that says why (with the
//   errno text) and what to do; it is never taken for an empty file (which means defaults).
// - Never throws; options are meaningful only when errors is empty.
//
// `atlasd --check-config FILE` and `atlas-check-config FILE` call CheckConfigCommand(), which
// exits 78 (EX_CONFIG from <sysexits.h>) on any error; systemd's RestartPreventExitStatus=78
// then stops restarting a daemon whose configuration is broken.

#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "formats/config/daemon_options.h"

namespace atlas {

inline constexpr int kExitConfigError = 78;  // EX_CONFIG

struct ConfigError {
  std::string file;
  int line = 0;  // 1-based; 0 when the error has no position (e.g. the file cannot be read)
  int column = 0;
  std::string key;  // dotted key, empty for file-level errors
  std::string message;

  // "FILE:LINE:COLUMN: KEY: MESSAGE" (parts without a value are left out).
  std::string ToString() const;
};

struct ConfigResult {
  DaemonOptions options;
  std::vector<ConfigError> errors;
  bool ok() const { return errors.empty(); }
};

// The options atlasd's modules derive from DaemonOptions (the atlas, the local maps, the step
// loop, the device readers) have their own Validate(). A DerivedCheck runs them all: empty when
// they accept the options, else one problem per line. atlasd and atlas-check-config pass
// ValidateDerivedOptions (daemon/atlasd/daemon_setup.h), so that a file the check accepts does
// not fail at start-up or at a reload; an empty DerivedCheck checks the file's own rules only.
// A derived problem is reported at each key of the file without which it goes away (keys set
// to their default are not suspects), else once for the file.
using DerivedCheck = std::function<std::string(const DaemonOptions&)>;

ConfigResult LoadConfigFile(const std::string& path, const DerivedCheck& derived);
// source_name is used as the file name in errors.
ConfigResult LoadConfigString(std::string_view toml_text, const std::string& source_name,
                              const DerivedCheck& derived = {});

// Every key with its value as text ("laser.baud" -> "500000"; enums by their file names), in
// key order: for logging the effective configuration and for comparing two of them.
std::map<std::string, std::string> FlattenOptions(const DaemonOptions& options);

// What a reload (SIGHUP) may change while running: the LCM periods and raw republishing, the
// noise models, the atlas parameters and budgets, the step budget and the save period. Devices,
// the LCM URL and channels, the state directory, queue capacities and scheduling need a restart.
bool IsReloadableKey(const std::string& key);

struct ReloadDiff {
  std::vector<std::string> reloadable;     // changed keys a running atlasd may apply
  std::vector<std::string> needs_restart;  // changed keys that take effect at the next start
};
ReloadDiff DiffForReload(const DaemonOptions& running, const DaemonOptions& loaded);

// Loads path (LoadConfigFile); prints each error on err (one per line) and returns
// kExitConfigError, or prints "PATH: configuration is valid" on out and returns 0.
int CheckConfigCommand(const std::string& path, const DerivedCheck& derived, std::ostream& out,
                       std::ostream& err);

}  // namespace atlas
