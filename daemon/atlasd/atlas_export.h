#pragma once
// `atlasd --export-atlas DIR`: the atlas saved in the state directory, written as the atlas
// files of atlas-replay's output (docs/formats.md, "Replay output"): graph.tsv (every
// edge), maps.tsv (every frame's lines) and points.tsv (the laser points each frame keeps for
// map-matching, or a grid frame's occupied cells), so that atlas-render --atlas draws what the
// daemon built. trajectory.tsv comes from the poses atlasd published (scripts/demo.sh records
// them). Reads the store only (AtlasStore::OpenReadOnly: creates, changes and moves no file);
// refuses (non-zero exit, message) a store that is missing, unreadable, corrupt, or one it cannot
// resume from.

#include <string>

#include "core/atlas/atlas.h"
#include "formats/config/daemon_options.h"

namespace atlas {

// Writes DIR/graph.tsv, DIR/maps.tsv and DIR/points.tsv of `atlas` (formats/graph_tsv.h,
// formats/replay_dir.h); empty on success, else what failed.
std::string WriteAtlasFiles(const Atlas& atlas, const std::string& dir);

// The command: loads the store of options.state.directory and writes the files. Exit code.
int ExportSavedAtlas(const DaemonOptions& options, const std::string& dir);

}  // namespace atlas
