#pragma once
// The live loop's StepSink: the pose at every step (and while dead reckoning), the graph and
// hypotheses every lcm.graph_period_s and the local map every lcm.local_map_period_s, by the
// loop thread's clock (docs/lcm.md). Beside every pose, the pose in the reference frame
// (lcm.reference_frame; reference_placement.h), re-projected every lcm.graph_period_s.

#include "core/atlas/atlas.h"
#include "core/mapper/step_loop.h"
#include "daemon/lcm_out/atlas_publisher.h"
#include "daemon/lcm_out/reference_placement.h"
#include "formats/config/daemon_options.h"

namespace atlas {

class LcmSink final : public StepSink {
 public:
  // `publisher` outlives the sink.
  LcmSink(AtlasPublisher* publisher, const LcmOptions& o);
  // A reload's new periods, from the next step on.
  void SetPeriods(const LcmOptions& o);

  void OnPose(Time stamp, const DominantOutput& pose, PoseSource source) override;
  void OnStep(Time stamp, const Atlas& atlas) override;

 private:
  AtlasPublisher* publisher_;
  ReferencePlacement reference_;
  Duration graph_period_{}, map_period_{};
  Time last_graph_{}, last_map_{};
};

}  // namespace atlas
