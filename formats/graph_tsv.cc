#include "formats/graph_tsv.h"

#include <algorithm>
#include <map>

#include "core/common/quote_for_message.h"
#include "core/geometry/covariance.h"
#include "formats/text_rows.h"

namespace atlas::formats {

bool EdgeKindFromName(std::string_view name, EdgeKind* kind) {
  for (EdgeKind k : {EdgeKind::kGenesis, EdgeKind::kMapMatch, EdgeKind::kRefined}) {
    if (name == EdgeKindName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::string ParseGraphTsv(std::string_view text, const std::string& source, GraphRows* out) {
  std::map<std::pair<FrameId, FrameId>, int64_t> pairs;  // the line of each joined pair
  return ForEachRow(
      text, source, 12, "from to x y theta c00 c01 c02 c11 c12 c22 kind",
      [&](std::span<const std::string_view> f, int64_t line) {
        eval::EdgeRow e;
        if (std::string bad = FrameField(f[0], 1, false, &e.from); !bad.empty()) return bad;
        if (std::string bad = FrameField(f[1], 2, false, &e.to); !bad.empty()) return bad;
        const std::string name = std::to_string(e.from) + "-" + std::to_string(e.to);
        if (e.from == e.to) return "edge " + name + " joins a frame to itself";
        if (std::string bad = PoseFields(f, 2, &e.to_in_from.mean); !bad.empty()) return bad;
        double c[6];
        for (size_t k = 0; k < 6; ++k)
          if (std::string bad = NumberField(f[5 + k], 6 + k, &c[k]); !bad.empty()) return bad;
        e.to_in_from.cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
        if (!IsPositiveDefiniteCovariance(e.to_in_from.cov))
          return "covariance of edge " + name +
                 " is not positive definite (fields 6-11, c00 c01 c02 c11 c12 c22, the upper "
                 "triangle of a 3x3 covariance; atlas-replay writes positive definite ones: "
                 "re-run it or fix the row)";
        if (!EdgeKindFromName(f[11], &e.kind))
          return "field 12 is " + QuoteForMessage(f[11]) +
                 ", not an edge kind (genesis, map-match, refined)";
        const std::pair<FrameId, FrameId> key{std::min(e.from, e.to), std::max(e.from, e.to)};
        if (const auto it = pairs.find(key); it != pairs.end())
          return "edge " + name + " joins two frames that line " + std::to_string(it->second) +
                 " already joins";
        pairs.emplace(key, line);
        out->frame_count = std::max(out->frame_count, std::max(e.from, e.to) + 1);
        out->edges.push_back(e);
        out->lines.push_back(line);
        return std::string();
      });
}

std::string GraphTsvRow(const AtlasEdge& edge) {
  std::string text;
  const Pose2& p = edge.b_in_a.mean;
  const Mat3& c = edge.b_in_a.cov;
  AppendF(&text, "%d\t%d\t%.6f\t%.6f\t%.6f\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%s\n", edge.a,
          edge.b, p.x, p.y, p.theta, c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2),
          EdgeKindName(edge.kind));
  return text;
}

std::string FormatGraphTsv(const AtlasGraph& graph, std::string_view comment) {
  std::string text = "# " + std::string(comment) + "\n";
  for (const AtlasEdge& edge : graph.Edges()) text += GraphTsvRow(edge);
  return text;
}

}  // namespace atlas::formats
