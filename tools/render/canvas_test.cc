#include "tools/render/canvas.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/building_generator.h"
#include "sim/carmen_writer.h"
#include "sim/simulation.h"
#include "tools/render/run_data.h"
#include "tools/render/run_drawing.h"

namespace atlas::draw {
namespace {

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("atlas_draw_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ViewTransform, FitsKeepsAspectFlipsYAndInverts) {
  const ViewTransform v = ViewTransform::Fit(Vec2(0, 0), Vec2(20, 10), 10, 50, 400, 400);
  EXPECT_DOUBLE_EQ(v.pixels_per_metre(), 20.0);  // limited by the width
  const Vec2 top_left = v.ToImage(Vec2(0, 10)), bottom_right = v.ToImage(Vec2(20, 0));
  EXPECT_NEAR(top_left.x(), 10, 1e-9);
  EXPECT_NEAR(bottom_right.x(), 410, 1e-9);
  EXPECT_NEAR(bottom_right.y() - top_left.y(), 200, 1e-9);          // y up in the world, down in px
  EXPECT_NEAR(0.5 * (top_left.y() + bottom_right.y()), 250, 1e-9);  // centred vertically
  const Vec2 w(3.5, 7.25);
  EXPECT_NEAR((v.ToWorld(v.ToImage(w)) - w).norm(), 0.0, 1e-9);
}

TEST(Canvas, DrawsPixelsWhereTheWorldSays) {
  const auto dir = TempDir("pixels");
  const std::string path = (dir / "t.png").string();
  const ViewTransform v = ViewTransform::Fit(Vec2(0, 0), Vec2(10, 10), 0, 0, 100, 100);
  std::string error;
  auto c = Canvas::Create(ImageFormat::kPng, path, 100, 100, v, &error);
  ASSERT_TRUE(c) << error;
  c->Points({Vec2(2.5, 2.5)}, Color{1, 0, 0}, 2.0);               // image (25, 75)
  c->Line(Vec2(0, 9), Vec2(10, 9), Stroke{Color{0, 0, 1}, 2.0});  // image row 10
  ASSERT_EQ(c->Finish(), "");
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  auto pixel = [&](int x, int y) {  // ARGB32, little-endian: B G R A
    const unsigned char* p = data + y * stride + 4 * x;
    return std::array<int, 3>{p[2], p[1], p[0]};
  };
  EXPECT_EQ(pixel(25, 75), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(pixel(50, 10), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(pixel(50, 50), (std::array<int, 3>{255, 255, 255}));
  cairo_surface_destroy(s);
  std::filesystem::remove_all(dir);
}

TEST(Canvas, BadPathIsAnErrorNotACrash) {
  const ViewTransform v = ViewTransform::Fit(Vec2(0, 0), Vec2(1, 1), 0, 0, 50, 50);
  std::string error;
  auto c = Canvas::Create(ImageFormat::kPng, "/nonexistent/dir/x.png", 50, 50, v, &error);
  ASSERT_TRUE(c);
  EXPECT_NE(c->Finish(), "");
  EXPECT_FALSE(Canvas::Create(ImageFormat::kPng, "x.png", 5, 5, v, &error));
  ImageFormat f;
  EXPECT_TRUE(ImageFormatOf("a/B.SVG", &f));
  EXPECT_EQ(f, ImageFormat::kSvg);
  EXPECT_FALSE(ImageFormatOf("a.jpg", &f));
}

// A short simulated run written as atlas-sim does, read back and drawn.
TEST(RunData, ReadsAndDrawsASimulatedRun) {
  const auto dir = TempDir("run");
  sim::BuildingOptions bo;
  bo.min_rooms = 8;
  const sim::World world = sim::GenerateBuilding(bo, 1);
  {
    std::ofstream w(dir / "world.txt");
    sim::WriteWorld(w, world);
  }
  struct Sink : sim::SimulationSink {
    std::string truth, log;
    void OnTruth(const TruthSample& t) override { sim::AppendTruthRow(&truth, t); }
    void OnOdometry(const OdometrySample& o, double v, double w) override {
      sim::AppendOdomLine(&log, o, v, w);
    }
    void OnLaser(const LaserScan& s, const Pose2& o) override { sim::AppendFlaserLine(&log, s, o); }
    void OnSonar(const SonarReading& r, const Pose2& o) override {
      sim::AppendSonarLine(&log, r, o);
    }
  } sink;
  sim::SimulationOptions so;
  so.length_m = 40.0;
  so.sonar = true;
  const sim::SimulationSummary summary = sim::Simulate(world, so, sink);
  std::ofstream(dir / "truth.tsv") << "# timestamp x y theta\n" << sink.truth;
  std::ofstream(dir / "run.clf") << sink.log;

  RunData run;
  RunReadOptions ro;
  ro.max_scans = 10;
  ASSERT_EQ(ReadRun(dir.string(), ro, &run), "");
  EXPECT_EQ(run.world.walls.size(), world.walls.size());
  EXPECT_EQ(static_cast<long>(run.truth.size()), summary.truth_samples);
  EXPECT_EQ(run.odometry.size(), run.truth.size());
  EXPECT_EQ(run.total_scans, summary.laser_scans);
  EXPECT_EQ(run.sonar_lines, summary.sonar_readings);
  EXPECT_LE(static_cast<long>(run.scans.size()), 2 * ro.max_scans);
  EXPECT_GE(static_cast<long>(run.scans.size()), ro.max_scans / 2);
  // Scan points placed at the true pose lie on walls: near the line of some wall.
  const RunScan& s = run.scans[run.scans.size() / 2];
  const Pose2 truth = InterpolateTruth(run.truth, s.stamp);
  int near = 0, total = 0;
  for (const Vec2& p :
       ScanPoints(s, Compose(truth, Between(s.robot_odometry, s.laser_in_odometry)))) {
    ++total;
    for (const sim::Wall& w : world.walls) {
      const Vec2 d = w.b - w.a;
      const double t = std::clamp((p - w.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((w.a + t * d - p).norm() < 0.05) {
        ++near;
        break;
      }
    }
  }
  EXPECT_GT(total, 100);
  EXPECT_GT(near, 0.97 * total);

  RunDrawOptions d;
  d.width_px = 400;
  int height = 0;
  ViewTransform v;
  LayoutRun(run, d, &height, &v);
  EXPECT_GT(height, 100);
  for (auto [name, format] :
       {std::pair{"r.png", ImageFormat::kPng}, {"r.svg", ImageFormat::kSvg}}) {
    std::string error;
    auto c = Canvas::Create(format, (dir / name).string(), d.width_px, height, v, &error);
    ASSERT_TRUE(c) << error;
    DrawRun(*c, run, d);
    EXPECT_EQ(c->Finish(), "");
    EXPECT_GT(std::filesystem::file_size(dir / name), 1000u);
  }

  // A damaged line of run.clf is reported with its line number, not skipped.
  const auto lines = std::count(sink.log.begin(), sink.log.end(), '\n');
  std::ofstream(dir / "run.clf") << sink.log << "this is not a carmen line\n";
  std::string e = ReadRun(dir.string(), ro, &run);
  EXPECT_NE(e.find("run.clf:" + std::to_string(lines + 1) + ": first word"), std::string::npos)
      << e;
  // An empty truth.tsv is an error naming it.
  std::ofstream(dir / "truth.tsv") << "# timestamp x y theta\n";
  e = ReadRun(dir.string(), ro, &run);
  EXPECT_NE(e.find("truth.tsv: no rows"), std::string::npos) << e;
  std::filesystem::remove_all(dir);
}

// Frees the font caches after the last test, so that the leak checker sees a clean exit.
class DrawingCachesEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { ReleaseDrawingCaches(); }
};
const auto* const kDrawingCaches =
    ::testing::AddGlobalTestEnvironment(new DrawingCachesEnvironment);

TEST(RunData, MissingDirectoryIsAClearError) {
  RunData run;
  const std::string e = ReadRun("/nonexistent/run", RunReadOptions{}, &run);
  EXPECT_NE(e.find("cannot open /nonexistent/run/world.txt"), std::string::npos) << e;
}

}  // namespace
}  // namespace atlas::draw
