#include "daemon/atlasd/atlas_checkpoint.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "core/common/parse_number.h"

namespace atlas {
namespace {

constexpr const char* kImageKey = "atlas_image";
constexpr const char* kImageVersionKey = "atlas_image_version";
constexpr const char* kStepsKey = "atlas_steps";

StoredEdge ToStored(const AtlasEdge& e) {
  StoredEdge s;
  s.frame_from = e.a;
  s.frame_to = e.b;
  s.x = e.b_in_a.mean.x;
  s.y = e.b_in_a.mean.y;
  s.theta = e.b_in_a.mean.theta;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s.covariance[static_cast<size_t>(3 * r + c)] = e.b_in_a.cov(r, c);
  s.kind = static_cast<int>(e.kind);
  return s;
}

bool SameEdge(const StoredEdge& a, const StoredEdge& b) {
  return a.frame_from == b.frame_from && a.frame_to == b.frame_to && a.x == b.x && a.y == b.y &&
         a.theta == b.theta && a.covariance == b.covariance && a.kind == b.kind;
}

}  // namespace

const char* ToString(ResumeOutcome o) {
  switch (o) {
    case ResumeOutcome::kEmpty:
      return "empty";
    case ResumeOutcome::kResumed:
      return "resumed";
    case ResumeOutcome::kRefusedCorrupt:
      return "refused (corrupt)";
    case ResumeOutcome::kRefusedNewer:
      return "refused (newer)";
    case ResumeOutcome::kFailed:
      return "failed";
  }
  return "?";
}

AtlasSnapshot CheckpointBuilder::Make(const Atlas& atlas) {
  AtlasSnapshot b;
  b.metadata[kImageKey] = atlas.SerializeWithoutFrameMaps();
  b.metadata[kImageVersionKey] = std::to_string(Atlas::kImageVersion);
  b.metadata[kStepsKey] = std::to_string(atlas.StepCount());
  const AtlasGraph& g = atlas.Graph();
  maps_sent_.resize(static_cast<size_t>(g.FrameCount()), 0);
  for (FrameId f = 0; f < g.FrameCount(); ++f) {
    const MapFrame& frame = g.Frame(f);
    uint64_t& sent = maps_sent_[static_cast<size_t>(f)];
    if (sent == frame.map_revision) continue;
    b.frames.push_back({f, frame.map->Serialize(), 0});
    sent = frame.map_revision;
  }
  const std::vector<AtlasEdge>& edges = g.Edges();
  edges_sent_.resize(edges.size());
  for (size_t i = 0; i < edges.size(); ++i) {
    const StoredEdge s = ToStored(edges[i]);
    if (!SameEdge(s, edges_sent_[i])) {
      b.edges.push_back(s);
      edges_sent_[i] = s;
    }
  }
  return b;
}

void CheckpointBuilder::AssumeSaved(const Atlas& atlas) {
  const AtlasGraph& g = atlas.Graph();
  maps_sent_.resize(static_cast<size_t>(g.FrameCount()));
  for (FrameId f = 0; f < g.FrameCount(); ++f)
    maps_sent_[static_cast<size_t>(f)] = g.Frame(f).map_revision;
  edges_sent_.clear();
  for (const AtlasEdge& e : g.Edges()) edges_sent_.push_back(ToStored(e));
}

std::string LoadSavedAtlas(const StoredAtlas& saved, Atlas* atlas, bool* maps_from_rows) {
  const auto image = saved.metadata.find(kImageKey);
  if (image == saved.metadata.end()) return "it holds no atlas image";
  // The rows are ordered by frame id (AtlasStore::Load).
  int from_rows = 0;
  const Atlas::FrameMapImages rows = [&saved, &from_rows](FrameId f) -> const std::string* {
    const auto row = std::lower_bound(saved.frames.begin(), saved.frames.end(), f,
                                      [](const StoredFrame& r, FrameId id) { return r.id < id; });
    if (row == saved.frames.end() || row->id != f) return nullptr;
    ++from_rows;
    return &row->blob;
  };
  const ImageLoadResult r = atlas->DeserializeWithFrameMaps(image->second, rows);
  if (maps_from_rows != nullptr)
    *maps_from_rows = r.ok() && from_rows == atlas->Graph().FrameCount();
  const std::string frame = "frame " + std::to_string(r.frame);
  switch (r.status) {
    case ImageLoadStatus::kLoaded:
      return "";
    case ImageLoadStatus::kMalformed:
      return "its atlas image (" + std::to_string(image->second.size()) +
             " bytes) does not decode with this configuration";
    case ImageLoadStatus::kFrameMapMissing:
      return "its atlas image keeps the map of " + frame +
             " in the frames table, which has no row for it";
    case ImageLoadStatus::kFrameMapMalformed: {
      const std::string* blob = rows(r.frame);
      return "the map of " + frame + " (its row in the frames table, " +
             std::to_string(blob != nullptr ? blob->size() : 0) +
             " bytes) does not decode with this configuration";
    }
  }
  return "its atlas image does not load";
}

ResumeResult ResumeFromStore(AtlasStore* store, Atlas* atlas, CheckpointBuilder* checkpoints) {
  ResumeResult r;
  StoredAtlas saved;
  std::string error;
  if (!store->Load(&saved, &error)) {
    r.message = "cannot read the atlas store " + store->path() + ": " + error;
    return r;
  }
  const auto image = saved.metadata.find(kImageKey);
  if (image == saved.metadata.end()) {
    r.outcome = ResumeOutcome::kEmpty;
    r.message = "the atlas store " + store->path() + " holds no atlas yet: starting empty";
    return r;
  }
  const auto version = saved.metadata.find(kImageVersionKey);
  constexpr long kMaxVersion = std::numeric_limits<uint32_t>::max();
  long v = 0;
  const bool version_read = version == saved.metadata.end() ||
                            ParseIntegerIn(version->second.c_str(), 0, kMaxVersion, &v);
  const bool newer = version_read && v > static_cast<long>(Atlas::kImageVersion);
  std::string why;
  if (!version_read) {
    why = std::string("its atlas image version (") + kImageVersionKey + ", " +
          std::to_string(version->second.size()) + " bytes) is not a decimal integer in [0, " +
          std::to_string(kMaxVersion) + "]";
  } else if (newer) {
    why = "its atlas image is version " + std::to_string(v) +
          ", written by a newer atlasd (this one reads version " +
          std::to_string(Atlas::kImageVersion) + ")";
  } else {
    bool maps_from_rows = false;
    why = LoadSavedAtlas(saved, atlas, &maps_from_rows);
    // An older image embeds its maps; its rows may be behind it: the next batch writes them all.
    if (why.empty() && maps_from_rows && checkpoints != nullptr) checkpoints->AssumeSaved(*atlas);
  }
  if (!why.empty()) {
    const StoreOpenResult moved = store->RefuseAndStartEmpty(newer, why);
    r.outcome = !moved.ok() ? ResumeOutcome::kFailed
                : newer     ? ResumeOutcome::kRefusedNewer
                            : ResumeOutcome::kRefusedCorrupt;
    r.message = moved.message;
    return r;
  }
  r.outcome = ResumeOutcome::kResumed;
  r.frames = atlas->Graph().FrameCount();
  r.steps = atlas->StepCount();
  const int edges = atlas->Graph().EdgeCount();
  r.new_frame = atlas->ResumeInNewFrame();
  r.message = "resumed the saved atlas from " + store->path() + ": " + std::to_string(r.frames) +
              " frames, " + std::to_string(edges) + " edges, " + std::to_string(r.steps) +
              " steps; the robot starts in the new frame " + std::to_string(r.new_frame) +
              ", to be joined to the old ones by map-matching";
  return r;
}

}  // namespace atlas
