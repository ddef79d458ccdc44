#include "daemon/atlasd/atlas_export.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "daemon/atlasd/atlas_checkpoint.h"
#include "daemon/atlasd/daemon_setup.h"

namespace atlas {
namespace {

template <typename... Args>
void Append(std::string& s, const char* format, Args... args) {
  char line[512];
  const int n = std::snprintf(line, sizeof(line), format, args...);
  if (n > 0) s.append(line, static_cast<size_t>(std::min<int>(n, sizeof(line) - 1)));
}

std::string WriteText(const std::string& dir, const char* name, const std::string& text) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return out.good() ? "" : "cannot write " + path;
}

}  // namespace

std::string GraphTsvRow(const AtlasEdge& edge) {
  std::string text;
  const Pose2& p = edge.b_in_a.mean;
  const Mat3& c = edge.b_in_a.cov;
  Append(text, "%d\t%d\t%.6f\t%.6f\t%.6f\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%s\n", edge.a, edge.b,
         p.x, p.y, p.theta, c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2),
         EdgeKindName(edge.kind));
  return text;
}

std::string MapsTsvRows(const AtlasGraph& graph) {
  std::string text;
  for (FrameId f = 0; f < graph.FrameCount(); ++f) {
    const LocalMap* map = graph.Frame(f).map.get();
    if (map == nullptr) continue;
    for (const MapLine& l : map->Lines())
      Append(text, "%d\t%d\t%.6f\t%.6f\t%.4f\t%.4f\t%.4f\t%.4f\t%.9g\t%.9g\t%.9g\n", f, l.id, l.rho,
             l.alpha, l.endpoint_a.x(), l.endpoint_a.y(), l.endpoint_b.x(), l.endpoint_b.y(),
             l.cov(0, 0), l.cov(0, 1), l.cov(1, 1));
  }
  return text;
}

std::string PointsTsvRows(const AtlasGraph& graph) {
  std::string text;
  for (FrameId f = 0; f < graph.FrameCount(); ++f)
    for (const Vec2& c : graph.Frame(f).points.Centres())
      Append(text, "%d\t%.2f\t%.2f\n", f, c.x(), c.y());
  return text;
}

std::string WriteAtlasFiles(const Atlas& atlas, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create " + dir + ": " + ec.message();
  const AtlasGraph& graph = atlas.Graph();
  std::string text = "# atlasd graph: from to x y theta c00 c01 c02 c11 c12 c22 kind\n";
  for (const AtlasEdge& edge : graph.Edges()) text += GraphTsvRow(edge);
  if (std::string e = WriteText(dir, "graph.tsv", text); !e.empty()) return e;
  text = "# atlasd maps: frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa\n";
  text += MapsTsvRows(graph);
  if (std::string e = WriteText(dir, "maps.tsv", text); !e.empty()) return e;
  text = "# atlasd points: frame x y (cell centres of the laser points each frame keeps)\n";
  text += PointsTsvRows(graph);
  return WriteText(dir, "points.tsv", text);
}

int ExportSavedAtlas(const DaemonOptions& options, const std::string& dir) {
  AtlasStore store;
  // Read-only: an export never creates, changes or moves the store (a corrupt one is only
  // reported; atlasd moves it aside when it starts).
  const StoreOpenResult opened = store.OpenReadOnly(options.state.directory);
  if (!opened.ok()) {
    std::fprintf(stderr, "atlasd: --export-atlas: %s\n", opened.message.c_str());
    return 1;
  }
  std::unique_ptr<Atlas> atlas = MakeAtlas(ToMapperSettings(options));
  StoredAtlas saved;
  std::string error;
  if (!store.Load(&saved, &error)) {
    std::fprintf(stderr, "atlasd: --export-atlas: %s\n", error.c_str());
    return 1;
  }
  const auto image = saved.metadata.find("atlas_image");
  if (image == saved.metadata.end() || !atlas->Deserialize(image->second)) {
    std::fprintf(stderr,
                 "atlasd: --export-atlas: %s holds no atlas this atlasd can read (start atlasd "
                 "once to have it checked)\n",
                 store.path().c_str());
    return 1;
  }
  if (std::string e = WriteAtlasFiles(*atlas, dir); !e.empty()) {
    std::fprintf(stderr, "atlasd: --export-atlas: %s\n", e.c_str());
    return 1;
  }
  std::fprintf(stderr, "atlasd: exported %d frames and %d edges from %s to %s\n",
               atlas->Graph().FrameCount(), atlas->Graph().EdgeCount(), store.path().c_str(),
               dir.c_str());
  return 0;
}

}  // namespace atlas
