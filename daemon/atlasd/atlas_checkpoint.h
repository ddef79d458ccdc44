#pragma once
// The atlas as the store keeps it (docs/atlasd.md, "Persistence"): what the step loop hands to the
// store's writer thread, and how a start resumes from what was saved.
//
// The atlas is saved in two parts, written in one transaction per batch:
// - the metadata value "atlas_image": Atlas::SerializeWithoutFrameMaps() (graph, frame points,
//   hypotheses with their trial maps, bookkeeping; no frame's map), with "atlas_image_version"
//   (Atlas::kImageVersion, decimal text) and "atlas_steps";
// - the frames table: one row per frame, its map image (LocalMap::Serialize()). A frame's row
//   is written when the frame is new and whenever its map changed since the last batch
//   (MapFrame::map_revision: every step of a mature hypothesis in it, a juvenile maturing into
//   it), so the rows and the image of a batch are the same atlas.
// The edges table holds each edge as last changed (for people and tools). Images of version 5
// and older embed every frame's map, and their frame rows are not read.
//
// Contract:
// - CheckpointBuilder::Make() runs on the loop thread between steps; it only reads the atlas
//   and copies bytes; it never touches SQLite. Its cost is O(frames + edges) comparisons plus
//   the image without maps plus the maps that changed (those of the frames with a mature
//   hypothesis since the last batch, and new frames), not the whole atlas
//   (atlas_checkpoint_benchmark.cc; docs/atlasd.md, "Persistence"). The loop calls it at
//   most once per state.save_period_s and hands the batch to AtlasStoreWriter::Submit(), whose
//   merges keep the newest row of each frame. Every batch must reach the store, in order (a
//   batch that is never saved leaves the rows behind the next image); when the writer stops,
//   nothing later is saved and the store keeps its last whole batch.
// - ResumeFromStore() runs before the loop starts. A store without an image leaves the atlas
//   empty (kEmpty). An image that decodes (with its frames' rows, version 6) replaces the
//   atlas, and the robot starts in a new frame (Atlas::ResumeInNewFrame(): every saved
//   hypothesis is dropped; map-matching joins the new frame to the old ones when it recognises
//   them) (kResumed); given the builder, it counts the loaded rows as sent, so that the first
//   batch carries only what changed. An image written by a newer atlasd (a larger
//   atlas_image_version), one that does not decode, or one whose frame has no row or a row
//   that does not decode, is refused: the store file is moved aside, never overwritten
//   (AtlasStore::RefuseAndStartEmpty), and the atlas starts empty (kRefusedNewer,
//   kRefusedCorrupt). An atlas_image_version that is not a whole decimal integer in
//   [0, 4294967295] ("abc", "1x", "", "-1", a larger number) is refused as corrupt. Every
//   outcome has a one-line message.

#include <cstdint>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "daemon/store/atlas_store.h"

namespace atlas {

class CheckpointBuilder {
 public:
  // A batch with the atlas image and the frame and edge rows that changed since the last call
  // (the first call: every frame and edge).
  AtlasSnapshot Make(const Atlas& atlas);
  // The store holds `atlas` as it is now, its frame and edge rows included (it was just loaded
  // from them): the next Make() sends only what changes from here.
  void AssumeSaved(const Atlas& atlas);

 private:
  std::vector<uint64_t> maps_sent_;     // by frame id: the map_revision last sent, 0 if none
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

// `store` is open; `atlas` is empty and built with the configured options. `checkpoints`
// (optional) is the builder of the batches that will follow.
ResumeResult ResumeFromStore(AtlasStore* store, Atlas* atlas,
                             CheckpointBuilder* checkpoints = nullptr);

// The atlas `saved` holds, loaded into `atlas` (the image, with the frames' maps from their
// rows when the image keeps them apart): "" when loaded, else why not, completing "refused
// the atlas store PATH because ..." (one line; `atlas` is then unchanged). For ResumeFromStore
// and atlasd --export-atlas. *maps_from_rows (optional): whether every frame's map came from
// its row.
std::string LoadSavedAtlas(const StoredAtlas& saved, Atlas* atlas, bool* maps_from_rows = nullptr);

const char* ToString(ResumeOutcome o);

}  // namespace atlas
