#pragma once
// What atlas-view draws: the latest of each atlasd message (docs/lcm.md), decoded from the bytes
// LCM delivered with lcm-gen's decode (which checks the type's fingerprint), with the time it
// arrived. Pure: no LCM instance, no socket; the server's LCM thread feeds it.
//
// ATLAS_LOCAL_MAP carries the dominant frame's map only, so the lines of every frame seen
// dominant are remembered (the latest map of each), for at most `max_maps` frames: when full,
// the map refreshed longest ago is forgotten. Kept laser points are not on LCM and are not drawn.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string_view>

#include "atlasd/atlas_graph_t.hpp"
#include "atlasd/health_t.hpp"
#include "atlasd/hypotheses_t.hpp"
#include "atlasd/local_map_t.hpp"
#include "atlasd/pose_t.hpp"
#include "core/common/time.h"
#include "tools/view/view_options.h"

namespace atlas::view {

enum class IngestResult {
  kStored,
  kUnknownChannel,  // not one of the five channels
  kUndecodable,     // not the channel's type (fingerprint), or cut short
  kTooLarge,        // over kMaxMessageBytes: ignored unread
};
const char* IngestResultName(IngestResult r);

// Larger than any atlas graph atlasd can publish on UDP multicast (LCM fragments up to 4 GB, but
// one message this large would stall the page anyway).
inline constexpr size_t kMaxMessageBytes = 64u << 20;

template <typename Message>
struct Received {
  Message message;
  Time at{};
};

class ViewState {
 public:
  ViewState(const ViewChannels& channels, int max_maps);

  IngestResult Ingest(std::string_view channel, const void* data, size_t size, Time now);

  const std::optional<Received<atlasd::pose_t>>& pose() const { return pose_; }
  const std::optional<Received<atlasd::atlas_graph_t>>& graph() const { return graph_; }
  const std::optional<Received<atlasd::hypotheses_t>>& hypotheses() const { return hypotheses_; }
  const std::optional<Received<atlasd::health_t>>& health() const { return health_; }
  // The latest map of each frame seen dominant, by frame id.
  const std::map<int32_t, Received<atlasd::local_map_t>>& maps() const { return maps_; }
  // The latest local map received (the dominant frame's), or nullptr.
  const Received<atlasd::local_map_t>* latest_map() const;

  // Increases with every stored message: a page update is due only when it changed.
  uint64_t version() const { return version_; }
  int64_t stored() const { return stored_; }
  int64_t rejected() const { return rejected_; }
  int64_t forgotten_maps() const { return forgotten_maps_; }

 private:
  ViewChannels channels_;
  int max_maps_;
  std::optional<Received<atlasd::pose_t>> pose_;
  std::optional<Received<atlasd::atlas_graph_t>> graph_;
  std::optional<Received<atlasd::hypotheses_t>> hypotheses_;
  std::optional<Received<atlasd::health_t>> health_;
  std::map<int32_t, Received<atlasd::local_map_t>> maps_;
  int32_t latest_map_frame_ = -1;
  uint64_t version_ = 0;
  int64_t stored_ = 0, rejected_ = 0, forgotten_maps_ = 0;
};

}  // namespace atlas::view
