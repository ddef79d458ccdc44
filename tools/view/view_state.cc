#include "tools/view/view_state.h"

#include <algorithm>
#include <climits>

namespace atlas::view {

const char* IngestResultName(IngestResult r) {
  switch (r) {
    case IngestResult::kStored:
      return "stored";
    case IngestResult::kUnknownChannel:
      return "unknown channel";
    case IngestResult::kUndecodable:
      return "undecodable";
    case IngestResult::kTooLarge:
      return "too large";
  }
  return "?";
}

namespace {

// lcm-gen's decode: the number of bytes read, or < 0 when the bytes are not a whole message of
// this type. Trailing bytes are refused too.
template <typename Message>
bool Decode(const void* data, size_t size, Message* out) {
  const int n = static_cast<int>(size);
  return out->decode(data, 0, n) == n;
}

}  // namespace

ViewState::ViewState(const ViewChannels& channels, int max_maps)
    : channels_(channels), max_maps_(std::max(1, max_maps)) {}

const Received<atlasd::local_map_t>* ViewState::latest_map() const {
  auto it = maps_.find(latest_map_frame_);
  return it == maps_.end() ? nullptr : &it->second;
}

IngestResult ViewState::Ingest(std::string_view channel, const void* data, size_t size, Time now) {
  IngestResult r = IngestResult::kStored;
  if (channel != channels_.pose && channel != channels_.local_map && channel != channels_.graph &&
      channel != channels_.hypotheses && channel != channels_.health) {
    r = IngestResult::kUnknownChannel;
  } else if (size > kMaxMessageBytes || size > static_cast<size_t>(INT_MAX)) {
    r = IngestResult::kTooLarge;
  } else if (channel == channels_.pose) {
    atlasd::pose_t m;
    if (!Decode(data, size, &m))
      r = IngestResult::kUndecodable;
    else
      pose_ = Received<atlasd::pose_t>{m, now};
  } else if (channel == channels_.graph) {
    atlasd::atlas_graph_t m;
    if (!Decode(data, size, &m))
      r = IngestResult::kUndecodable;
    else
      graph_ = Received<atlasd::atlas_graph_t>{std::move(m), now};
  } else if (channel == channels_.hypotheses) {
    atlasd::hypotheses_t m;
    if (!Decode(data, size, &m))
      r = IngestResult::kUndecodable;
    else
      hypotheses_ = Received<atlasd::hypotheses_t>{std::move(m), now};
  } else if (channel == channels_.health) {
    atlasd::health_t m;
    if (!Decode(data, size, &m))
      r = IngestResult::kUndecodable;
    else
      health_ = Received<atlasd::health_t>{std::move(m), now};
  } else {
    atlasd::local_map_t m;
    if (!Decode(data, size, &m)) {
      r = IngestResult::kUndecodable;
    } else if (m.frame_id >= 0) {  // -1: no dominant hypothesis, nothing to remember
      const int32_t frame = m.frame_id;
      if (!maps_.contains(frame) && static_cast<int>(maps_.size()) >= max_maps_) {
        auto oldest = std::min_element(
            maps_.begin(), maps_.end(),
            [](const auto& a, const auto& b) { return a.second.at < b.second.at; });
        maps_.erase(oldest);
        ++forgotten_maps_;
      }
      maps_[frame] = Received<atlasd::local_map_t>{std::move(m), now};
      latest_map_frame_ = frame;
    }
  }
  if (r == IngestResult::kStored) {
    ++version_;
    ++stored_;
  } else {
    ++rejected_;
  }
  return r;
}

}  // namespace atlas::view
