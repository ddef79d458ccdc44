#include "core/localmap/scan_observation.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/localmap/line_extraction.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/world.h"

namespace atlas {
namespace {

// Field by field and bit for bit: the observation's lines must be the extraction's own.
void ExpectSameLines(const std::vector<ObservedLine>& got, const std::vector<ObservedLine>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].rho, want[i].rho);
    EXPECT_EQ(got[i].alpha, want[i].alpha);
    EXPECT_EQ(got[i].cov, want[i].cov);
    EXPECT_EQ(got[i].endpoint_a, want[i].endpoint_a);
    EXPECT_EQ(got[i].endpoint_b, want[i].endpoint_b);
    EXPECT_EQ(got[i].num_points, want[i].num_points);
    EXPECT_EQ(got[i].first_beam, want[i].first_beam);
    EXPECT_EQ(got[i].last_beam, want[i].last_beam);
  }
}

LaserScan RoomScan() {
  const std::vector<sim::Wall> walls = {{Vec2(-3.0, -2.0), Vec2(4.0, -2.0)},
                                        {Vec2(4.0, -2.0), Vec2(4.0, 3.0)},
                                        {Vec2(4.0, 3.0), Vec2(-3.0, 3.0)}};
  FakeWallScanner scanner(walls, FakeLaserOptions(), 3);
  LaserScan scan = scanner.Scan(Pose2{0.5, 0.2, 0.3});
  scan.sensor_pose = Pose2{0.1, -0.05, 0.02};  // robot frame differs from the sensor frame
  return scan;
}

TEST(ScanObservationTest, LinesAreTheRobotFrameExtraction) {
  const LaserScan scan = RoomScan();
  const LineExtractionOptions options = FakeWallMapOptions().extraction;
  const ScanObservation obs(scan);
  const std::vector<ObservedLine> want = ExtractRobotFrameLines(scan, options);
  ASSERT_GE(want.size(), 3u);
  ExpectSameLines(obs.RobotFrameLines(options), want);
  // A second request with equal options is served from the same lines.
  const std::vector<ObservedLine>* first = &obs.RobotFrameLines(options);
  EXPECT_EQ(&obs.RobotFrameLines(options), first);
  ExpectSameLines(obs.RobotFrameLines(options), want);
  EXPECT_EQ(obs.scan().ranges, scan.ranges);
}

TEST(ScanObservationTest, OtherOptionsExtractAgain) {
  const LaserScan scan = RoomScan();
  const LineExtractionOptions loose = FakeWallMapOptions().extraction;
  LineExtractionOptions strict = loose;
  strict.min_length = 6.0;  // only the long walls
  const ScanObservation obs(scan);
  const std::vector<ObservedLine> want_loose = ExtractRobotFrameLines(scan, loose);
  const std::vector<ObservedLine> want_strict = ExtractRobotFrameLines(scan, strict);
  ASSERT_NE(want_loose.size(), want_strict.size());
  ExpectSameLines(obs.RobotFrameLines(loose), want_loose);
  ExpectSameLines(obs.RobotFrameLines(strict), want_strict);
  ExpectSameLines(obs.RobotFrameLines(loose), want_loose);
}

TEST(ScanObservationTest, CopiesCarryTheLines) {
  const LaserScan scan = RoomScan();
  const LineExtractionOptions options = FakeWallMapOptions().extraction;
  ScanObservation obs(scan);
  const std::vector<ObservedLine> want = obs.RobotFrameLines(options);
  const ScanObservation copy = obs;
  obs = ScanObservation();
  ExpectSameLines(copy.RobotFrameLines(options), want);
  EXPECT_TRUE(obs.RobotFrameLines(options).empty());  // no beams, no lines
}

}  // namespace
}  // namespace atlas
