// atlas-check-config: checks atlasd configuration files, as `atlasd --check-config FILE` does.
#include <cstring>
#include <iostream>
#include <string>

#include "daemon/atlasd/daemon_setup.h"
#include "daemon/config/config_loader.h"

namespace {

void PrintHelp() {
  std::cout
      << "usage: atlas-check-config FILE...\n"
         "\n"
         "Checks atlasd configuration files (TOML; config/atlasd.toml documents every key).\n"
         "Prints every error as FILE:LINE:COLUMN: KEY: MESSAGE.\n"
         "Exit status: 0 when every file is valid, 78 (EX_CONFIG) otherwise, 64 on bad usage.\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    PrintHelp();
    return 64;  // EX_USAGE
  }
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      PrintHelp();
      return 0;
    }
  }
  for (int i = 1; i < argc; ++i) {
    if (atlas::CheckConfigCommand(argv[i], atlas::ValidateDerivedOptions, std::cout, std::cerr) !=
        0) {
      status = atlas::kExitConfigError;
    }
  }
  return status;
}
