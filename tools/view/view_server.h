#pragma once
// atlas-view's process: the owner of the sockets (LCM and HTTP) around the pure parts
// (view_state.h decodes, view_json.h builds, snapshot_hub.h hands updates over).
//
// Threads: the LCM thread feeds a ViewState; the update thread, while at least one event stream
// is open, builds the page's JSON at most `rate_hz` times a second when something new arrived
// and publishes it to the hub; HTTP requests run on a fixed pool of max_clients + 2 threads
// (each open event stream holds one) with a bounded hand-over queue, so further connections wait
// in the kernel's listen backlog. Routes: GET / (the page), GET /events (text/event-stream),
// GET /snapshot.json (the latest update); nothing else, and nothing that writes.

#include "tools/view/view_options.h"

namespace atlas::view {

// Runs until SIGINT or SIGTERM (the caller blocks them in every thread first). Returns the exit
// code: 0 after a signal, 1 when the port cannot be bound or LCM cannot be opened.
int RunViewServer(const ViewOptions& options);

}  // namespace atlas::view
