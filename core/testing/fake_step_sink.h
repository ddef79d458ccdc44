#pragma once
// For the StepLoop and replay tests: a StepSink that records what the loop reports, and sensor
// items at a stamp.

#include <vector>

#include "core/mapper/step_loop.h"
#include "core/testing/atlas_test_world.h"

namespace atlas {

struct RecordedPose {
  Time stamp;
  DominantOutput pose;
  PoseSource source;
};

class FakeStepSink : public StepSink {
 public:
  void OnPose(Time stamp, const DominantOutput& pose, PoseSource source) override {
    poses.push_back({stamp, pose, source});
  }
  void OnStep(Time, const Atlas& atlas) override { last_steps = atlas.StepCount(); }
  std::vector<RecordedPose> poses;
  int64_t last_steps = 0;
};

// TestScan() (core/testing/atlas_test_world.h) at `t` seconds.
inline LaserScan ScanAt(double t) {
  LaserScan s = TestScan();
  s.stamp = FromSeconds(t);
  return s;
}

// A reading of one return at 1 m from transducer 0, at `t` seconds.
inline SonarReading SonarAt(double t) {
  SonarReading r;
  r.stamp = FromSeconds(t);
  r.returns.push_back(SonarReturn{0, 1.0f});
  return r;
}

}  // namespace atlas
