#pragma once
// A simulator world with repetitive structure, for Condition 2 (paper, Sections II-A and IV):
// one rectangular corridor loop whose outer wall opens into an alcove every `period` metres,
// all alcoves alike. A local map of a few metres of this corridor matches the map of any other
// stretch shifted by a whole number of periods, so a loop closure is unique only when the
// prior (the Dijkstra projection around the loop) is tighter than the period: with sonar, whose
// heading correction is weak, the prior around a long loop is not, and the atlas must refuse
// the ambiguous match.
//
// Layout (metres): the outer wall is the rectangle [0, length] x [0, width]; the inner wall the
// rectangle inset by corridor_width. Alcoves (alcove_width along the wall, alcove_depth deep)
// are cut into the outer wall of every side long enough, one per period, keeping
// corner_clearance from the corners. The route graph is the corridor centreline: a ring of
// corridor nodes at most node_spacing apart, so a route (sim PlanRoute, which never
// turns straight back) drives round the loop, always the same way, whatever the seed.

#include <string>

#include "sim/world.h"

namespace atlas::sonar_eval {

struct AlcoveLoopOptions {
  double length = 36.0;
  double width = 14.0;
  double corridor_width = 2.4;
  double period = 4.0;
  double alcove_width = 1.5;
  double alcove_depth = 1.0;
  double corner_clearance = 3.0;  // from the inner corner to the first alcove
  double node_spacing = 4.0;

  std::string Validate() const;  // empty when valid
};

// `options` must be valid.
sim::World AlcoveLoopWorld(const AlcoveLoopOptions& options);

}  // namespace atlas::sonar_eval
