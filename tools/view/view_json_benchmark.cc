// The cost of one page update (BuildViewJson) as the atlas grows: N frames in a grid, each joined
// to its left and lower neighbour, each with a remembered map of 10 lines (atlas.map_capacity's
// default), a pose and 5 hypotheses. At --rate 4, one update per 250 ms.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "tools/view/view_json.h"

namespace atlas::view {
namespace {

template <typename Message>
void Feed(ViewState& s, const char* channel, const Message& m) {
  std::vector<uint8_t> b(static_cast<size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  s.Ingest(channel, b.data(), b.size(), FromSeconds(1));
}

void BM_BuildViewJson(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0));
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  ViewState s(ViewChannels{}, n);
  atlasd::atlas_graph_t g{};
  g.num_frames = n;
  g.frames.resize(static_cast<size_t>(n));
  auto edge = [&](int a, int b, double x, double y) {
    atlasd::atlas_edge_t e{};
    e.frame_from = a;
    e.frame_to = b;
    e.x = x;
    e.y = y;
    e.covariance[0] = e.covariance[4] = 0.01;
    e.covariance[8] = 0.001;
    g.edges.push_back(e);
  };
  for (int i = 0; i < n; ++i) {
    if (i % side > 0) edge(i - 1, i, 5, 0);
    if (i >= side) edge(i - side, i, 0, 5);
    atlasd::local_map_t m{};
    m.frame_id = i;
    m.capacity = 10;
    for (int k = 0; k < 10; ++k) {
      atlasd::line_segment_t l{};
      l.x0 = k * 0.3;
      l.x1 = k * 0.3 + 2;
      l.y1 = 1;
      m.lines.push_back(l);
    }
    m.num_lines = 10;
    Feed(s, "ATLAS_LOCAL_MAP", m);
  }
  g.num_edges = static_cast<int32_t>(g.edges.size());
  g.dominant_frame_id = n / 2;
  Feed(s, "ATLAS_GRAPH", g);
  atlasd::pose_t p{};
  p.frame_id = n / 2;
  p.covariance[0] = p.covariance[4] = 0.01;
  Feed(s, "ATLAS_POSE", p);
  atlasd::hypotheses_t hs{};
  for (int i = 0; i < 5; ++i) {
    atlasd::hypothesis_t h{};
    h.id = i;
    h.frame_id = (n / 2 + i) % n;
    hs.hypotheses.push_back(h);
  }
  hs.num_hypotheses = 5;
  Feed(s, "ATLAS_HYPOTHESES", hs);
  size_t bytes = 0;
  for (auto _ : bench) {
    const std::string json = BuildViewJson(s, FromSeconds(2), n);
    bytes = json.size();
    benchmark::DoNotOptimize(json.data());
  }
  bench.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_BuildViewJson)->Arg(30)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace atlas::view
