// atlas-refine: offline global least-squares arrangement of a finished atlas (atlas-replay
// output directory). See --help.

#include <cstdio>
#include <optional>
#include <string>

#include "core/eval/atlas_relations.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "tools/cli/command_line.h"
#include "tools/refine/global_refinement.h"

namespace atlas::refine {
namespace {

constexpr const char* kDescription =
    R"(Arranges all map-frames of an atlas globally by nonlinear least squares (Ceres) over the atlas
graph's edges, each a relative SE(2) constraint weighted by its inverse covariance, starting
from the Dijkstra projection from frame 0 with frame 0 held fixed. Offline only: the Atlas never
does this in its step loop (paper, Section I-A).

DIR is an atlas-replay output directory; reads DIR/graph.tsv and DIR/trajectory.tsv and writes
the refined global trajectory, "timestamp x y theta" as global.tsv (docs/formats.md), to
DIR/global_refined.tsv (or --out FILE). atlas-replay --refine does the same at the end of a run.)";

constexpr const char* kFooter =
    R"(Frames that the edges do not connect to frame 0 cannot be placed: their trajectory rows are
left out, and a warning on stderr says how many and which frames. An edge whose covariance is
not usable is an error when graph.tsv is read (file:line).

Exit status: 0 written (warnings on stderr), 1 bad input or the solver failed (message on
stderr), 2 bad command line.
)";

int Main(int argc, char** argv) {
  std::string dir, out;
  RefineOptions options;
  cli::CommandLine command_line("atlas-refine", {"atlas-refine [options] DIR"}, kDescription,
                                kFooter);
  CLI::App& app = command_line.app();
  cli::AddPositional(app, "DIR", &dir, "an atlas-replay output directory");
  cli::AddText(app, "-o,--out", "FILE", &out,
               "output trajectory file (default DIR/global_refined.tsv)");
  cli::AddInteger(
      app, "--max-iterations", "N", 1, 100000, &options.max_iterations,
      "solver iterations (default " + std::to_string(RefineOptions{}.max_iterations) + ")");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
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
