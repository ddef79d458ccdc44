#include "daemon/atlasd/atlas_checkpoint.h"

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
  b.metadata[kImageKey] = atlas.Serialize();
  b.metadata[kImageVersionKey] = std::to_string(Atlas::kImageVersion);
  b.metadata[kStepsKey] = std::to_string(atlas.StepCount());
  const AtlasGraph& g = atlas.Graph();
  std::vector<bool> send(static_cast<size_t>(g.FrameCount()), false);
  for (FrameId f = frames_sent_; f < g.FrameCount(); ++f) send[static_cast<size_t>(f)] = true;
  for (const Hypothesis& h : atlas.Hypotheses())
    if (h.frame >= 0 && h.frame < g.FrameCount()) send[static_cast<size_t>(h.frame)] = true;
  for (FrameId f = 0; f < g.FrameCount(); ++f)
    if (send[static_cast<size_t>(f)]) b.frames.push_back({f, g.Frame(f).map->Serialize(), 0});
  frames_sent_ = g.FrameCount();
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

ResumeResult ResumeFromStore(AtlasStore* store, Atlas* atlas) {
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
  } else if (!atlas->Deserialize(image->second)) {
    why = "its atlas image (" + std::to_string(image->second.size()) +
          " bytes) does not decode with this configuration";
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
