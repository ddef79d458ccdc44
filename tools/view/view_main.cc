// atlas-view: watch atlasd live in a browser (see --help and docs/atlas-view.md).
#include <signal.h>

#include <cstdio>

#include "core/common/version.h"
#include "tools/view/view_options.h"
#include "tools/view/view_server.h"

int main(int argc, char** argv) {
  const atlas::view::ViewArguments args = atlas::view::ParseViewArguments(argc, argv);
  if (args.help) {
    std::fputs(atlas::view::kViewHelp, stdout);
    return 0;
  }
  if (args.version) {
    std::fputs(atlas::VersionLine("atlas-view").c_str(), stdout);
    return 0;
  }
  if (!args.error.empty()) {
    std::fprintf(stderr, "atlas-view: %s (see --help)\n", args.error.c_str());
    return 2;
  }
  // SIGINT and SIGTERM are taken by sigtimedwait in RunViewServer: blocked in every thread.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  signal(SIGPIPE, SIG_IGN);
  return atlas::view::RunViewServer(args.options);
}
