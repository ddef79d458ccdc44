// atlas-eval: scores a trajectory against ground-truth relations (Freiburg SLAM benchmark) or
// against a reference trajectory. See --help and docs/formats.md.

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/eval/reference_score.h"
#include "core/eval/relations_metric.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "tools/cli/command_line.h"
#include "tools/eval/trajectory_files.h"

namespace atlas::eval {
namespace {

constexpr const char* kDescription =
    R"(TRAJECTORY and REFERENCE are trajectory files: one pose per line, "timestamp x y theta"
(seconds, metres, radians), '#' comments; plain or gzip (docs/formats.md). RELATIONS is a
Freiburg SLAM-benchmark relations file "t1 t2 x y z roll pitch yaw".

Relations metric (Kuemmerle et al. 2009): for each relation, delta = P(t1) (-) P(t2),
error = relation (-) delta; translational |error.xy| in m, rotational |error.yaw| in deg;
mean +- standard deviation and the squared versions over the matched relations.
With --atlas DIR (atlas-replay's output directory), P(t1) and P(t2) are read from
DIR/trajectory.tsv, each in its own map-frame; when the frames differ, P(t2) is carried into
P(t1)'s frame along the Dijkstra path (minimum det of the composed covariance, paper eq. 2-3)
between the two frames in DIR/graph.tsv, as the paper does; no global arrangement is used.
Relations whose frames are not connected are counted and left out. The score is also printed
for four parts of the relations: both poses in one frame / composed across frames, and
spanning under 1 s / 1 s or more (on mit-csail the long ones are the robot's returns).
Reference scoring: relative pose error over pose pairs a fixed distance (--segment) or a fixed
number of poses (--step) apart, and absolute error after the best rigid alignment.)";

constexpr const char* kFooter =
    R"(Input files are checked as they are read: a malformed line, a value out of range (|t| > 4e9 s,
|x|, |y| > 1e7 m, |angle| > 1e3 rad), two poses with the same stamp, an edge whose covariance
is not positive definite or that names a frame DIR/frames.tsv does not list is an error naming
the file and line.

Exit status: 0 scored, 1 bad input or nothing to score (no relation or pose matched, no RPE
pair; message on stderr), 2 bad command line.
)";

int Fail(const std::string& error) {
  std::fprintf(stderr, "atlas-eval: %s\n", error.c_str());
  return 1;
}

// --errors FILE: one row per matched relation. Empty path: nothing written.
std::string WriteRelationErrors(const std::string& path, const std::vector<Relation>& relations,
                                const RelationsScore& score,
                                std::span<const FrameJoin> joins = {}) {
  if (path.empty()) return "";
  return formats::WriteTextFile(path, FormatRelationErrors(relations, score, joins));
}

// --atlas DIR: relations scored per frame, composed along Dijkstra paths of DIR/graph.tsv.
int ScoreAtlas(const std::string& dir, const std::string& relations_path, Duration tolerance,
               bool json, const std::string& errors_path) {
  // trajectory.tsv and graph.tsv, checked against the run's other files (formats/replay_dir.h).
  formats::ReplayOutput run;
  if (std::string e = formats::ReadReplayOutput(dir, formats::ReplayFilesWanted{}, &run);
      !e.empty())
    return Fail(e);
  const std::string graph_path = dir + "/graph.tsv";
  AtlasGraph graph;
  if (std::string e = BuildGraphFromEdges(run.frame_count, run.graph.edges, &graph); !e.empty())
    return Fail(graph_path + ": " + e);
  std::vector<FramePose> rows;
  rows.reserve(run.trajectory.size());
  for (const formats::FramePoseRow& r : run.trajectory) rows.push_back({r.stamp, r.frame, r.pose});
  formats::TextFile rf = formats::ReadTextFile(relations_path);
  if (!rf.error.empty()) return Fail(rf.error);
  const RelationsParse relations = ParseRelations(rf.text, relations_path);
  if (!relations.error.empty()) return Fail(relations.error);

  const size_t poses = rows.size();
  // The relations split by composition (same frame or not) and by span; each part scored with
  // a lookup of its own.
  std::vector<Relation> part[4];  // same frame, cross frame, span < 1 s, span >= 1 s
  {
    DijkstraComposedPoses classify(rows, graph, tolerance);
    for (const Relation& r : relations.relations) {
      const int64_t cross = classify.Counts().cross_frame;
      if (!classify(r.t1, r.t2)) continue;
      part[classify.Counts().cross_frame > cross ? 1 : 0].push_back(r);
      part[r.t2 - r.t1 < std::chrono::seconds(1) ? 2 : 3].push_back(r);
    }
  }
  RelationsScore part_score[4];
  for (int k = 0; k < 4; ++k) {
    DijkstraComposedPoses part_lookup(rows, graph, tolerance);
    part_score[k] =
        ScoreRelations(part[k], [&part_lookup](Time t1, Time t2) { return part_lookup(t1, t2); });
  }
  static constexpr const char* kPartName[4] = {"same_frame", "cross_frame", "span_under_1s",
                                               "span_1s_or_more"};
  DijkstraComposedPoses lookup(std::move(rows), graph, tolerance);
  // How each relation's poses are joined, by relation (ScoreRelations asks for each relation
  // once, in order).
  std::vector<FrameJoin> join_of(relations.relations.size(), FrameJoin::kSameFrame);
  size_t asked = 0;
  const RelationsScore s = ScoreRelations(
      relations.relations,
      [&lookup, &join_of, &asked](Time t1, Time t2) { return lookup(t1, t2, &join_of[asked++]); });
  std::vector<FrameJoin> joins;
  joins.reserve(s.errors.size());
  for (const RelationError& e : s.errors) joins.push_back(join_of[e.relation]);
  if (std::string e = WriteRelationErrors(errors_path, relations.relations, s, joins); !e.empty())
    return Fail(e);
  const CompositionCounts& c = lookup.Counts();
  if (json) {
    std::printf(
        "{\"estimate\": %s, \"relations\": %s, \"poses\": %zu, \"frames\": %d, \"edges\": %zu, "
        "\"matched\": %lld, \"same_frame\": %lld, \"cross_frame\": %lld, \"neighbours\": %lld, "
        "\"through_map_match\": %lld, \"chain\": %lld, \"unconnected\": %lld, "
        "\"unmatched\": %lld, \"translation_m\": %s, \"rotation_deg\": %s, \"parts\": {",
        JsonString(dir).c_str(), JsonString(relations_path).c_str(), poses, run.frame_count,
        run.graph.edges.size(), static_cast<long long>(s.matched),
        static_cast<long long>(c.same_frame), static_cast<long long>(c.cross_frame),
        static_cast<long long>(c.neighbours), static_cast<long long>(c.through_map_match),
        static_cast<long long>(c.chain), static_cast<long long>(c.unconnected),
        static_cast<long long>(c.unmatched), StatsJson(s.translation_m).c_str(),
        StatsJson(s.rotation_deg).c_str());
    for (int k = 0; k < 4; ++k)
      std::printf("%s\"%s\": {\"matched\": %lld, \"translation_m\": %s, \"rotation_deg\": %s}",
                  k > 0 ? ", " : "", kPartName[k], static_cast<long long>(part_score[k].matched),
                  StatsJson(part_score[k].translation_m).c_str(),
                  StatsJson(part_score[k].rotation_deg).c_str());
    std::printf("}}\n");
  } else {
    std::printf("estimate:   %s (%zu poses in %d frames, %zu edges)\nrelations:  %s\n", dir.c_str(),
                poses, run.frame_count, run.graph.edges.size(), relations_path.c_str());
    std::printf(
        "matched %lld of %lld relations: %lld same-frame, %lld cross-frame (Dijkstra-composed); "
        "left out: %lld unconnected frames, %lld stamps without a pose\n",
        static_cast<long long>(s.matched), static_cast<long long>(s.matched + s.unmatched),
        static_cast<long long>(c.same_frame), static_cast<long long>(c.cross_frame),
        static_cast<long long>(c.unconnected), static_cast<long long>(c.unmatched));
    std::printf(
        "cross-frame joins: %lld neighbouring frames, %lld through a map-match edge, %lld along a "
        "chain of two or more Genesis or refined edges\n",
        static_cast<long long>(c.neighbours), static_cast<long long>(c.through_map_match),
        static_cast<long long>(c.chain));
    std::fputs(FormatStats("translational", "m", s.translation_m).c_str(), stdout);
    std::fputs(FormatStats("rotational", "deg", s.rotation_deg).c_str(), stdout);
    for (int k = 0; k < 4; ++k) {
      std::printf("%s (%lld relations): translational %.4f m, rotational %.3f deg\n", kPartName[k],
                  static_cast<long long>(part_score[k].matched), part_score[k].translation_m.mean,
                  part_score[k].rotation_deg.mean);
    }
  }
  return s.matched > 0 ? 0
                       : Fail(
                             "no relation matched: are the trajectory and relations stamps on "
                             "the same clock (the log's ipc timestamps)?");
}

int Main(int argc, char** argv) {
  std::string relations_path, reference_path, log_path, trajectory_path, atlas_dir, errors_path;
  double tolerance_s = 0.001;
  ReferenceScoreOptions ref_options;
  bool json = false, step_given = false, segment_given = false;
  cli::CommandLine command_line(
      "atlas-eval",
      {"atlas-eval --relations RELATIONS TRAJECTORY         score against ground-truth relations",
       "atlas-eval --reference REFERENCE TRAJECTORY         score against a reference trajectory",
       "atlas-eval --relations RELATIONS --dead-reckon LOG  score a CARMEN log's dead reckoning",
       "atlas-eval --relations RELATIONS --atlas DIR        score atlas-replay output, per frame"},
      kDescription, kFooter);
  CLI::App& app = command_line.app();
  cli::AddPositional(app, "TRAJECTORY", &trajectory_path, "the trajectory file to score");
  cli::AddText(app, "--relations", "FILE", &relations_path, "relations file to score against");
  cli::AddText(app, "--reference", "FILE", &reference_path,
               "reference trajectory file to score against");
  cli::AddText(app, "--dead-reckon", "LOG", &log_path,
               "use the odometry of a CARMEN log (at each scan) as the trajectory");
  cli::AddText(app, "--atlas", "DIR", &atlas_dir,
               "score atlas-replay output (DIR/trajectory.tsv, DIR/graph.tsv)");
  cli::AddNumber(app, "--tolerance", "S", 0, 1e6, &tolerance_s,
                 "stamp matching tolerance in seconds (default 0.001)");
  cli::AddNumber(
      app, "--segment", "M", 0.001, 1e6,
      [&](double m) {
        ref_options.segment_length_m = m;
        ref_options.step_count = 0;
        segment_given = true;
      },
      "reference scoring: RPE pairs M metres of travel apart (default 1.0)");
  cli::AddInteger(app, "--step", "N", 1, 1000000000, &ref_options.step_count,
                  "reference scoring: RPE pairs N poses apart (instead of --segment;\n"
                  "give one of the two)")
      .Each([&](const std::string&) { step_given = true; });
  cli::AddFlag(app, "--json", &json, "print a JSON object instead of text");
  cli::AddText(app, "--errors", "FILE", &errors_path,
               "relations scoring: write each matched relation's error to FILE, one\n"
               "row \"t1 t2 translation_m rotation_deg\" in the relations' order");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (step_given) ref_options.segment_length_m = 0.0;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (relations_path.empty() == reference_path.empty()) {
    return Usage("give exactly one of --relations and --reference");
  }
  if (!trajectory_path.empty() + !log_path.empty() + !atlas_dir.empty() != 1) {
    return Usage("give exactly one of a trajectory file, --dead-reckon LOG and --atlas DIR");
  }
  if (!atlas_dir.empty() && relations_path.empty()) return Usage("--atlas needs --relations");
  if (!errors_path.empty() && relations_path.empty()) return Usage("--errors needs --relations");
  if (step_given && segment_given)
    return Usage(
        "give --step N or --segment M, not both (RPE pairs are either N poses or M m apart)");
  if ((step_given || segment_given) && reference_path.empty())
    return Usage("--step and --segment need --reference");
  ref_options.match_tolerance = Duration(static_cast<int64_t>(tolerance_s * 1e9));
  if (std::string bad = ref_options.Validate(); !bad.empty()) return Usage(bad);

  if (!atlas_dir.empty()) {
    return ScoreAtlas(atlas_dir, relations_path, Duration(static_cast<int64_t>(tolerance_s * 1e9)),
                      json, errors_path);
  }

  // The estimate.
  TimedTrajectory estimate;
  std::string estimate_name;
  if (!log_path.empty()) {
    std::fprintf(stderr, "atlas-eval: reading %s ...\n", log_path.c_str());
    carmen::CarmenReadResult r = carmen::ReadCarmenLog(log_path, {});
    if (!r.ok()) return Fail(r.error);
    estimate = OdometryAtScans(r.log.events);
    estimate_name = "dead reckoning of " + log_path;
  } else {
    formats::TextFile f = formats::ReadTextFile(trajectory_path);
    if (!f.error.empty()) return Fail(f.error);
    TrajectoryParse p = ParseTrajectory(f.text, trajectory_path);
    if (!p.error.empty()) return Fail(p.error);
    estimate = std::move(p.trajectory);
    estimate_name = trajectory_path;
  }

  if (!relations_path.empty()) {
    formats::TextFile f = formats::ReadTextFile(relations_path);
    if (!f.error.empty()) return Fail(f.error);
    RelationsParse p = ParseRelations(f.text, relations_path);
    if (!p.error.empty()) return Fail(p.error);
    const RelationsScore s =
        ScoreRelations(p.relations, BetweenPosesOf(estimate, ref_options.match_tolerance));
    if (std::string e = WriteRelationErrors(errors_path, p.relations, s); !e.empty())
      return Fail(e);
    if (json) {
      std::printf(
          "{\"estimate\": %s, \"relations\": %s, \"poses\": %zu, \"matched\": %lld, "
          "\"unmatched\": %lld, \"translation_m\": %s, \"rotation_deg\": %s}\n",
          JsonString(estimate_name).c_str(), JsonString(relations_path).c_str(), estimate.size(),
          static_cast<long long>(s.matched), static_cast<long long>(s.unmatched),
          StatsJson(s.translation_m).c_str(), StatsJson(s.rotation_deg).c_str());
    } else {
      std::printf("estimate:   %s (%zu poses)\nrelations:  %s\n", estimate_name.c_str(),
                  estimate.size(), relations_path.c_str());
      std::printf("matched %lld of %lld relations (%lld unmatched, tolerance %.4g s)\n",
                  static_cast<long long>(s.matched),
                  static_cast<long long>(s.matched + s.unmatched),
                  static_cast<long long>(s.unmatched), tolerance_s);
      std::fputs(FormatStats("translational", "m", s.translation_m).c_str(), stdout);
      std::fputs(FormatStats("rotational", "deg", s.rotation_deg).c_str(), stdout);
    }
    return s.matched > 0 ? 0
                         : Fail(
                               "no relation matched the trajectory's stamps: are both on the "
                               "same clock (the log's ipc timestamps)?");
  }

  formats::TextFile f = formats::ReadTextFile(reference_path);
  if (!f.error.empty()) return Fail(f.error);
  TrajectoryParse p = ParseTrajectory(f.text, reference_path);
  if (!p.error.empty()) return Fail(p.error);
  const ReferenceScore s = ScoreAgainstReference(estimate, p.trajectory, ref_options);
  char pairing[64];
  if (ref_options.step_count > 0) {
    std::snprintf(pairing, sizeof pairing, "%d poses", ref_options.step_count);
  } else {
    std::snprintf(pairing, sizeof pairing, "%.3g m", ref_options.segment_length_m);
  }
  if (s.matched == 0) {
    return Fail(
        "no pose of the trajectory matched a reference stamp: were both written from the same "
        "log with the same clock options?");
  }
  if (s.pairs == 0) {
    char what[256];
    if (ref_options.step_count > 0) {
      std::snprintf(what, sizeof what,
                    "no two of the %lld matched poses are %d poses apart: give a --step below "
                    "%lld",
                    static_cast<long long>(s.matched), ref_options.step_count,
                    static_cast<long long>(s.matched));
    } else {
      std::snprintf(what, sizeof what,
                    "no two matched poses are %.6g m of reference travel apart (the matched "
                    "reference path is %.6g m long): give a shorter --segment",
                    ref_options.segment_length_m, s.reference_path_m);
    }
    return Fail(std::string("no relative pose error pair: ") + what);
  }
  if (json) {
    std::printf(
        "{\"estimate\": %s, \"reference\": %s, \"poses\": %zu, \"matched\": %lld, "
        "\"unmatched\": %lld, \"rpe_pairing\": %s, \"rpe_pairs\": %lld, "
        "\"rpe_translation_m\": %s, \"rpe_rotation_deg\": %s, \"ate_translation_m\": %s, "
        "\"ate_rotation_deg\": %s, \"alignment\": [%.6g, %.6g, %.6g]}\n",
        JsonString(estimate_name).c_str(), JsonString(reference_path).c_str(), estimate.size(),
        static_cast<long long>(s.matched), static_cast<long long>(s.unmatched),
        JsonString(pairing).c_str(), static_cast<long long>(s.pairs),
        StatsJson(s.rpe_translation_m).c_str(), StatsJson(s.rpe_rotation_deg).c_str(),
        StatsJson(s.ate_translation_m).c_str(), StatsJson(s.ate_rotation_deg).c_str(),
        s.alignment.x, s.alignment.y, s.alignment.theta);
  } else {
    std::printf("estimate:   %s (%zu poses)\nreference:  %s (%zu poses)\n", estimate_name.c_str(),
                estimate.size(), reference_path.c_str(), p.trajectory.size());
    std::printf("matched %lld poses (%lld unmatched, tolerance %.4g s)\n",
                static_cast<long long>(s.matched), static_cast<long long>(s.unmatched),
                tolerance_s);
    std::printf("relative pose error over %lld pairs %s apart:\n", static_cast<long long>(s.pairs),
                pairing);
    std::fputs(FormatStats("  translational", "m", s.rpe_translation_m).c_str(), stdout);
    std::fputs(FormatStats("  rotational", "deg", s.rpe_rotation_deg).c_str(), stdout);
    std::printf("absolute error after alignment (%.3f m, %.3f m, %.2f deg):\n", s.alignment.x,
                s.alignment.y, s.alignment.theta * 180.0 / M_PI);
    std::fputs(FormatStats("  translational", "m", s.ate_translation_m).c_str(), stdout);
    std::fputs(FormatStats("  rotational", "deg", s.ate_rotation_deg).c_str(), stdout);
  }
  return 0;
}

}  // namespace
}  // namespace atlas::eval

int main(int argc, char** argv) { return atlas::eval::Main(argc, argv); }
