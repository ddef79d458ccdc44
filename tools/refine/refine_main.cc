// atlas-refine: offline global least-squares arrangement of a finished atlas (atlas-replay
// output directory). See --help.

#include <cstdio>
#include <string>

#include "core/common/parse_number.h"
#include "core/common/version.h"
#include "core/eval/atlas_relations.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "tools/refine/global_refinement.h"

namespace atlas::refine {
namespace {

constexpr const char* kHelp = R"(Usage: atlas-refine [options] DIR

Arranges all map-frames of an atlas globally by nonlinear least squares (Ceres) over the atlas
graph's edges, each a relative SE(2) constraint weighted by its inverse covariance, starting
from the Dijkstra projection from frame 0 with frame 0 held fixed. Offline only: the Atlas never
does this in its step loop (paper, Section I-A).

DIR is an atlas-replay output directory; reads DIR/graph.tsv and DIR/trajectory.tsv and writes
the refined global trajectory, "timestamp x y theta" as global.tsv (docs/formats.md), to
DIR/global_refined.tsv (or --out FILE). atlas-replay --refine does the same at the end of a run.

Options:
  --out FILE           output trajectory file (default DIR/global_refined.tsv)
  --max-iterations N   solver iterations (default 100)
  --version            the version
  -h, --help           this text

Frames that the edges do not connect to frame 0 cannot be placed: their trajectory rows are
left out, and a warning on stderr says how many and which frames. An edge whose covariance is
not usable is an error when graph.tsv is read (file:line).

Exit status: 0 written (warnings on stderr), 1 bad input or the solver failed (message on
stderr), 2 bad command line.
)";

int Usage(const std::string& what) {
  std::fprintf(stderr, "atlas-refine: %s\nTry 'atlas-refine --help'.\n", what.c_str());
  return 2;
}

int Main(int argc, char** argv) {
  std::string dir, out;
  RefineOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--version") {
      std::fputs(atlas::VersionLine("atlas-refine").c_str(), stdout);
      return 0;
    }
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "--out" || a == "--max-iterations") {
      if (i + 1 >= argc) return Usage(a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--out") {
        out = v;
      } else if (std::string error;
                 !IntegerArgument(a, v.c_str(), 1, 100000, options.max_iterations, error)) {
        return Usage(error);
      }
    } else if (!a.empty() && a[0] == '-') {
      return Usage("unknown option " + a);
    } else if (dir.empty()) {
      dir = a;
    } else {
      return Usage("one DIR only");
    }
  }
  if (dir.empty()) return Usage("no DIR given (an atlas-replay output directory)");
  if (out.empty()) out = dir + "/global_refined.tsv";

  formats::ReplayOutput run;
  if (std::string e = formats::ReadReplayOutput(dir, formats::ReplayFilesWanted{}, &run);
      !e.empty()) {
    std::fprintf(stderr, "atlas-refine: %s\n", e.c_str());
    return 1;
  }
  AtlasGraph graph;
  if (std::string e = eval::BuildGraphFromEdges(run.frame_count, run.graph.edges, &graph);
      !e.empty()) {
    std::fprintf(stderr, "atlas-refine: %s/graph.tsv: %s\n", dir.c_str(), e.c_str());
    return 1;
  }
  const RefineResult r = RefineGlobal(graph, options);
  std::printf(
      "atlas-refine %s: %s; %d frames placed, %d constraints, cost %.6g -> %.6g, %d "
      "iterations\n",
      dir.c_str(), ToString(r.status), r.frames, r.edges, r.initial_cost, r.final_cost,
      r.iterations);
  if (r.status == RefineStatus::kFailed || r.status == RefineStatus::kNoFrames) {
    std::fprintf(stderr, "atlas-refine: refinement %s: %s\n", ToString(r.status),
                 r.message.c_str());
    return 1;
  }
  int rows = 0;
  const std::string text = formats::FormatGlobalTrajectory(
      run.trajectory, r.refined,
      "atlas-refine global_refined: timestamp x y theta (global least-squares arrangement of "
      "the frames, frame 0 fixed)",
      &rows);
  if (std::string e = formats::WriteTextFile(out, text); !e.empty()) {
    std::fprintf(stderr, "atlas-refine: %s\n", e.c_str());
    return 1;
  }
  std::printf("wrote %s (%d rows)\n", out.c_str(), rows);
  if (r.skipped_edges > 0)
    std::fprintf(stderr,
                 "atlas-refine: warning: %d edges of %s/graph.tsv left out: covariance not usable "
                 "(not finite, a negative variance or not positive definite)\n",
                 r.skipped_edges, dir.c_str());
  if (r.unreached > 0) {
    std::string list;
    int listed = 0;
    for (size_t f = 0; f < r.refined.size(); ++f) {
      if (r.refined[f]) continue;
      if (++listed > 10) {
        list += " ...";
        break;
      }
      list += (list.empty() ? "" : " ") + std::to_string(f);
    }
    std::fprintf(stderr,
                 "atlas-refine: warning: %d of %d frames (%s) are not connected to frame 0 by the "
                 "usable edges of %s/graph.tsv; their %zu of %zu trajectory rows are left out of "
                 "%s\n",
                 r.unreached, r.frames + r.unreached, list.c_str(), dir.c_str(),
                 run.trajectory.size() - static_cast<size_t>(rows), run.trajectory.size(),
                 out.c_str());
  }
  return 0;
}

}  // namespace
}  // namespace atlas::refine

int main(int argc, char** argv) { return atlas::refine::Main(argc, argv); }
