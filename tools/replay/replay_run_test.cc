#include "replay/replay_run.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "atlas_paths.h"
#include "tools/replay/replay_refiner.h"

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

// Run a refines (--refine) after the run, run b does not: refinement changes none of the other
// files, and only a's summary carries its figures.
TEST_F(ReplayMitCsail, FilesWellFormedAndRunDeterministic) {
  ReplayOptions options;
  // With atlasd's settings (the defaults) the first Genesis comes at scan 320: 500 scans make
  // three frames, so that refinement has edges to work on.
  options.max_scans = 500;
  const std::string a = TempDir(), b = TempDir();
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  int64_t progress_calls = 0;
  options.refine = MakeRefiner(refine::RefineOptions{});
  const ReplayResult ra = RunReplay(
      read_.log.events, options, a, [&](int64_t, int64_t) { ++progress_calls; }, 100);
  ASSERT_TRUE(ra.error.empty()) << ra.error;
  options.refine = nullptr;
  const ReplayResult rb = RunReplay(read_.log.events, options, b);
  ASSERT_TRUE(rb.error.empty()) << rb.error;
  EXPECT_EQ(progress_calls, 5);
  EXPECT_EQ(ra.summary.scans, 500);
  EXPECT_GE(ra.summary.frames, 1);

  // Deterministic: everything but the measured step times is byte-identical.
  for (const char* name : {"trajectory.tsv", "graph.tsv", "global.tsv", "points.tsv"})
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
  EXPECT_EQ(ta.size(), 500u);
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
  // points.tsv: the laser points the frames keep (the laser atlas keeps them), by frame.
  const auto points = Rows(ReadAll(a + "/points.tsv"));
  EXPECT_GT(points.size(), 100u);
  for (const auto& p : points) {
    ASSERT_EQ(p.size(), 3u);
    const int frame = std::atoi(p[0].c_str());
    EXPECT_GE(frame, 0);
    EXPECT_LT(frame, ra.summary.frames);
    EXPECT_TRUE(IsFiniteNumber(p[1]) && IsFiniteNumber(p[2])) << p[1] << " " << p[2];
  }
  const std::string json = ReadAll(a + "/summary.json");
  EXPECT_NE(json.find("\"scans\": 500"), std::string::npos) << json;
  EXPECT_NE(json.find("\"frames\": " + std::to_string(ra.summary.frames)), std::string::npos);

  // The refinement's figures: every frame placed or counted as not connected, at least one
  // solver iteration for the constraints and no more than allowed (plus the initial one).
  const ReplaySummary& sa = ra.summary;
  EXPECT_EQ(sa.refine_status, "converged");
  EXPECT_EQ(sa.refined_frames + sa.refine_unreached_frames, sa.frames);
  EXPECT_EQ(sa.refine_unreached_frames, 0);  // the graph is connected (global.tsv above)
  EXPECT_LE(sa.refine_constraints + sa.refine_skipped_edges, sa.edges);
  EXPECT_GT(sa.refine_constraints, 0);
  EXPECT_GE(sa.refine_iterations, 1);
  EXPECT_LE(sa.refine_iterations, refine::RefineOptions{}.max_iterations + 1);
  for (const std::string& field :
       {"\"refine_iterations\": " + std::to_string(sa.refine_iterations),
        "\"refine_unreached_frames\": " + std::to_string(sa.refine_unreached_frames),
        "\"refine_skipped_edges\": " + std::to_string(sa.refine_skipped_edges),
        "\"refine_constraints\": " + std::to_string(sa.refine_constraints)})
    EXPECT_NE(json.find(field), std::string::npos) << field << " in " << json;
  const std::string json_b = ReadAll(b + "/summary.json");
  EXPECT_EQ(json_b.find("\"refine_iterations\""), std::string::npos) << json_b;
  EXPECT_FALSE(std::filesystem::exists(b + "/global_refined.tsv"));
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
}

