// Time of one AtlasStore::Save() batch (one transaction, WAL, synchronous=NORMAL): the writer
// thread must keep up with state.save_period_s, or batches are merged.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "daemon/store/atlas_store.h"

namespace atlas {
namespace {

void BM_SaveBatch(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  const int blob_bytes = static_cast<int>(state.range(1));
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("atlas_store_bench_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  AtlasStore store;
  if (!store.Open(dir.string()).ok()) {
    state.SkipWithError("cannot open the store");
    return;
  }
  AtlasSnapshot batch;
  for (int i = 0; i < frames; ++i) {
    batch.frames.push_back(
        {i, std::string(static_cast<size_t>(blob_bytes), static_cast<char>(i)), 0});
    StoredEdge e;
    e.frame_from = i;
    e.frame_to = i + 1;
    batch.edges.push_back(e);
  }
  std::string error;
  int64_t round = 0;
  for (auto _ : state) {
    batch.metadata["round"] = std::to_string(++round);  // rows are rewritten every round
    if (!store.Save(batch, &error)) {
      state.SkipWithError(error.c_str());
      break;
    }
  }
  state.SetBytesProcessed(state.iterations() * frames * int64_t{blob_bytes});
  store.Close();
  std::filesystem::remove_all(dir);
}
// (frames changed per batch, bytes per local-map image)
BENCHMARK(BM_SaveBatch)
    ->Args({1, 8192})
    ->Args({10, 8192})
    ->Args({50, 8192})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace atlas
