#pragma once
// Map-matching (paper, III-D) by a matcher of the local maps' own kind, for maps without
// lines (core/gridmap/grid_map_matcher.h: probability grids). When an Atlas is given one
// (Atlas::SetMapMatcher), it replaces the line matcher of map_match.h and its self-matches; the
// candidates, the prior from the bounded Dijkstra projection, the edge and the bookkeeping stay
// the Atlas's. Condition 2 is the matcher's to enforce: a match it cannot single out is
// kAmbiguous, never a guess.
//
// A match may be carried over several steps (Begin, then MapMatchSearch::Continue once per
// step), so that a search larger than one step's budget costs each step a bounded share
// (docs/design.md, "Constant time").

#include <memory>

#include "core/atlas/map_match.h"
#include "core/localmap/local_map.h"

namespace atlas {

class MapMatchSearch {
 public:
  virtual ~MapMatchSearch() = default;
  // One slice of at most the matcher's work per step. `a` and `b` are the maps of the two
  // frames the search began with, as they are now (they may have grown, or been replaced by a
  // matured juvenile's map, since). True when Result() is final.
  virtual bool Continue(const LocalMap& a, const LocalMap& b) = 0;
  virtual const MapMatch& Result() const = 0;
};

class MapMatcher {
 public:
  virtual ~MapMatcher() = default;
  // t (eq. 9): the pose of b's frame in a's frame. `prior` is that pose projected through the
  // graph (III-A), or null when the two frames are not connected.
  virtual MapMatch Match(const LocalMap& a, const LocalMap& b,
                         const UncertainPose* prior) const = 0;
  // The same match in slices. The matcher must outlive the search. Default: the whole Match at
  // the first Continue.
  virtual std::unique_ptr<MapMatchSearch> Begin(const LocalMap& a, const LocalMap& b,
                                                const UncertainPose* prior) const;
};

}  // namespace atlas
