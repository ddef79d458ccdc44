#include "tools/eval/trajectory_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>

#include "atlas_paths.h"
#include "formats/text_rows.h"

namespace atlas::eval {
namespace {

const std::string kMitLog = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
const std::string kMitRelations =
    std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.relations";

TEST(TrajectoryFilesTest, ParsesTrajectoryWithCommentsAndTabs) {
  const TrajectoryParse p = ParseTrajectory(
      "# header\n\n1134864629.895182\t1.5 -2 3.5\n  # indented comment\n1.25 0 0 -0.5\r\n", "t");
  ASSERT_EQ(p.error, "");
  ASSERT_EQ(p.trajectory.size(), 2u);
  EXPECT_EQ(p.trajectory.poses()[0].stamp, FromSeconds(1.25));  // sorted
  EXPECT_NEAR(ToSeconds(p.trajectory.poses()[1].stamp), 1134864629.895182, 1e-6);
  EXPECT_DOUBLE_EQ(p.trajectory.poses()[1].pose.x, 1.5);
  EXPECT_NEAR(p.trajectory.poses()[1].pose.theta, 3.5 - 2 * std::numbers::pi, 1e-12);
}

TEST(TrajectoryFilesTest, RejectsBadRowsWithLineNumbers) {
  EXPECT_EQ(ParseTrajectory("1 2 3 4\n1 2 x 4\n", "t.tsv").error,
            "t.tsv:2: field 3 is 'x', not a number");
  EXPECT_EQ(ParseTrajectory("# c\n1 2 3\n", "t.tsv").error,
            "t.tsv:2: expected 4 fields (timestamp x y theta), found 3");
  EXPECT_EQ(ParseTrajectory("1 2 3 nan\n", "t.tsv").error,
            "t.tsv:1: field 4 is 'nan', not a number");
  EXPECT_EQ(ParseTrajectory("# only a comment\n", "t.tsv").error, "t.tsv: no poses");
  EXPECT_NE(ParseRelations("1 2 3 4 5 6 7\n", "r").error.find("r:1: expected 8"),
            std::string::npos);
}

TEST(TrajectoryFilesTest, RejectsOutOfRangeValuesAndRepeatedStamps) {
  EXPECT_EQ(
      ParseTrajectory("1 2 3 4\n2 1e308 0 0\n", "t.tsv").error.rfind("t.tsv:2: field 2 is ", 0),
      0u);
  EXPECT_EQ(
      ParseTrajectory("1e300 0 0 0\n", "t.tsv").error.rfind("t.tsv:1: field 1 (a timestamp)", 0),
      0u);
  EXPECT_EQ(ParseTrajectory("1 0 0 1e9\n", "t.tsv").error.rfind("t.tsv:1: field 4 is ", 0), 0u);
  // Unsorted rows are fine (sorted); a repeated stamp names both lines.
  EXPECT_EQ(ParseTrajectory("2 0 0 0\n1 0 0 0\n", "t.tsv").error, "");
  EXPECT_EQ(ParseTrajectory("# h\n1 0 0 0\n2 0 0 0\n1.0000000001 5 0 0\n", "t.tsv").error,
            "t.tsv:4: timestamp 1.000000 repeats line 2 (one pose per stamp: remove one of the two "
            "rows)");
  EXPECT_EQ(ParseRelations("1 2 1e308 0 0 0 0 0\n", "r").error.rfind("r:1: field 3 is ", 0), 0u);
  EXPECT_EQ(ParseRelations("1 2 0 0 0 0 0 1e6\n", "r").error.rfind("r:1: field 8 is ", 0), 0u);
}

TEST(TrajectoryFilesTest, ParsesRelations) {
  const RelationsParse p = ParseRelations(
      "1134864645.90321 1134864646.32420 0.31293 0.02935 0.00000  0.00000 0.00000 0.24198\n", "r");
  ASSERT_EQ(p.error, "");
  ASSERT_EQ(p.relations.size(), 1u);
  EXPECT_NEAR(ToSeconds(p.relations[0].t1), 1134864645.90321, 1e-6);
  EXPECT_DOUBLE_EQ(p.relations[0].delta.x, 0.31293);
  EXPECT_DOUBLE_EQ(p.relations[0].delta.y, 0.02935);
  EXPECT_DOUBLE_EQ(p.relations[0].delta.theta, 0.24198);  // yaw, the 8th field
}

TEST(TrajectoryFilesTest, RelationErrorsOnePerMatchedRelationInOrder) {
  // Three relations; the estimate has poses for the first and last only.
  const std::vector<Relation> relations = {
      {FromSeconds(10.0), FromSeconds(11.0), Pose2{1.0, 0.0, 0.0}},
      {FromSeconds(10.0), FromSeconds(99.0), Pose2{1.0, 0.0, 0.0}},
      {FromSeconds(11.0), FromSeconds(12.0), Pose2{0.0, 0.0, 0.1}}};
  const TimedTrajectory t({{FromSeconds(10.0), {0.0, 0.0, 0.0}},
                           {FromSeconds(11.0), {1.0, 0.3, 0.0}},
                           {FromSeconds(12.0), {1.0, 0.3, 0.0}}});
  const RelationsScore s = ScoreRelations(relations, BetweenPosesOf(t));
  ASSERT_EQ(s.matched, 2);
  const std::string text = FormatRelationErrors(relations, s);
  EXPECT_EQ(text,
            "# atlas-eval relation errors: t1 t2 translation_m rotation_deg\n"
            "10.000000 11.000000 0.300000 0.000000\n"
            "11.000000 12.000000 0.000000 5.729578\n");
  // With how the atlas joined each relation's poses (atlas-eval --atlas): a fifth column.
  const FrameJoin joins[] = {FrameJoin::kChain, FrameJoin::kThroughMapMatch};
  EXPECT_EQ(FormatRelationErrors(relations, s, joins),
            "# atlas-eval relation errors: t1 t2 translation_m rotation_deg join\n"
            "10.000000 11.000000 0.300000 0.000000 chain\n"
            "11.000000 12.000000 0.000000 5.729578 map-match\n");
}

LaserScan ScanAt(double s) {
  LaserScan scan;
  scan.stamp = FromSeconds(s);
  return scan;
}

TEST(TrajectoryFilesTest, OdometryAtScansInterpolates) {
  std::vector<carmen::CarmenEvent> events(5);
  events[0].event = OdometrySample{FromSeconds(1.0), Pose2{0, 0, 3.0}};
  events[1].event = ScanAt(0.5);  // before any odometry: left out
  events[2].event = ScanAt(1.25);
  events[3].event = OdometrySample{FromSeconds(2.0), Pose2{4, 2, -3.0}};
  events[4].event = ScanAt(2.0);
  // (order as in a log: stamps need not be sorted for this function)
  const TimedTrajectory t = OdometryAtScans(events);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t.poses()[0].pose.x, 1.0);
  EXPECT_DOUBLE_EQ(t.poses()[0].pose.y, 0.5);
  // Heading 3.0 -> -3.0 goes the short way through pi: a quarter of 0.283 rad past 3.0.
  EXPECT_NEAR(t.poses()[0].pose.theta, 3.0 + 0.25 * (2 * std::numbers::pi - 6.0), 1e-12);
  EXPECT_DOUBLE_EQ(t.poses()[1].pose.x, 4.0);
}

// End to end: reader, timestamps and metric agree with the published dead-reckoning score
// (datasets README: 1.68 +- 5.29 m, 5.07 +- 8.25 deg).
TEST(TrajectoryFilesTest, MitCsailDeadReckoningMatchesThePublishedScore) {
  if (!std::filesystem::exists(kMitLog) || !std::filesystem::exists(kMitRelations)) {
    GTEST_SKIP() << "dataset absent: " << kMitLog;
  }
  const carmen::CarmenReadResult log = carmen::ReadCarmenLog(kMitLog, {});
  ASSERT_TRUE(log.ok()) << log.error;
  const TimedTrajectory dr = OdometryAtScans(log.log.events);
  EXPECT_EQ(dr.size(), 1988u);
  const formats::TextFile f = formats::ReadTextFile(kMitRelations);
  ASSERT_EQ(f.error, "");
  const RelationsParse rel = ParseRelations(f.text, kMitRelations);
  ASSERT_EQ(rel.error, "");
  ASSERT_EQ(rel.relations.size(), 1172u);
  const RelationsScore s = ScoreRelations(rel.relations, BetweenPosesOf(dr));
  EXPECT_EQ(s.matched, 1172);
  EXPECT_NEAR(s.translation_m.mean, 1.68, 0.005);
  EXPECT_NEAR(s.translation_m.stddev, 5.29, 0.01);
  EXPECT_NEAR(s.rotation_deg.mean, 5.07, 0.01);
  EXPECT_NEAR(s.rotation_deg.stddev, 8.25, 0.015);
}

}  // namespace
}  // namespace atlas::eval
