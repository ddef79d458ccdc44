#pragma once
// `atlasd --export-atlas DIR`: the atlas saved in the state directory, written as the atlas
// files of atlas-replay's output (docs/formats.md, "atlas-replay output"): graph.tsv (every
// edge), maps.tsv (every frame's lines) and points.tsv (the laser points each frame keeps for
// map-matching), so that atlas-render --atlas draws what the daemon built. trajectory.tsv comes
// from the poses atlasd published (scripts/demo.sh records them). Reads the store only
// (AtlasStore::OpenReadOnly: creates, changes and moves no file); refuses (non-zero exit,
// message) a store that is missing, unreadable, corrupt, or one it cannot resume from.

#include <string>

#include "core/atlas/atlas.h"
#include "daemon/config/daemon_options.h"

namespace atlas {

// One graph.tsv row (with its newline) for an edge: "from to x y theta c00 c01 c02 c11 c12 c22
// kind". Shared with atlas-replay, which writes the same format.
std::string GraphTsvRow(const AtlasEdge& edge);
// The maps.tsv rows of every frame's lines: "frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa".
std::string MapsTsvRows(const AtlasGraph& graph);
// The points.tsv rows of every frame's points (core/atlas/frame_points.h): "frame x y", the
// cell centres in the frame's coordinates.
std::string PointsTsvRows(const AtlasGraph& graph);

// Writes DIR/graph.tsv, DIR/maps.tsv and DIR/points.tsv of `atlas`; empty on success, else what
// failed.
std::string WriteAtlasFiles(const Atlas& atlas, const std::string& dir);

// The command: loads the store of options.state.directory and writes the files. Exit code.
int ExportSavedAtlas(const DaemonOptions& options, const std::string& dir);

}  // namespace atlas
