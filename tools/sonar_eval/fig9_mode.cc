#include "tools/sonar_eval/fig9_mode.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/sonar/sonar_local_map.h"
#include "tools/cli/command_line.h"
#include "tools/monte_carlo/corridor.h"
#include "tools/render/canvas.h"
#include "tools/sonar_eval/corridor_run.h"
#include "tools/sonar_eval/sonar_atlas_run.h"

namespace atlas::sonar_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

// The options' defaults.
struct Fig9Defaults {
  std::string png = "sonar_fig9.png";
  int ring = 24;
  int seed = 1;
  int lines = 4;
  int phantoms = 0;
  double minutes = 3;
};

void Arc(draw::Canvas& c, const Pose2& sensor, double range, double half, const draw::Stroke& s) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= 12; ++i) {
    const double a = sensor.theta - half + 2.0 * half * i / 12.0;
    pts.push_back(Vec2(sensor.x + range * std::cos(a), sensor.y + range * std::sin(a)));
  }
  c.Polyline(pts, s);
}

int RunFig9Mode(const cli::ToolOptions& args) {
  const Fig9Defaults d;
  int ring = d.ring, seed = d.seed, lines = d.lines, phantoms = d.phantoms;
  double minutes = d.minutes;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetIntegerOption(args, "--lines", 1, 20, lines, error) ||
      !GetIntegerOption(args, "--phantoms", 0, 1, phantoms, error) ||
      !GetNumberOption(args, "--minutes", 0.1, 600, minutes, error)) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", error.c_str());
    return 2;
  }
  const std::string png = args.values.count("--png") ? args.values.at("--png") : d.png;
  draw::ImageFormat format;
  if (!draw::ImageFormatOf(png, &format)) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: --png must end in .png or .svg\n");
    return 2;
  }
  CorridorRun run(static_cast<uint64_t>(seed), static_cast<int>(ring));
  SonarLocalMap map(SimulatedMapOptions(RangeSensors::kSonar, 20, run.wheel, run.sonar));
  struct Drawn {
    Pose2 robot;
    InitialisedLine line;
  };
  std::vector<Drawn> drawn;
  std::vector<Vec2> path, true_path;
  const Pose2 origin = run.follower.pose();
  Pose2 last_odo = run.odometry.Step(TruthSample{Time{}, origin}).pose;
  const double dt = mc::kOdometryDt;
  const std::vector<Vec2> wall_lines = WallLinesInFrame(run.walls, origin);
  for (int s = 1; s <= minutes * 60 * 50 && static_cast<int>(drawn.size()) < lines; ++s) {
    run.follower.Step(dt);
    const Pose2 world = run.follower.pose();
    const Pose2 odo = run.odometry.Step(TruthSample{FromSeconds(s * dt), world}).pose;
    map.Predict(Between(last_odo, odo));
    last_odo = odo;
    if (s % mc::kScanEvery != 0) continue;
    const SonarUpdate up = map.UpdateSonar(
        run.ring_model.Read(run.caster, world, FromSeconds(s * dt)), run.sonar.ring, true);
    const Pose2 est = map.RobotPose().mean;
    path.push_back(Vec2(est.x, est.y));
    const Pose2 t = Between(origin, world);
    true_path.push_back(Vec2(t.x, t.y));
    for (const InitialisedLine& l : up.initialised) {
      if (phantoms != 0) {
        const Vec2 seen = WallLine(sim::Wall{est.TransformPoint(l.line.endpoint_a),
                                             est.TransformPoint(l.line.endpoint_b)});
        if (!FarFromEveryWall(seen, wall_lines)) continue;
      }
      drawn.push_back(Drawn{est, l});
    }
  }
  if (drawn.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: no %s was initialised in %.1f minutes\n",
                 phantoms != 0 ? "phantom line" : "line", minutes);
    return 1;
  }
  Vec2 lo(-1, -2.5), hi(21, 2.5);
  std::string err;
  const draw::ViewTransform view = draw::ViewTransform::Fit(lo, hi, 10, 60, 1780, 520);
  auto canvas = draw::Canvas::Create(format, png, 1800, 640, view, &err);
  if (!canvas) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", err.c_str());
    return 1;
  }
  for (const sim::Wall& w : run.walls) {
    canvas->Line(Inverse(origin).TransformPoint(w.a), Inverse(origin).TransformPoint(w.b),
                 draw::Stroke{draw::Color{0.7, 0.7, 0.7, 1.0}, 6.0, false});
  }
  canvas->Polyline(true_path, draw::Stroke{draw::Color{0.3, 0.7, 0.3, 1.0}, 1.5, false});
  canvas->Polyline(path, draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 1.5, false});
  const draw::Color palette[4] = {
      {0.85, 0.1, 0.1, 1.0}, {0.6, 0.1, 0.7, 1.0}, {0.9, 0.5, 0.0, 1.0}, {0.0, 0.55, 0.55, 1.0}};
  for (size_t i = 0; i < drawn.size(); ++i) {
    const Drawn& d = drawn[i];
    const draw::Color col = palette[i % 4];
    const double half = 0.5 * run.sonar.ring[0].beam_width;
    for (size_t j = 0; j < d.line.sensors.size(); ++j) {
      const Pose2 sensor = Compose(d.robot, d.line.sensors[j]);
      Arc(*canvas, sensor, d.line.ranges[j], half, draw::Stroke{col.WithAlpha(0.45), 1.0, false});
      canvas->FilledCircle(d.robot.TransformPoint(d.line.tangent_points[j]), 2.5, col);
    }
    for (const Pose2& v : d.line.vantage)
      canvas->Pose(Compose(d.robot, v), 0.12, col.WithAlpha(0.8));
    canvas->Line(d.robot.TransformPoint(d.line.line.endpoint_a),
                 d.robot.TransformPoint(d.line.line.endpoint_b), draw::Stroke{col, 4.0, false});
    std::printf(
        "line %zu: %d returns from %zu vantage points over %.2f m baseline; sigma rho "
        "%.3f m, sigma alpha %.2f deg\n",
        i + 1, d.line.support, d.line.vantage.size(), d.line.baseline,
        std::sqrt(d.line.line.cov(0, 0)),
        std::sqrt(d.line.line.cov(1, 1)) * 180.0 / std::numbers::pi);
  }
  char title[200];
  std::snprintf(title, sizeof(title),
                "Sonar feature initialisation from several vantage points (%d-transducer ring, "
                "seed %d): first %zu %s",
                static_cast<int>(ring), static_cast<int>(seed), drawn.size(),
                phantoms != 0 ? "phantom lines (0.25 m or 10 deg off every wall)" : "lines");
  canvas->TextPx(Vec2(12, 28), title, 20, draw::Color{}, true);
  canvas->ScaleBar();
  canvas->Legend(
      Vec2(12, 630),
      {{"true walls", {0.7, 0.7, 0.7, 1}, false},
       {"true / estimated path", {0.1, 0.4, 0.9, 1}, false},
       {"returns (arcs), tangent points, vantage poses, line", {0.85, 0.1, 0.1, 1}, false}});
  const std::string fin = canvas->Finish();
  if (!fin.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", fin.c_str());
    return 1;
  }
  std::printf("wrote %s\n", png.c_str());
  return 0;
}

}  // namespace

cli::ToolMode Fig9Mode() {
  const Fig9Defaults d;
  return {
      "fig9",
      "sonar feature initialisations drawn like the paper's Fig. 9",
      {{"--png", "F", "the picture, .png or .svg (default " + d.png + ")"},
       RingOption(d.ring),
       {"--seed", "S", "noise seed of the corridor run (default " + std::to_string(d.seed) + ")"},
       {"--lines", "K",
        "features drawn, the first K initialised (default " + std::to_string(d.lines) + ")"},
       {"--phantoms", "0|1",
        "1: only lines 0.25 m or 10 deg off every wall (default " + std::to_string(d.phantoms) +
            ")"},
       {"--minutes", "M",
        "longest drive to find them, minutes (default " + cli::HelpNumber(d.minutes) + ")"}},
      RunFig9Mode};
}

}  // namespace atlas::sonar_eval
