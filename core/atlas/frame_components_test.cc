#include "core/atlas/frame_components.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

TEST(FrameComponents, JoinsAndCounts) {
  FrameComponents c;
  for (int i = 0; i < 5; ++i) c.AddFrame();
  EXPECT_FALSE(c.Connected(0, 1));
  c.Join(0, 1);
  c.Join(3, 4);
  EXPECT_TRUE(c.Connected(1, 0));
  EXPECT_TRUE(c.Connected(4, 3));
  EXPECT_FALSE(c.Connected(1, 3));
  EXPECT_EQ(c.Size(0), 2);
  EXPECT_EQ(c.Size(2), 1);
  c.Join(1, 4);
  c.Join(0, 3);  // already joined: no change
  EXPECT_TRUE(c.Connected(0, 4));
  EXPECT_EQ(c.Size(3), 4);
  EXPECT_FALSE(c.Connected(2, 0));
}

TEST(FrameComponents, RebuildFromGraph) {
  AtlasGraph g;
  for (int i = 0; i < 4; ++i) g.AddFrame(nullptr);
  ASSERT_EQ(g.AddEdge(0, 1, UncertainPose{}, EdgeKind::kGenesis), AddEdgeResult::kAdded);
  ASSERT_EQ(g.AddEdge(2, 3, UncertainPose{}, EdgeKind::kMapMatch), AddEdgeResult::kAdded);
  FrameComponents c;
  c.Rebuild(g);
  EXPECT_EQ(c.Count(), 4);
  EXPECT_TRUE(c.Connected(0, 1));
  EXPECT_TRUE(c.Connected(2, 3));
  EXPECT_FALSE(c.Connected(1, 2));
  EXPECT_EQ(c.Size(1), 2);
}

}  // namespace
}  // namespace atlas
