#include "logs/lcm/lcm_log_reader.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "atlasd/pose_t.hpp"

namespace atlas {
namespace {

class LcmLogReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir_template[] = "/tmp/atlas_lcm_log_XXXXXX";  // mkdtemp replaces the X's
    ASSERT_NE(mkdtemp(dir_template), nullptr) << std::strerror(errno);
    dir_ = dir_template;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // An lcm-logger file written by LCM's own writer: `n` poses on ATLAS_POSE, then one event of
  // 3 bytes on ATLAS_POSE (not a pose_t) when `bad_pose`. Returns the offset of every event.
  std::vector<int64_t> WriteLog(const std::string& path, int n, bool bad_pose = false) {
    std::vector<int64_t> offsets;
    lcm::LogFile log(path, "w");
    EXPECT_TRUE(log.good());
    std::vector<uint8_t> buffer;
    for (int i = 0; i < n + (bad_pose ? 1 : 0); ++i) {
      atlasd::pose_t p{};
      p.utime = 1000 * i;
      p.x = i;
      p.frame_id = i;
      buffer.resize(static_cast<size_t>(p.getEncodedSize()));
      p.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
      if (i == n) buffer = {1, 2, 3};
      lcm::LogEvent e;
      e.eventnum = i;
      e.timestamp = 5000 + i;
      e.channel = "ATLAS_POSE";
      e.datalen = static_cast<int32_t>(buffer.size());
      e.data = buffer.data();
      offsets.push_back(log.getFilePtr() ? std::ftell(log.getFilePtr()) : -1);
      EXPECT_EQ(log.writeEvent(&e), 0);
    }
    return offsets;
  }

  static std::string Bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  static void Write(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
  }
  // Opens `path` and reads it to the end; the events read.
  static int ReadAll(LcmLogReader* r, const std::string& path) {
    EXPECT_TRUE(r->Open(path)) << r->error();
    LcmLogEvent e;
    int n = 0;
    while (r->Next(&e)) ++n;
    EXPECT_EQ(n, r->events());
    return n;
  }

  std::string dir_;
};

TEST_F(LcmLogReaderTest, ReadsWhatLcmWrote) {
  const std::string path = dir_ + "/a.lcm";
  const std::vector<int64_t> offsets = WriteLog(path, 5);
  LcmLogReader r;
  ASSERT_TRUE(r.Open(path)) << r.error();
  LcmLogEvent e;
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(r.Next(&e)) << r.problem();
    EXPECT_EQ(e.offset, offsets[static_cast<size_t>(i)]);
    EXPECT_EQ(e.eventnum, i);
    EXPECT_EQ(e.timestamp, 5000 + i);
    EXPECT_EQ(e.channel, "ATLAS_POSE");
    atlasd::pose_t p{};
    ASSERT_TRUE(r.Decode(e, &p));
    EXPECT_EQ(p.utime, 1000 * i);
    EXPECT_EQ(p.x, i);
    EXPECT_EQ(p.frame_id, i);
  }
  EXPECT_FALSE(r.Next(&e));
  EXPECT_FALSE(r.Next(&e));
  EXPECT_EQ(r.problem(), "");
  EXPECT_TRUE(r.Problems().empty());
  EXPECT_FALSE(r.truncated());
}

