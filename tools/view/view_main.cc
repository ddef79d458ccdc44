// atlas-view: watch atlasd live in a browser (see --help and docs/atlas-view.md).
#include <signal.h>

#include <optional>

#include "tools/view/view_options.h"
#include "tools/view/view_server.h"

int main(int argc, char** argv) {
  atlas::view::ViewOptions options;
  if (std::optional<int> done = atlas::view::ParseViewCommandLine(argc, argv, &options))
    return *done;
  // SIGINT and SIGTERM are taken by sigtimedwait in RunViewServer: blocked in every thread.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  signal(SIGPIPE, SIG_IGN);
  return atlas::view::RunViewServer(options);
}
