#pragma once
// graph.tsv of a replay output directory and of `atlasd --export-atlas` (docs/formats.md,
// "Replay output"): one row per edge of the atlas graph, "from to x y theta c00 c01 c02 c11
// c12 c22 kind": the pose of frame `to` in frame `from`, the upper triangle of its covariance
// over (x, y, theta), and the provenance of the estimate (genesis, map-match, refined).

#include <string>
#include <string_view>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/eval/atlas_relations.h"

namespace atlas::formats {

struct GraphRows {
  std::vector<eval::EdgeRow> edges;
  std::vector<int64_t> lines;  // the line of each edge
  int frame_count = 0;         // 1 + the largest frame id named
};

// Appends the rows of `text` to `out`; "" or "<source>:<line>: <what>". Refused: a field that is
// not a frame id, a number or an edge kind; a pose beyond the limits of text_rows.h (theta is
// wrapped to (-pi, pi]); a covariance that is not positive definite
// (core/geometry/covariance.h); an edge joining a frame to itself; a second edge between two
// frames (the atlas graph holds at most one, core/atlas/atlas_graph.h).
std::string ParseGraphTsv(std::string_view text, const std::string& source, GraphRows* out);

// One row (with its newline) for an edge; poses with 6 decimals, covariances with %.9g.
std::string GraphTsvRow(const AtlasEdge& edge);
// The file: the header line "# <comment>", then one row per edge of `graph`.
std::string FormatGraphTsv(const AtlasGraph& graph, std::string_view comment);

// The kind written in graph.tsv back to the enum; false for an unknown name.
bool EdgeKindFromName(std::string_view name, EdgeKind* kind);

}  // namespace atlas::formats
