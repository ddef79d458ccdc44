#include "tools/replay/replay_run.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace atlas::replay {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Data rows of a .tsv (header comment dropped), split into fields.
std::vector<std::vector<std::string>> Rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::istringstream f(line);
    std::string field;
    while (std::getline(f, field, '\t')) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

bool IsFiniteNumber(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(v);
}

std::string TempDir() {
  char pattern[] = "/tmp/atlas_replay_test_XXXXXX";
  const char* d = mkdtemp(pattern);
  return d == nullptr ? std::string() : std::string(d);
}

class ReplayMitCsail : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string path = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
    if (access(path.c_str(), R_OK) != 0) GTEST_SKIP() << path << " is absent";
    read_ = carmen::ReadCarmenLog(path, carmen::CarmenLogOptions{});
    ASSERT_TRUE(read_.ok()) << read_.error;
  }
  carmen::CarmenReadResult read_;
};

TEST_F(ReplayMitCsail, FilesWellFormedAndRunDeterministic) {
  ReplayOptions options;
  options.max_scans = 300;
  const std::string a = TempDir(), b = TempDir();
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  int64_t progress_calls = 0;
  const ReplayResult ra = RunReplay(
      read_.log.events, options, a, [&](int64_t, int64_t) { ++progress_calls; }, 100);
  ASSERT_TRUE(ra.error.empty()) << ra.error;
  const ReplayResult rb = RunReplay(read_.log.events, options, b);
  ASSERT_TRUE(rb.error.empty()) << rb.error;
  EXPECT_EQ(progress_calls, 3);
  EXPECT_EQ(ra.summary.scans, 300);
  EXPECT_GE(ra.summary.frames, 1);

  // Deterministic: everything but the measured step times is byte-identical.
  for (const char* name : {"trajectory.tsv", "graph.tsv", "global.tsv"})
    EXPECT_EQ(ReadAll(a + "/" + name), ReadAll(b + "/" + name)) << name;
  auto ta = Rows(ReadAll(a + "/timing.tsv")), tb = Rows(ReadAll(b + "/timing.tsv"));
  ASSERT_EQ(ta.size(), tb.size());
  for (size_t i = 0; i < ta.size(); ++i) {
    ASSERT_EQ(ta[i].size(), 6u);
    ASSERT_EQ(tb[i].size(), 6u);
    ta[i].pop_back();
    tb[i].pop_back();
    EXPECT_EQ(ta[i], tb[i]) << "timing row " << i;
  }

  // Well-formed: field counts, numbers, and consistency between the files.
  const auto traj = Rows(ReadAll(a + "/trajectory.tsv"));
  const auto graph = Rows(ReadAll(a + "/graph.tsv"));
  const auto global = Rows(ReadAll(a + "/global.tsv"));
  EXPECT_EQ(ta.size(), 300u);
  EXPECT_GT(traj.size(), 250u);
  EXPECT_EQ(global.size(), traj.size());  // the graph is connected: every frame is placed
  EXPECT_EQ(static_cast<int>(graph.size()), ra.summary.edges);
  EXPECT_GE(ra.summary.edges, ra.summary.frames - 1);
  double last_stamp = -1;
  for (size_t i = 0; i < traj.size(); ++i) {
    ASSERT_EQ(traj[i].size(), 5u);
    for (const auto& f : traj[i]) EXPECT_TRUE(IsFiniteNumber(f)) << f;
    const int frame = std::atoi(traj[i][1].c_str());
    EXPECT_GE(frame, 0);
    EXPECT_LT(frame, ra.summary.frames);
    const double stamp = std::strtod(traj[i][0].c_str(), nullptr);
    EXPECT_GT(stamp, last_stamp);
    last_stamp = stamp;
    ASSERT_EQ(global[i].size(), 4u);
    EXPECT_EQ(global[i][0], traj[i][0]);
    // Poses in frame 0 are their own global poses.
    if (frame == 0) {
      for (size_t k = 1; k < 4; ++k) EXPECT_EQ(global[i][k], traj[i][k + 1]);
    }
  }
  for (const auto& e : graph) {
    ASSERT_EQ(e.size(), 12u);
    for (size_t k = 0; k < 11; ++k) EXPECT_TRUE(IsFiniteNumber(e[k])) << e[k];
    EXPECT_TRUE(e[11] == "genesis" || e[11] == "map-match" || e[11] == "refined") << e[11];
    EXPECT_GE(std::strtod(e[5].c_str(), nullptr), 0.0);   // c00
    EXPECT_GE(std::strtod(e[8].c_str(), nullptr), 0.0);   // c11
    EXPECT_GE(std::strtod(e[10].c_str(), nullptr), 0.0);  // c22
  }
  const std::string json = ReadAll(a + "/summary.json");
  EXPECT_NE(json.find("\"scans\": 300"), std::string::npos) << json;
  EXPECT_NE(json.find("\"frames\": " + std::to_string(ra.summary.frames)), std::string::npos);
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
}

TEST(Replay, UnwritableOutputIsAnErrorNotACrash) {
  const ReplayResult r = RunReplay({}, ReplayOptions{}, "/proc/atlas-replay-cannot-be-here");
  EXPECT_FALSE(r.error.empty());
}

}  // namespace
}  // namespace atlas::replay
