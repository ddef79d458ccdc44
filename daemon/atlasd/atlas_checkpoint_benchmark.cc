// CheckpointBuilder::Make, the loop thread's share of a checkpoint (atlas_checkpoint.h), on an
// atlas of N frames whose map images are as large as a grid frame's (440 kB, the intel log's),
// after one step: the batch carries the atlas image and the rows of the frames whose maps
// changed. Counters: frame rows and bytes per batch.
//
// Warm-up (not timed): the robot explores until the atlas holds N frames, and a first batch
// carries every frame. Timed: Make() after each step (the step itself is not timed).

#include <benchmark/benchmark.h>

#include <memory>

#include "core/atlas/atlas.h"
#include "core/testing/atlas_test_world.h"
#include "daemon/atlasd/atlas_checkpoint.h"

namespace atlas {
namespace {

constexpr int kGridFrameImageBytes = 440 * 1000;

void BM_CheckpointAfterOneStep(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  TestWorld w;
  w.radius = 1.5;
  w.image_padding = kGridFrameImageBytes;
  w.Install();
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  const LaserScan scan = TestScan();
  for (int i = 0; atlas.Graph().FrameCount() < frames; ++i)
    atlas.Step(Pose2{0.25, 0.0, (i / 150) % 2 ? 0.02 : -0.02}, scan);
  CheckpointBuilder builder;
  builder.Make(atlas);
  int64_t k = 0, rows = 0, bytes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    atlas.Step(Pose2{(k / 24) % 2 ? -0.25 : 0.25, 0.0, 0.0}, scan);
    state.ResumeTiming();
    const AtlasSnapshot batch = builder.Make(atlas);
    rows += static_cast<int64_t>(batch.frames.size());
    for (const StoredFrame& f : batch.frames) bytes += static_cast<int64_t>(f.blob.size());
    for (const auto& [key, value] : batch.metadata) bytes += static_cast<int64_t>(value.size());
    ++k;
  }
  state.counters["frames"] = atlas.Graph().FrameCount();
  state.counters["rows/batch"] = static_cast<double>(rows) / static_cast<double>(k);
  state.counters["kB/batch"] = static_cast<double>(bytes) / 1000.0 / static_cast<double>(k);
}
BENCHMARK(BM_CheckpointAfterOneStep)
    ->Arg(10)
    ->Arg(50)
    ->Arg(200)
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace atlas
