#pragma once
// `atlasd --export-atlas DIR`: the atlas saved in the state directory, written as the atlas
// files of atlas-replay's output (docs/formats.md, "atlas-replay output"): graph.tsv (every
// edge) and maps.tsv (every frame's lines), so that atlas-render --atlas draws what the daemon
// built. trajectory.tsv comes from the poses atlasd published (scripts/demo.sh records them).
// Reads the store only; refuses (non-zero exit, message) a store it cannot resume from.

#include <string>

#include "core/atlas/atlas.h"
#include "daemon/config/daemon_options.h"

namespace atlas {

// Writes DIR/graph.tsv and DIR/maps.tsv of `atlas`; empty on success, else what failed.
std::string WriteAtlasFiles(const Atlas& atlas, const std::string& dir);

// The command: loads the store of options.state.directory and writes the files. Exit code.
int ExportSavedAtlas(const DaemonOptions& options, const std::string& dir);

}  // namespace atlas
