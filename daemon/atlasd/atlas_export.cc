#include "daemon/atlasd/atlas_export.h"

#include <cstdio>
#include <filesystem>

#include "daemon/atlasd/atlas_checkpoint.h"
#include "daemon/atlasd/daemon_setup.h"
#include "formats/graph_tsv.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"

namespace atlas {
namespace {

std::string WriteText(const std::string& dir, const char* name, const std::string& text) {
  return formats::WriteTextFile((std::filesystem::path(dir) / name).string(), text);
}

}  // namespace

std::string WriteAtlasFiles(const Atlas& atlas, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create " + dir + ": " + ec.message();
  const AtlasGraph& graph = atlas.Graph();
  std::string text = formats::FormatGraphTsv(
      graph, "atlasd graph: from to x y theta c00 c01 c02 c11 c12 c22 kind");
  if (std::string e = WriteText(dir, "graph.tsv", text); !e.empty()) return e;
  text = "# atlasd maps: frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa\n";
  text += formats::MapsTsvRows(graph);
  if (std::string e = WriteText(dir, "maps.tsv", text); !e.empty()) return e;
  text =
      "# atlasd points: frame x y (cell centres of the laser points each frame keeps, or of a "
      "grid frame's occupied cells)\n";
  text += formats::PointsTsvRows(graph);
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
  if (const std::string why = LoadSavedAtlas(saved, atlas.get()); !why.empty()) {
    std::fprintf(stderr,
                 "atlasd: --export-atlas: %s holds no atlas this atlasd can read: %s (start "
                 "atlasd once to have it checked)\n",
                 store.path().c_str(), why.c_str());
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
