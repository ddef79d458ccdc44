#include "daemon/atlasd/lcm_sink.h"

#include "daemon/atlasd/live_timing.h"

namespace atlas {

LcmSink::LcmSink(AtlasPublisher* publisher, const LcmOptions& o)
    : publisher_(publisher), reference_(o.reference_frame) {
  SetPeriods(o);
}

void LcmSink::SetPeriods(const LcmOptions& o) {
  graph_period_ = SecondsToDuration(o.graph_period_s);
  map_period_ = SecondsToDuration(o.local_map_period_s);
}

void LcmSink::OnPose(Time stamp, const DominantOutput& pose, PoseSource) {
  publisher_->Pose(stamp, pose);
  publisher_->ReferencePose(
      ToReferencePoseMessage(stamp, pose, reference_.reference(), reference_.Place(pose)));
}

void LcmSink::OnStep(Time stamp, const Atlas& atlas) {
  const Time now = Now();
  const bool graph_due = Due(now, last_graph_, graph_period_);
  reference_.Update(atlas, graph_due);
  if (graph_due) {
    last_graph_ = now;
    publisher_->Graph(stamp, atlas);
    publisher_->Hypotheses(stamp, atlas);
  }
  if (Due(now, last_map_, map_period_)) {
    last_map_ = now;
    publisher_->LocalMap(stamp, atlas);
  }
}

}  // namespace atlas
