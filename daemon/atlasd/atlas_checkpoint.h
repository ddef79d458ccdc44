#pragma once
// The atlas as the store keeps it (docs/atlasd.md, "Persistence"): what the step loop hands to the
// store's writer thread, and how a start resumes from what was saved.
//
// The authoritative record is the whole atlas image (Atlas::Serialize(), graph, maps,
// hypotheses and bookkeeping) in the metadata value "atlas_image", with "atlas_image_version"
// (Atlas::kImageVersion, decimal text) and "atlas_steps". The frames and edges tables are kept
// for people and tools: a frame's row (its map image) is written when the frame is new or holds
// a live hypothesis (only those maps change), an edge's row when its transform or kind changed.
//
// Contract:
// - CheckpointBuilder::Make() runs on the loop thread between steps; it only reads the atlas
//   and copies bytes (O(atlas size)); it never touches SQLite. The loop calls it at most once
//   per state.save_period_s and hands the batch to AtlasStoreWriter::Submit().
// - ResumeFromStore() runs before the loop starts. A store without an image leaves the atlas
//   empty (kEmpty). An image that decodes replaces the atlas, and the robot starts in a new
//   frame (Atlas::ResumeInNewFrame(): every saved hypothesis is dropped; map-matching joins
//   the new frame to the old ones when it recognises them) (kResumed). An image written by a
//   newer atlasd (a larger atlas_image_version), or one that does not decode, is refused: the
//   store file is moved aside, never overwritten (AtlasStore::RefuseAndStartEmpty), and the
//   atlas starts empty (kRefusedNewer, kRefusedCorrupt). An atlas_image_version that is not a
//   whole decimal integer in [0, 4294967295] ("abc", "1x", "", "-1", a larger number) is
//   refused as corrupt. Every outcome has a one-line message.

#include <cstdint>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "daemon/store/atlas_store.h"

namespace atlas {

class CheckpointBuilder {
 public:
  // A batch with the atlas image and the frame and edge rows that changed since the last call.
  AtlasSnapshot Make(const Atlas& atlas);

 private:
  int frames_sent_ = 0;
  std::vector<StoredEdge> edges_sent_;  // as last sent, by edge index
};

enum class ResumeOutcome { kEmpty, kResumed, kRefusedCorrupt, kRefusedNewer, kFailed };

struct ResumeResult {
  ResumeOutcome outcome = ResumeOutcome::kFailed;
  std::string message;           // one line, for the log
  int frames = 0;                // frames of the saved atlas
  int64_t steps = 0;             // steps the saved atlas had made
  FrameId new_frame = kNoFrame;  // kResumed: the robot's new, unconnected frame
};

// `store` is open; `atlas` is empty and built with the configured options.
ResumeResult ResumeFromStore(AtlasStore* store, Atlas* atlas);

const char* ToString(ResumeOutcome o);

}  // namespace atlas
