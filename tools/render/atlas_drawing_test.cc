#include "tools/render/atlas_drawing.h"

#include <cairo.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/eval/atlas_relations.h"

namespace atlas::draw {
namespace {

// Three frames in a row, 10 m apart, each edge with 0.1 m^2 position variance; one line per
// frame. From frame 0 the projection reaches all three, frame 2 with twice the covariance.
struct Fixture {
  formats::ReplayOutput run;
  AtlasGraph graph{4};
  Fixture() {
    for (int f = 0; f < 3; ++f) {
      formats::FrameLine l;
      l.frame = f;
      l.line.endpoint_a = Vec2(0, 1);
      l.line.endpoint_b = Vec2(5, 1);
      run.lines.push_back(l);
      graph.AddFrame(nullptr);
    }
    UncertainPose e;
    e.mean = Pose2{10, 0, 0};
    e.cov = Vec3(0.1, 0.1, 1e-4).asDiagonal();
    graph.AddEdge(0, 1, e, EdgeKind::kGenesis);
    graph.AddEdge(1, 2, e, EdgeKind::kGenesis);
    run.frame_count = 3;
  }
};

TEST(AtlasDrawing, LayoutPlacesFramesByTheProjection) {
  Fixture fx;
  AtlasDrawOptions o;
  o.width_px = 800;
  AtlasLayout layout;
  int height = 0;
  ViewTransform view;
  ASSERT_EQ(LayoutAtlas(fx.run, fx.graph, o, nullptr, &layout, &height, &view), "");
  EXPECT_EQ(layout.reached, 3);
  ASSERT_TRUE(layout.frame_pose[2].has_value());
  EXPECT_NEAR(layout.frame_pose[2]->mean.x, 20.0, 1e-12);
  EXPECT_NEAR(layout.frame_pose[2]->cov(0, 0), 0.2, 1e-9);
  EXPECT_NEAR(layout.max.x(), 26.0, 1e-12);  // frame 2's line ends at x = 25, plus 1 m margin
  // From frame 2, frame 0 lies 20 m behind.
  o.source = 2;
  ASSERT_EQ(LayoutAtlas(fx.run, fx.graph, o, nullptr, &layout, &height, &view), "");
  EXPECT_NEAR(layout.frame_pose[0]->mean.x, -20.0, 1e-12);
  o.source = 7;
  EXPECT_NE(LayoutAtlas(fx.run, fx.graph, o, nullptr, &layout, &height, &view), "");
}

TEST(AtlasDrawing, ProjectionAndTimelinePicturesAreWritten) {
  Fixture fx;
  const auto dir =
      std::filesystem::temp_directory_path() / ("atlas_drawing_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  AtlasDrawOptions o;
  o.width_px = 600;
  AtlasLayout layout;
  int height = 0;
  ViewTransform view;
  ASSERT_EQ(LayoutAtlas(fx.run, fx.graph, o, nullptr, &layout, &height, &view), "");
  std::string error;
  const std::string projection = (dir / "p.png").string();
  auto canvas = Canvas::Create(ImageFormat::kPng, projection, o.width_px, height, view, &error);
  ASSERT_NE(canvas, nullptr) << error;
  DrawAtlasProjection(*canvas, fx.run, fx.graph, layout, o);
  ASSERT_EQ(canvas->Finish(), "");
  EXPECT_GT(std::filesystem::file_size(projection), 1000u);

  std::vector<formats::TimingRecord> timing;
  for (int i = 0; i < 500; ++i)
    timing.push_back({i + 1, 0.1 * i, 1 + i / 100, 2, i / 100, 50000 + 100 * (i % 7)});
  TimelineOptions t;
  t.width_px = 600;
  t.height_px = 400;
  const std::string timeline = (dir / "t.png").string();
  canvas = Canvas::Create(ImageFormat::kPng, timeline, t.width_px, t.height_px,
                          ViewTransform::Fit(Vec2(0, 0), Vec2(600, 400), 0, 0, 600, 400), &error);
  ASSERT_NE(canvas, nullptr) << error;
  DrawTimeline(*canvas, timing, t);
  ASSERT_EQ(canvas->Finish(), "");
  EXPECT_GT(std::filesystem::file_size(timeline), 1000u);
  canvas.reset();
  std::filesystem::remove_all(dir);
}

// An atlas of grid frames: maps.tsv without rows, the map in points.tsv. Read as atlas-render
// reads an atlas, it is placed and drawn from its points.
TEST(AtlasDrawing, AnAtlasWithPointsAndNoLinesIsDrawnFromItsPoints) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("atlas_drawing_points_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name) << text;
  };
  write("trajectory.tsv", "# h\n1.0 0 0 0 0\n2.0 1 0 0 0\n");
  write("graph.tsv", "# h\n0 1 10 0 1.5707963 0.01 0 0 0.01 0 0.001 genesis\n");
  write("maps.tsv", "# h\n");
  std::string points = "# h\n";
  for (int f = 0; f < 2; ++f)  // a wall 2 m in front of each frame's origin, 4 m long
    for (int i = 0; i <= 80; ++i)
      points += std::to_string(f) + " 2 " + std::to_string(-2 + 0.05 * i) + "\n";
  write("points.tsv", points);
  formats::ReplayFilesWanted wanted;  // atlas-render's for the atlas pictures
  wanted.maps = true;
  formats::ReplayOutput run;
  ASSERT_EQ(formats::ReadReplayOutput(dir.string(), wanted, &run), "");
  EXPECT_TRUE(run.lines.empty());
  ASSERT_EQ(run.points.size(), 162u);
  AtlasGraph graph;
  ASSERT_EQ(eval::BuildGraphFromEdges(run.frame_count, run.graph.edges, &graph), "");

  AtlasDrawOptions o;
  o.width_px = 600;
  AtlasLayout layout;
  int height = 0;
  ViewTransform view;
  ASSERT_EQ(LayoutAtlas(run, graph, o, nullptr, &layout, &height, &view), "");
  // Frame 1 at (10, 0) turned a quarter: its wall runs along y = 2 from x = 8 to 12; the view
  // holds both walls and the origins, with 1 m to spare.
  EXPECT_NEAR(layout.min.x(), -1.0, 1e-6);  // frame 0's origin
  EXPECT_NEAR(layout.max.x(), 13.0, 1e-6);
  EXPECT_NEAR(layout.min.y(), -3.0, 1e-6);
  EXPECT_NEAR(layout.max.y(), 3.0, 1e-6);
  const std::string path = (dir / "p.png").string();
  std::string error;
  auto canvas = Canvas::Create(ImageFormat::kPng, path, o.width_px, height, view, &error);
  ASSERT_NE(canvas, nullptr) << error;
  DrawAtlasProjection(*canvas, run, graph, layout, o);
  ASSERT_EQ(canvas->Finish(), "");
  canvas.reset();
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  // Dark where the walls are, white between them.
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const auto grey = [&](const Vec2& world) {  // ARGB32: B G R A
    const Vec2 px = view.ToImage(world);
    const unsigned char* p =
        data + static_cast<int>(px.y()) * stride + 4 * static_cast<int>(px.x());
    return (p[0] + p[1] + p[2]) / 3;
  };
  EXPECT_LT(grey(Vec2(2.0, -1.0)), 160);  // frame 0's wall
  EXPECT_LT(grey(Vec2(9.0, 2.0)), 160);   // frame 1's wall
  EXPECT_GT(grey(Vec2(6.0, -2.0)), 240);  // nothing
  cairo_surface_destroy(s);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace atlas::draw
