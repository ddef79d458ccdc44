#include "daemon/atlasd/lcm_sink.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include "core/atlas/dijkstra_projection.h"
#include "core/testing/atlas_test_world.h"

namespace atlas {
namespace {

// ATLAS_POSE and ATLAS_REFERENCE_POSE as the sink publishes them over memq://.
struct Received {
  std::vector<atlasd::pose_t> poses;
  std::vector<atlasd::reference_pose_t> reference;
  void OnPose(const lcm::ReceiveBuffer*, const std::string&, const atlasd::pose_t* m) {
    poses.push_back(*m);
  }
  void OnReference(const lcm::ReceiveBuffer*, const std::string&,
                   const atlasd::reference_pose_t* m) {
    reference.push_back(*m);
  }
};

class LcmSinkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(lcm_.good());
    lcm_.subscribe(options_.channels.pose, &Received::OnPose, &received_);
    lcm_.subscribe(options_.channels.reference_pose, &Received::OnReference, &received_);
  }
  // One step as StepLoop makes it: the pose after Localize(), the step after MaintainGraph().
  void Step(LcmSink* sink, Atlas* atlas, double t) {
    atlas->Localize(Pose2{0.5, 0, 0}, TestScan());
    sink->OnPose(FromSeconds(t), atlas->Dominant(), PoseSource::kScan);
    atlas->MaintainGraph();
    sink->OnStep(FromSeconds(t), *atlas);
    while (lcm_.handleTimeout(0) > 0) {
    }
  }

  lcm::LCM lcm_{"memq://"};
  LcmOptions options_;
  Received received_;
};

TEST_F(LcmSinkTest, ReferencePoseEqualsThePoseInTheReferenceFrame) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), nullptr);
  AtlasPublisher publisher(&lcm_, options_.channels, EpochClock());
  options_.graph_period_s = 0;  // re-projected after every step: compared with a fresh projection
  LcmSink sink(&publisher, options_);  // reference_frame 0
  Step(&sink, &atlas, 1.0);            // the first step: no projection kept before its pose
  ASSERT_EQ(received_.reference.size(), 1u);
  EXPECT_FALSE(received_.reference[0].placed);
  int in_frame_zero = 0;
  for (int i = 0; i < 40; ++i) {
    Step(&sink, &atlas, 2.0 + i);
    ASSERT_EQ(received_.poses.size(), received_.reference.size());
    const atlasd::pose_t& p = received_.poses.back();
    const atlasd::reference_pose_t& r = received_.reference.back();
    EXPECT_EQ(r.utime, p.utime);
    EXPECT_EQ(r.frame_id, p.frame_id);
    EXPECT_EQ(r.reference_frame_id, 0);
    if (p.frame_id != 0) continue;
    ++in_frame_zero;
    // The dominant frame is the reference frame: the pose and covariance of ATLAS_POSE.
    ASSERT_TRUE(r.placed);
    EXPECT_EQ(r.hops, 0);
    EXPECT_EQ(r.x, p.x);
    EXPECT_EQ(r.y, p.y);
    EXPECT_EQ(r.theta, p.theta);
    for (int k = 0; k < 9; ++k) {
      EXPECT_EQ(r.covariance[k], p.covariance[k]);
      EXPECT_EQ(r.frame_covariance[k], 0.0);
    }
    EXPECT_EQ(r.q, p.q);
  }
  EXPECT_GT(in_frame_zero, 0);
  // The robot left frame 0: the last pose is carried along the projection's path.
  const atlasd::pose_t& p = received_.poses.back();
  const atlasd::reference_pose_t& r = received_.reference.back();
  ASSERT_GT(p.frame_id, 0);
  ASSERT_TRUE(r.placed);
  const Projection projection = DijkstraProjection(atlas.Graph(), 0);
  const ProjectedFrame* f = projection.Find(p.frame_id);
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(r.hops, f->hops);
  EXPECT_GT(r.hops, 0);
  const Pose2 expected = Compose(f->pose.mean, Pose2{p.x, p.y, p.theta});
  EXPECT_NEAR(r.x, expected.x, 1e-9);
  EXPECT_NEAR(r.y, expected.y, 1e-9);
  EXPECT_NEAR(r.theta, expected.theta, 1e-9);
  EXPECT_NEAR(r.frame_x, f->pose.mean.x, 1e-9);
  // Composed with the frame's uncertainty, the pose is less certain than in its own frame.
  EXPECT_GT(r.covariance[0] + r.covariance[4], p.covariance[0] + p.covariance[4]);
}

TEST_F(LcmSinkTest, AnotherReferenceFrameAndOneTheAtlasDoesNotHave) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), nullptr);
  for (int i = 0; i < 40; ++i) atlas.Step(Pose2{0.5, 0, 0}, TestScan());
  const DominantOutput d = atlas.Dominant();
  ASSERT_TRUE(d.valid);
  ASSERT_GT(d.frame, 0);
  AtlasPublisher publisher(&lcm_, options_.channels, EpochClock());
  LcmOptions anchored = options_;
  anchored.reference_frame = d.frame;
  LcmSink sink(&publisher, anchored);
  sink.OnPose(FromSeconds(2.0), atlas.Dominant(), PoseSource::kScan);  // nothing projected yet
  sink.OnStep(FromSeconds(2.0), atlas);
  sink.OnPose(FromSeconds(3.0), atlas.Dominant(), PoseSource::kOdometryOnly);
  while (lcm_.handleTimeout(0) > 0) {
  }
  ASSERT_EQ(received_.reference.size(), 2u);
  EXPECT_FALSE(received_.reference[0].placed);
  const atlasd::reference_pose_t& r = received_.reference[1];
  ASSERT_TRUE(r.placed);
  EXPECT_EQ(r.reference_frame_id, d.frame);
  EXPECT_EQ(r.x, received_.poses[1].x);
  EXPECT_EQ(r.hops, 0);

  LcmOptions beyond = options_;
  beyond.reference_frame = atlas.Graph().FrameCount() + 5;
  LcmSink far(&publisher, beyond);
  far.OnStep(FromSeconds(4.0), atlas);
  far.OnPose(FromSeconds(5.0), atlas.Dominant(), PoseSource::kScan);
  while (lcm_.handleTimeout(0) > 0) {
  }
  ASSERT_EQ(received_.reference.size(), 3u);
  EXPECT_FALSE(received_.reference[2].placed);
  EXPECT_EQ(received_.reference[2].x, 0.0);
  EXPECT_EQ(received_.reference[2].frame_id, d.frame);
}

}  // namespace
}  // namespace atlas
