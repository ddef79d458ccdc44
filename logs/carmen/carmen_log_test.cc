#include "logs/carmen/carmen_log.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "atlas_paths.h"

namespace atlas::carmen {
namespace {

const std::string kShared = ATLAS_SHARED_DIR;
const std::string kMit = kShared + "/datasets/mit-csail/mit-csail.clf.gz";
const std::string kIntel = kShared + "/datasets/corrected/intel-corrected.log.gz";

// The first `max_lines` lines of a (gzip or plain) file, or empty when it is absent.
std::vector<std::string> HeadLines(const std::string& path, size_t max_lines) {
  std::vector<std::string> out;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) return out;
  std::string line;
  char buf[4096];
  while (out.size() < max_lines && gzgets(f, buf, sizeof buf) != nullptr) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      out.push_back(line);
      line.clear();
    }
  }
  gzclose(f);
  return out;
}

class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("atlas_carmen_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

std::string Join(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

void WritePlain(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

void WriteGzip(const std::string& path, const std::string& text) {
  gzFile f = gzopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(gzwrite(f, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  gzclose(f);
}

// Replaces the `field`-th whitespace-separated word (0-based) of `line`.
std::string ReplaceField(const std::string& line, int field, const std::string& with) {
  std::istringstream in(line);
  std::string w, out;
  for (int i = 0; in >> w; ++i) out += (out.empty() ? "" : " ") + (i == field ? with : w);
  return out;
}

CarmenLog ReadOk(const std::string& path, const CarmenLogOptions& o = {}) {
  CarmenReadResult r = ReadCarmenLog(path, o);
  EXPECT_TRUE(r.ok()) << r.error;
  return std::move(r.log);
}

int CountOdometry(const CarmenLog& log) {
  int n = 0;
  for (const CarmenEvent& e : log.events) n += std::holds_alternative<OdometrySample>(e.event);
  return n;
}

TEST(CarmenLogTest, BuilderOrdersEventsAndKeepsLines) {
  CarmenLogBuilder b(CarmenLogOptions{}, "mem");
  ASSERT_TRUE(b.AddLine(1, "# header"));
  ASSERT_TRUE(b.AddLine(2, "ODOM 1 0 0 0 0 0 10.5 h 0"));
  ASSERT_TRUE(b.AddLine(3, "FLASER 2 1.0 90 0 0 0 5 5 0 10.7 h 0"));
  ASSERT_TRUE(b.AddLine(4, "ODOM 2 0 0 0 0 0 10.2 h 0"));  // stamped before line 2
  ASSERT_TRUE(b.AddLine(5, "NEFF 30"));
  const CarmenLog log = b.Finish();
  ASSERT_EQ(log.events.size(), 3u);
  // ODOM lines exist, so the FLASER odometry fields are not used.
  EXPECT_EQ(log.events[0].line, 4);
  EXPECT_EQ(log.events[1].line, 2);
  EXPECT_EQ(log.events[2].line, 3);
  EXPECT_EQ(log.out_of_order_lines, 1);
  EXPECT_EQ(log.odometry_events, 2);
  EXPECT_EQ(log.lines_by_message.at("NEFF"), 1);
  EXPECT_EQ(log.comment_or_blank_lines, 1);
  const auto& scan = std::get<LaserScan>(log.events[2].event);
  EXPECT_EQ(scan.stamp, FromSeconds(10.7));
  ASSERT_EQ(scan.ranges.size(), 2u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.0f);
  EXPECT_FALSE(IsReturn(scan.ranges[1]));  // 90 m >= CARMEN's 80 m FLASER maximum
  EXPECT_EQ(log.no_return_beams, 1);
  EXPECT_FLOAT_EQ(log.largest_range, 90.0f);
  EXPECT_EQ(log.events[2].odometry_pose->x, 5.0);
}

TEST(CarmenLogTest, OdometryFromLaserLinesWhenNoOdomLines) {
  CarmenLogBuilder b(CarmenLogOptions{}, "mem");
  ASSERT_TRUE(b.AddLine(1, "FLASER 1 1.0 0.5 0 0.1 0 0 0 3.0 h 0"));
  ASSERT_TRUE(b.AddLine(2, "FLASER 1 1.0 1.5 0 0.1 1 0 0 4.0 h 0"));
  const CarmenLog log = b.Finish();
  ASSERT_EQ(log.events.size(), 4u);
  const auto& o = std::get<OdometrySample>(log.events[2].event);
  EXPECT_EQ(o.stamp, FromSeconds(4.0));
  EXPECT_DOUBLE_EQ(o.pose.x, 1.0);
  EXPECT_TRUE(std::holds_alternative<LaserScan>(log.events[3].event));  // odometry first
  // sensor pose = laser pose seen from the odometry pose: 0.5 m ahead, rotated 0.1 rad.
  const auto& scan = std::get<LaserScan>(log.events[3].event);
  EXPECT_NEAR(scan.sensor_pose.x, 0.5, 1e-12);
  EXPECT_NEAR(scan.sensor_pose.theta, 0.1, 1e-12);
}

TEST(CarmenLogTest, LineOrderClockAndReferenceTrajectory) {
  CarmenLogOptions o = CarmenLogOptions::ForCorrectedLog();
  o.line_period_s = 0.5;
  CarmenLogBuilder b(o, "mem");
  ASSERT_TRUE(b.AddLine(1, "ODOM 1 0 0 0 0 0 1.13486e+09 h 0"));
  ASSERT_TRUE(b.AddLine(2, "NEFF 27.6 0 h 0"));
  ASSERT_TRUE(b.AddLine(3, "FLASER 1 1.0 2 0 7 2 0 7 1.13486e+09 h 0"));
  ASSERT_TRUE(b.AddLine(4, "ODOM 3 0 0 0 0 0 0 h 0"));
  const CarmenLog log = b.Finish();
  EXPECT_EQ(log.out_of_order_lines, 0);
  ASSERT_EQ(log.events.size(), 1u);  // the scan; odometry is not taken from corrected poses
  EXPECT_EQ(StampOf(log.events[0].event), FromSeconds(1.5));
  ASSERT_EQ(log.reference.size(), 3u);
  EXPECT_EQ(log.reference[0].truth.stamp, FromSeconds(0.5));
  EXPECT_EQ(log.reference[1].truth.stamp, FromSeconds(1.5));
  EXPECT_TRUE(log.reference[1].at_laser);
  EXPECT_NEAR(log.reference[1].truth.pose.theta, 7 - 2 * std::numbers::pi, 1e-12);  // wrapped
  EXPECT_DOUBLE_EQ(log.reference[2].truth.pose.x, 3.0);
}

TEST(CarmenLogTest, MaxRangeOptionMapsAClampToNoReturn) {
  CarmenLogOptions o;
  o.max_range_m = 50.0;
  CarmenLogBuilder b(o, "mem");
  ASSERT_TRUE(b.AddLine(1, "FLASER 3 49.9 50 60 0 0 0 0 0 0 1 h 0"));
  const CarmenLog log = b.Finish();
  const auto& scan = std::get<LaserScan>(log.events[1].event);
  EXPECT_TRUE(IsReturn(scan.ranges[0]));
  EXPECT_FALSE(IsReturn(scan.ranges[1]));
  EXPECT_FALSE(IsReturn(scan.ranges[2]));
  EXPECT_EQ(scan.max_range, 50.0f);
}

// A FLASER line of `n` beams reading `value` and one reading 10 m.
std::string ClampedLine(int n, double value) {
  std::string line = "FLASER " + std::to_string(n + 1);
  for (int i = 0; i < n; ++i) line += " " + std::to_string(value);
  return line + " 10 0 0 0 0 0 0 1 h 0";
}

TEST(CarmenLogTest, AClampKeptAsReturnsIsNoted) {
  CarmenLogBuilder b(CarmenLogOptions{}, "mem");
  ASSERT_TRUE(b.AddLine(1, ClampedLine(static_cast<int>(kClampBeams), 50.0)));
  const CarmenLog log = b.Finish();
  EXPECT_EQ(log.largest_range_returns, kClampBeams);
  const std::string note = ClampNote(log);
  EXPECT_NE(note.find("100 beams read 50.00 m"), std::string::npos) << note;
  EXPECT_NE(note.find("--log-max-range 50"), std::string::npos) << note;

  CarmenLogOptions clamp;
  clamp.max_range_m = 50.0;
  CarmenLogBuilder read_as_no_return(clamp, "mem");
  ASSERT_TRUE(read_as_no_return.AddLine(1, ClampedLine(static_cast<int>(kClampBeams), 50.0)));
  EXPECT_EQ(ClampNote(read_as_no_return.Finish()), "");

  CarmenLogBuilder fewer(CarmenLogOptions{}, "mem");
  ASSERT_TRUE(fewer.AddLine(1, ClampedLine(static_cast<int>(kClampBeams) - 1, 50.0)));
  EXPECT_EQ(ClampNote(fewer.Finish()), "");
}

TEST(CarmenLogTest, CannotOpenIsReported) {
  const CarmenReadResult r = ReadCarmenLog("/nonexistent/dir/x.log.gz", {});
  EXPECT_EQ(r.status, ReadStatus::kCannotOpen);
  EXPECT_NE(r.error.find("/nonexistent/dir/x.log.gz"), std::string::npos);
}

TEST(CarmenLogTest, TruncatedGzipIsAReadError) {
  std::vector<std::string> lines = HeadLines(kMit, 200);
  if (lines.empty()) GTEST_SKIP() << "dataset absent: " << kMit;
  TempDir dir;
  WriteGzip(dir.File("full.gz"), Join(lines));
  std::ifstream in(dir.File("full.gz"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  WritePlain(dir.File("cut.gz"), bytes.substr(0, bytes.size() / 2));
  const CarmenReadResult r = ReadCarmenLog(dir.File("cut.gz"), {});
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.error.find("cut.gz"), std::string::npos) << r.error;
}

// Known content: 300 ODOM lines, each with 9 fields after the message name.
std::string KnownOdomLines() {
  std::string text;
  for (int i = 0; i < 300; ++i) {
    const std::string t = std::to_string(1.0 + 0.05 * i);
    text += "ODOM " + std::to_string(0.01 * i) + " 0.5 0.1 0.2 0 0 " + t + " host " + t + "\n";
  }
  return text;
}

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(CarmenLogTest, TruncatedGzipIsReportedAsTruncatedNotAsABadLine) {
  TempDir dir;
  const std::string text = KnownOdomLines();
  WriteGzip(dir.File("full.gz"), text);
  ASSERT_TRUE(ReadCarmenLog(dir.File("full.gz"), {}).ok());
  const std::string bytes = FileBytes(dir.File("full.gz"));
  // Cut in the middle of the deflate data (the last line read is then a piece of a line), and
  // cut only the 8-byte trailer (every line is whole, the stream has no end).
  for (const size_t keep : {bytes.size() / 2, bytes.size() - 8}) {
    WritePlain(dir.File("cut.gz"), bytes.substr(0, keep));
    for (const bool skip : {false, true}) {
      CarmenLogOptions o;
      o.skip_bad_lines = skip;
      const CarmenReadResult r = ReadCarmenLog(dir.File("cut.gz"), o);
      EXPECT_EQ(r.status, ReadStatus::kReadError) << keep << " " << r.error;
      EXPECT_NE(r.error.find(dir.File("cut.gz") + " is truncated (the gzip stream ends early) "
                                                  "after line "),
                std::string::npos)
          << r.error;
      EXPECT_EQ(r.error.find("fields"), std::string::npos) << r.error;
    }
  }
  WritePlain(dir.File("cut.gz"), bytes.substr(0, bytes.size() - 8));
  EXPECT_NE(ReadCarmenLog(dir.File("cut.gz"), {}).error.find("after line 300"), std::string::npos);
}

TEST(CarmenLogTest, GzipCrcErrorIsReportedAsSuch) {
  TempDir dir;
  WriteGzip(dir.File("full.gz"), KnownOdomLines());
  std::string bytes = FileBytes(dir.File("full.gz"));
  bytes[bytes.size() - 8] = static_cast<char>(bytes[bytes.size() - 8] ^ 0x55);  // the CRC-32
  WritePlain(dir.File("crc.gz"), bytes);
  const CarmenReadResult r = ReadCarmenLog(dir.File("crc.gz"), {});
  EXPECT_EQ(r.status, ReadStatus::kReadError);
  EXPECT_EQ(r.error, dir.File("crc.gz") +
                         ": gzip CRC error (incorrect data check): the file is corrupt; copy or "
                         "download it again");
}

TEST(CarmenLogTest, GzipAndPlainReadTheSame) {
  const std::vector<std::string> lines = HeadLines(kIntel, 400);
  if (lines.empty()) GTEST_SKIP() << "dataset absent: " << kIntel;
  TempDir dir;
  const std::string text = Join(lines);
  WritePlain(dir.File("a.log"), text);
  WriteGzip(dir.File("a.log.gz"), text);
  const CarmenLog plain = ReadOk(dir.File("a.log"));
  const CarmenLog gz = ReadOk(dir.File("a.log.gz"));
  EXPECT_EQ(plain.lines, 400);
  EXPECT_EQ(gz.lines, 400);
  ASSERT_EQ(plain.events.size(), gz.events.size());
  ASSERT_GT(plain.laser_events, 5);
  for (size_t i = 0; i < plain.events.size(); ++i) {
    EXPECT_EQ(plain.events[i].line, gz.events[i].line);
    EXPECT_EQ(StampOf(plain.events[i].event), StampOf(gz.events[i].event));
  }
  // A last line without '\n' is read too.
  WritePlain(dir.File("b.log"), text.substr(0, text.size() - 1));
  EXPECT_EQ(ReadOk(dir.File("b.log")).events.size(), plain.events.size());
}

TEST(CarmenLogTest, CorruptedCopyIsRejectedWithItsLineNumber) {
  std::vector<std::string> lines = HeadLines(kMit, 60);
  if (lines.empty()) GTEST_SKIP() << "dataset absent: " << kMit;
  ASSERT_EQ(lines[40].rfind("FLASER", 0), 0u);
  TempDir dir;
  const std::string good_path = dir.File("good.clf.gz");
  WriteGzip(good_path, Join(lines));
  const CarmenLog good = ReadOk(good_path);

  // Line 41: a range that is not a number.
  lines[40] = ReplaceField(lines[40], 100, "1.2x5");
  // Line 53: cut short in the middle of the ranges.
  lines[52] = lines[52].substr(0, lines[52].size() / 2);
  const std::string bad_path = dir.File("bad.clf.gz");
  WriteGzip(bad_path, Join(lines));

  const CarmenReadResult r = ReadCarmenLog(bad_path, {});
  EXPECT_EQ(r.status, ReadStatus::kBadLine);
  EXPECT_NE(r.error.find("bad.clf.gz:41:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("'1.2x5'"), std::string::npos) << r.error;

  CarmenLogOptions skip;
  skip.skip_bad_lines = true;
  const CarmenLog skipped = ReadOk(bad_path, skip);
  EXPECT_EQ(skipped.bad_lines, 2);
  ASSERT_EQ(skipped.bad_line_reasons.size(), 2u);
  EXPECT_NE(skipped.bad_line_reasons[1].find(":53:"), std::string::npos);
  EXPECT_EQ(skipped.laser_events, good.laser_events - 2);
  EXPECT_EQ(skipped.odometry_events, good.odometry_events - 2);
}

TEST(CarmenLogTest, OverlongLineIsMalformed) {
  TempDir dir;
  CarmenLogOptions o;
  o.max_line_bytes = 100;
  o.skip_bad_lines = true;
  WritePlain(dir.File("long.log"), "ODOM 1 0 0 0 0 0 1 h 0\nFLASER 200" + std::string(300, ' ') +
                                       "1\nODOM 2 0 0 0 0 0 2 h 0\n");
  const CarmenLog log = ReadOk(dir.File("long.log"), o);
  EXPECT_EQ(log.bad_lines, 1);
  EXPECT_EQ(log.odometry_events, 2);
  EXPECT_NE(log.bad_line_reasons[0].find(":2:"), std::string::npos);
}

// Counts taken with zcat | awk '{print $1}' | sort | uniq -c.
struct DatasetExpectation {
  const char* file;
  int flaser, odom, neff, beams_per_scan;
};

TEST(CarmenLogTest, ReadsEveryDataset) {
  const DatasetExpectation kFiles[] = {
      {"mit-csail/mit-csail.clf.gz", 1988, 0, 0, 361},
      {"corrected/aces-corrected.log.gz", 440, 7814, 440, 180},
      {"corrected/csail-corrected.log.gz", 406, 2394, 406, 361},
      {"corrected/freiburg-079-corrected.log.gz", 4791, 9725, 4791, 360},
      {"corrected/freiburg-101-corrected.log.gz", 292, 4569, 292, 360},
      {"corrected/intel-corrected.log.gz", 910, 14541, 910, 180},
      {"corrected/seattle-corrected.log.gz", 241, 19311, 241, 361},
  };
  int read = 0;
  for (const DatasetExpectation& d : kFiles) {
    const std::string path = kShared + "/datasets/" + d.file;
    if (!std::filesystem::exists(path)) continue;
    ++read;
    SCOPED_TRACE(d.file);
    const bool corrected = d.odom > 0;
    const CarmenLog log =
        ReadOk(path, corrected ? CarmenLogOptions::ForCorrectedLog() : CarmenLogOptions{});
    EXPECT_EQ(log.laser_events, d.flaser);
    EXPECT_EQ(log.bad_lines, 0);
    EXPECT_EQ(log.out_of_order_lines, 0);
    if (d.neff > 0) {
      EXPECT_EQ(log.lines_by_message.at("NEFF"), d.neff);
    }
    if (corrected) {
      EXPECT_EQ(static_cast<int>(log.reference.size()), d.flaser + d.odom);
      EXPECT_EQ(CountOdometry(log), 0);
    } else {
      EXPECT_EQ(CountOdometry(log), d.flaser);  // from the FLASER odometry fields
    }
    for (const CarmenEvent& e : log.events) {
      if (const auto* s = std::get_if<LaserScan>(&e.event)) {
        ASSERT_EQ(static_cast<int>(s->ranges.size()), d.beams_per_scan);
        ASSERT_NEAR(s->angle_min, -std::numbers::pi / 2, 1e-6);
      }
    }
  }
  if (read == 0) GTEST_SKIP() << "datasets absent under " << kShared;
}

TEST(CarmenLogTest, MitCsailTimestampsAndNoReturns) {
  if (!std::filesystem::exists(kMit)) GTEST_SKIP() << "dataset absent: " << kMit;
  const CarmenLog log = ReadOk(kMit);
  ASSERT_EQ(log.events.size(), 2u * 1988);
  EXPECT_NEAR(ToSeconds(StampOf(log.events.front().event)), 1134864629.895182, 1e-6);
  EXPECT_NEAR(ToSeconds(StampOf(log.events.back().event)), 1134865053.892206, 1e-6);
  EXPECT_EQ(log.events.front().line, 4);  // after three comment lines
  EXPECT_FLOAT_EQ(log.largest_range, 81.91f);
  EXPECT_EQ(log.no_return_beams, log.largest_range_count);  // every 81.91 is a no-return
  EXPECT_GT(log.no_return_beams, 1000);
  const auto& o = std::get<OdometrySample>(log.events.front().event);
  EXPECT_DOUBLE_EQ(o.pose.x, 576.536523);
  EXPECT_DOUBLE_EQ(o.pose.theta, -2.255213);
}

}  // namespace
}  // namespace atlas::carmen
