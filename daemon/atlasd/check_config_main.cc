// atlas-check-config: checks atlasd configuration files, as `atlasd --check-config FILE` does.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "daemon/atlasd/daemon_setup.h"
#include "formats/config/config_loader.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    "Checks atlasd configuration files (TOML; config/atlasd.toml documents every key).\n"
    "Prints every error as FILE:LINE:COLUMN: KEY: MESSAGE. After --, every argument is a FILE\n"
    "(for a file name that starts with '-').";

constexpr const char* kFooter =
    "Exit status: 0 when every file is valid, 78 (EX_CONFIG) otherwise, 2 on a bad command line\n"
    "(as atlasd).\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  atlas::cli::CommandLine command_line("atlas-check-config", {"atlas-check-config [--] FILE..."},
                                       kDescription, kFooter);
  atlas::cli::AddPositional(command_line.app(), "FILE", &files, "configuration files");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (files.empty()) return command_line.Usage("no configuration FILE given");
  int status = 0;
  for (const std::string& file : files) {
    if (atlas::CheckConfigCommand(file, atlas::ValidateDerivedOptions, std::cout, std::cerr) != 0)
      status = atlas::kExitConfigError;
  }
  return status;
}
