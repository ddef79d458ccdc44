// atlas-check-config: checks atlasd configuration files, as `atlasd --check-config FILE` does.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "daemon/atlasd/daemon_setup.h"
#include "formats/config/config_loader.h"

namespace {

constexpr const char* kHelp =
    "usage: atlas-check-config [--] FILE...\n"
    "\n"
    "Checks atlasd configuration files (TOML; config/atlasd.toml documents every key).\n"
    "Prints every error as FILE:LINE:COLUMN: KEY: MESSAGE. After --, every argument is a FILE\n"
    "(for a file name that starts with '-').\n"
    "\n"
    "options:\n"
    "  -h, --help  this text\n"
    "\n"
    "Exit status: 0 when every file is valid, 78 (EX_CONFIG) otherwise, 2 on a bad command line\n"
    "(as atlasd).\n";

int Usage(const std::string& what) {
  std::fprintf(stderr, "atlas-check-config: %s (see atlas-check-config --help)\n", what.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  bool options_done = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (!options_done && (a == "-h" || a == "--help")) {
      std::fputs(kHelp, stdout);
      return 0;
    }
    if (!options_done && a == "--") {
      options_done = true;
    } else if (!options_done && a.size() > 1 && a[0] == '-') {
      return Usage("unknown option '" + a + "'");
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) return Usage("no configuration FILE given");
  int status = 0;
  for (const std::string& file : files) {
    if (atlas::CheckConfigCommand(file, atlas::ValidateDerivedOptions, std::cout, std::cerr) != 0)
      status = atlas::kExitConfigError;
  }
  return status;
}