// hypotheses.tsv: at every step, the live hypotheses that timing.tsv counts, exactly one of them
// dominant, in timing.tsv's dominant frame and at the pose trajectory.tsv published.
TEST_F(ReplayMitCsail, HypothesesFileListsEveryStepsLiveHypothesesWithTheDominantOneAsOutput) {
  ReplayOptions options;
  options.max_scans = 600;
  options.hypotheses = true;
  const std::string dir = TempDir(), plain = TempDir();
  ASSERT_FALSE(dir.empty());
  ASSERT_FALSE(plain.empty());
  const ReplayResult r = RunReplay(read_.log.events, options, dir);
  ASSERT_TRUE(r.error.empty()) << r.error;
  options.hypotheses = false;
  ASSERT_TRUE(RunReplay(read_.log.events, options, plain).error.empty());
  EXPECT_FALSE(std::filesystem::exists(plain + "/hypotheses.tsv"));
  EXPECT_EQ(ReadAll(dir + "/trajectory.tsv"), ReadAll(plain + "/trajectory.tsv"));

  const auto timing = Rows(ReadAll(dir + "/timing.tsv"));
  const auto traj = Rows(ReadAll(dir + "/trajectory.tsv"));
  const auto hyp = Rows(ReadAll(dir + "/hypotheses.tsv"));
  ASSERT_EQ(timing.size(), 600u);
  std::map<std::string, std::vector<std::string>> traj_at;  // by timestamp
  for (const auto& t : traj) traj_at[t[0]] = t;
  size_t k = 0;
  int juvenile_rows = 0;
  // Each hypothesis lives over consecutive steps and processes one scan per step.
  std::map<std::string, std::pair<long, long>> last_of;  // id -> (step, steps)
  for (const auto& t : timing) {
    const std::string& step = t[0];
    int live = 0, dominant = 0;
    for (; k < hyp.size() && hyp[k][0] == step; ++k) {
      const auto& h = hyp[k];
      ASSERT_EQ(h.size(), 17u);
      for (size_t c : {0u, 1u, 2u, 3u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 14u, 15u, 16u})
        EXPECT_TRUE(IsFiniteNumber(h[c])) << h[c];
      EXPECT_EQ(h[1], t[1]);
      ASSERT_TRUE(h[4] == "juvenile" || h[4] == "mature") << h[4];
      const double q = std::strtod(h[7].c_str(), nullptr);
      EXPECT_GE(q, 0.0);
      EXPECT_LE(q, 1.0);
      ++live;
      const long step_no = std::atol(h[0].c_str()), steps = std::atol(h[6].c_str());
      const auto prev = last_of.find(h[2]);
      if (prev != last_of.end()) {
        EXPECT_EQ(step_no, prev->second.first + 1) << "hypothesis " << h[2];
        EXPECT_EQ(steps, prev->second.second + 1) << "hypothesis " << h[2];
      } else if (step_no > 1) {
        EXPECT_EQ(steps, 0) << "hypothesis " << h[2];  // made during this step (Genesis, traversal)
      }
      last_of[h[2]] = {step_no, steps};
      if (h[4] == "juvenile") {
        ++juvenile_rows;
        EXPECT_EQ(h[5], "0");  // the output is a mature hypothesis
      }
      if (h[5] != "1") continue;
      ++dominant;
      EXPECT_EQ(h[3], t[4]) << "step " << step;  // timing.tsv's dominant frame
      const auto it = traj_at.find(h[1]);
      if (it == traj_at.end()) continue;
      EXPECT_EQ(it->second[1], h[3]);
      for (size_t c = 0; c < 3; ++c) EXPECT_EQ(it->second[2 + c], h[11 + c]) << "step " << step;
    }
    EXPECT_EQ(live, std::atoi(t[3].c_str())) << "step " << step;
    EXPECT_EQ(dominant, t[4] == "-1" ? 0 : 1) << "step " << step;
  }
  EXPECT_EQ(k, hyp.size());  // no row outside timing.tsv's steps
  EXPECT_GT(juvenile_rows, 0);
  EXPECT_GT(last_of.size(), 2u);
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(plain);
}

// --restart-after-scans: the atlas is read back from its image and the robot goes on in a new
// frame that no edge joins to the old ones until map-matching without a prior does; the summary
// says where the restart was and whether (after how many scans) the parts were joined.
TEST_F(ReplayMitCsail, RestartGoesOnInAnUnconnectedFrameAndCountsTheRejoin) {
  ReplayOptions options;
  options.max_scans = 900;
  options.restart_after_scans = 400;
  const std::string dir = TempDir();
  ASSERT_FALSE(dir.empty());
  const ReplayResult r = RunReplay(read_.log.events, options, dir);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const int restart = r.summary.restart_frame;
  const auto traj = Rows(ReadAll(dir + "/trajectory.tsv"));
  ASSERT_EQ(traj.size(), 900u);
  int before = 0;
  for (size_t i = 0; i < traj.size(); ++i) {
    const int frame = std::stoi(traj[i][1]);
    if (i < 400) {
      EXPECT_LT(frame, restart) << "row " << i;
      before = std::max(before, frame + 1);
    } else {
      EXPECT_GE(frame, restart) << "row " << i;
    }
  }
  EXPECT_EQ(restart, before);  // the new frame follows the saved ones
  bool crossing = false;
  for (const auto& e : Rows(ReadAll(dir + "/graph.tsv")))
    crossing |= (std::stoi(e[0]) < restart) != (std::stoi(e[1]) < restart);
  EXPECT_EQ(crossing, r.summary.rejoined_after_scans >= 0);
  if (r.summary.rejoined_after_scans < 0) {
    // Not joined: global.tsv places only the frames connected to frame 0.
    EXPECT_EQ(Rows(ReadAll(dir + "/global.tsv")).size(), 400u);
  } else {
    EXPECT_LE(r.summary.rejoined_after_scans, 500);
  }
  const std::string summary = ReadAll(dir + "/summary.json");
  EXPECT_NE(summary.find("\"restart_frame\": " + std::to_string(restart)), std::string::npos);
  std::filesystem::remove_all(dir);

  options.restart_after_scans = -1;
  EXPECT_NE(options.Validate().find("restart_after_scans"), std::string::npos);
}

TEST(Replay, UnwritableOutputIsAnErrorNotACrash) {
  const ReplayResult r =
      RunReplay(std::vector<SensorEvent>{}, ReplayOptions{}, "/proc/atlas-replay-cannot-be-here");
  EXPECT_FALSE(r.error.empty());
}

}  // namespace
}  // namespace atlas::replay