TEST_F(LcmLogReaderTest, RefusesWhatIsNotAnLcmLog) {
  struct Case {
    std::string path;
    bool write;  // `content` into `path` first
    std::string content, expected;
  };
  const std::vector<Case> cases = {
      {dir_, false, "", "is a directory"},
      {dir_ + "/missing.lcm", false, "", "cannot read the LCM log (No such file or directory)"},
      {dir_ + "/empty.lcm", true, "", "is empty, not an LCM log"},
      {dir_ + "/random.bin", true, std::string("\x7f\x03\xa0\x11\x00\xff garbage", 14),
       "not an LCM log: it begins with 7F 03 A0 11, not with the sync word ED A1 DA 01"},
      {dir_ + "/short.lcm", true, "\xED\xA1", "not an LCM log: it begins with ED A1,"},
      {dir_ + "/mit.clf", true, "# CARMEN Logfile\nFLASER 180 1.0\n", "a CARMEN log?"},
      {"/dev/null", false, "", "is not a regular file"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    if (c.write) Write(c.path, c.content);
    LcmLogReader r;
    EXPECT_FALSE(r.Open(c.path));
    EXPECT_EQ(r.error().rfind(c.path + ": ", 0), 0u) << r.error();
    EXPECT_NE(r.error().find(c.expected), std::string::npos) << r.error();
    LcmLogEvent e;
    EXPECT_FALSE(r.Next(&e));
  }
}

// Cut at every byte: the complete events are read, then the cut is reported, with the byte
// where the file ends (none at a cut between events).
TEST_F(LcmLogReaderTest, ReportsATruncatedLog) {
  const std::string path = dir_ + "/a.lcm";
  std::vector<int64_t> offsets = WriteLog(path, 3);
  const std::string bytes = Bytes(path);
  offsets.push_back(static_cast<int64_t>(bytes.size()));
  const std::string cut = dir_ + "/cut.lcm";
  for (size_t size = 4; size <= bytes.size(); ++size) {
    SCOPED_TRACE(size);
    Write(cut, bytes.substr(0, size));
    int complete = 0;
    bool boundary = false;
    for (size_t i = 1; i < offsets.size(); ++i) {
      complete += offsets[i] <= static_cast<int64_t>(size);
      boundary = boundary || offsets[i] == static_cast<int64_t>(size);
    }
    LcmLogReader r;
    ASSERT_EQ(ReadAll(&r, cut), complete);
    if (boundary) {
      EXPECT_EQ(r.problem(), "");
      continue;
    }
    EXPECT_TRUE(r.truncated());
    EXPECT_EQ(r.problem().rfind(cut + ": truncated at byte " + std::to_string(size) +
                                    ": the last event, event " + std::to_string(complete + 1) +
                                    " (from byte " + std::to_string(offsets[complete]) +
                                    "), is incomplete",
                                0),
              0u)
        << r.problem();
    EXPECT_EQ(r.Problems(), std::vector<std::string>{r.problem()});
  }
}

TEST_F(LcmLogReaderTest, ReportsACorruptEvent) {
  const std::string path = dir_ + "/a.lcm";
  const std::vector<int64_t> offsets = WriteLog(path, 3);
  const std::string bytes = Bytes(path);
  const size_t second = static_cast<size_t>(offsets[1]);
  struct Case {
    size_t at;
    std::string put, expected;
  };
  const std::vector<Case> cases = {
      {second, std::string("\x00\x00\x00\x00", 4),
       "does not begin with the sync word ED A1 DA 01 (found 00 00 00 00)"},
      {second + 20, "\xFF\xFF\xFF\xFF", "has an invalid channel length -1 (1 to 999)"},
      {second + 20, std::string("\x00\x00\x00\x00", 4), "has an invalid channel length 0"},
      {second + 24, "\xFF\xFF\xFF\xFE", "has a negative data length -2"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    std::string b = bytes;
    ASSERT_EQ(c.put.size(), 4u);
    b.replace(c.at, 4, c.put);
    Write(path, b);
    LcmLogReader r;
    EXPECT_EQ(ReadAll(&r, path), 1);
    EXPECT_FALSE(r.truncated());
    const std::string at = std::to_string(second);
    EXPECT_EQ(r.problem().rfind(
                  path + ": corrupt at byte " + at + ": event 2 (from byte " + at + ") ", 0),
              0u)
        << r.problem();
    EXPECT_NE(r.problem().find(c.expected), std::string::npos) << r.problem();
    EXPECT_NE(r.problem().find("; the event before it was read, none after it"), std::string::npos)
        << r.problem();
  }
}

TEST_F(LcmLogReaderTest, CountsEventsThatDoNotDecode) {
  const std::string path = dir_ + "/a.lcm";
  WriteLog(path, 2, /*bad_pose=*/true);
  LcmLogReader r;
  ASSERT_TRUE(r.Open(path)) << r.error();
  LcmLogEvent e;
  int decoded = 0;
  while (r.Next(&e)) {
    atlasd::pose_t p{};
    decoded += r.Decode(e, &p);
  }
  EXPECT_EQ(decoded, 2);
  EXPECT_EQ(r.events(), 3);
  EXPECT_EQ(r.undecodable_total(), 1);
  EXPECT_EQ(r.undecodable().at("ATLAS_POSE"), 1);
  EXPECT_EQ(r.problem(), "");
  EXPECT_EQ(r.Problems(),
            std::vector<std::string>{
                path + ": 1 event on ATLAS_POSE could not be decoded as that channel's "
                       "type (another lcmtypes version, or damaged data) and was left "
                       "out"});
}

}  // namespace
}  // namespace atlas
