#pragma once
// A scripted world for Atlas tests and benchmarks (not a fake of a class: a test fixture).
// Every fake map explains the observations made within `radius` of its own origin, and only as
// far as it has features (2 observations per feature), so a fresh map starts poor and a known
// map is good at once. Maps are tagged with their creation order, which equals the frame id
// when the atlas is the only user of the factory.

#include <memory>

#include "core/atlas/atlas.h"
#include "core/testing/fake_local_map.h"

namespace atlas {

// The atlas the scripted worlds are written for: SonarAtlasOptions (no points, no return band,
// the paper's Genesis edge) with generic map-matching (MapMatchOptions{}), 4 hypotheses, a
// probation of 8 scans, q's sigmas 0.5 m, 0.5 m, 0.2 rad and one map-matching candidate per
// step.
inline AtlasOptions BaselineAtlasOptions() {
  AtlasOptions o = SonarAtlasOptions();
  o.match = MapMatchOptions{};
  o.max_hypotheses = 4;
  o.lifecycle.probation_scans = 8;
  o.quality.sigma_x = 0.5;
  o.quality.sigma_y = 0.5;
  o.quality.sigma_theta = 0.2;
  o.match_candidates_per_step = 1;
  return o;
}

struct TestWorld {
  double radius = 3.0;
  int capacity = 6;
  int image_padding = 0;  // FakeLocalMapOptions::image_padding
  int observations = 10;
  std::shared_ptr<FakeWorldScript> script = std::make_shared<FakeWorldScript>();
  std::shared_ptr<int> next_tag = std::make_shared<int>(0);

  TestWorld() { Install(); }
  void Install() {
    const double r = radius;
    script->observations = observations;
    script->matched = [r](int, const Pose2& p, int obs, int complexity) {
      return std::hypot(p.x, p.y) < r ? std::min(obs, 2 * complexity) : 0;
    };
  }
  Atlas::MapFactory Factory() const {
    FakeLocalMapOptions o;
    o.capacity = capacity;
    o.image_padding = image_padding;
    auto script_copy = std::shared_ptr<const FakeWorldScript>(script);
    auto tag = next_tag;
    return [o, script_copy, tag]() {
      return std::make_unique<FakeLocalMap>(o, script_copy, (*tag)++);
    };
  }
  // The scripted world's atlas: BaselineAtlasOptions with alpha 0.3 and edge refinement every
  // 3 steps.
  static AtlasOptions Options() {
    AtlasOptions o = BaselineAtlasOptions();
    o.quality.alpha = 0.3;
    o.refine_interval_steps = 3;
    return o;
  }
};

inline LaserScan TestScan() {
  LaserScan s;
  s.ranges.assign(10, 1.0f);
  return s;
}

}  // namespace atlas
