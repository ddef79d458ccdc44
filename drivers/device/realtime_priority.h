#pragma once
// Real-time scheduling of a reader thread, so that arrival stamps are not delayed on a loaded
// machine (docs/atlasd.md, the `scheduling.*` keys).

#include <string>

namespace atlas {

// Puts the calling thread under SCHED_FIFO at `priority` (1..99). Empty when done; else why it
// was refused ("SCHED_FIFO priority 40 refused (Operation not permitted)"), and the thread keeps
// its scheduling.
std::string UseRealtimePriority(int priority);

}  // namespace atlas
