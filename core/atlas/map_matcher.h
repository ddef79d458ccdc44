#pragma once
// Map-matching (paper, III-D) by a matcher of the local maps' own kind, for maps without
// lines (core/gridmap/grid_map_matcher.h: probability grids). When an Atlas is given one
// (Atlas::SetMapMatcher), it replaces the line matcher of map_match.h and its self-matches; the
// candidates, the prior from the bounded Dijkstra projection, the edge and the bookkeeping stay
// the Atlas's. Condition 2 is the matcher's to enforce: a match it cannot single out is
// kAmbiguous, never a guess.

#include "core/atlas/map_match.h"
#include "core/localmap/local_map.h"

namespace atlas {

class MapMatcher {
 public:
  virtual ~MapMatcher() = default;
  // t (eq. 9): the pose of b's frame in a's frame. `prior` is that pose projected through the
  // graph (III-A), or null when the two frames are not connected.
  virtual MapMatch Match(const LocalMap& a, const LocalMap& b,
                         const UncertainPose* prior) const = 0;
};

}  // namespace atlas
