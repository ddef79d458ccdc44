// One 361-value B0 telegram (mm) fed as one chunk through the stream decoder and decoded into
// a LaserScan, the work the laser reader thread does per scan.

#include <benchmark/benchmark.h>

#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

namespace atlas::sick {
namespace {

std::vector<uint8_t> Telegram361() {
  LaserScan scan;
  scan.ranges.resize(361);
  for (int i = 0; i < 361; ++i) scan.ranges[i] = i % 17 == 0 ? kNoReturn : 0.5f + 0.01f * i;
  return *EncodeMeasuredValues(scan, Unit::kMillimetre, 0x10);
}

void BM_StreamDecode361(benchmark::State& state) {
  const std::vector<uint8_t> bytes = Telegram361();
  StreamDecoder decoder;
  LaserScan scan;
  ScanInfo info;
  int64_t scans = 0;
  for (auto _ : state) {
    decoder.FeedAll(bytes, [&](const StreamEvent& e) {
      if (DecodeMeasuredValues(e.telegram, Time{}, ScanOptions{}, &scan, &info) ==
          ScanDecode::kOk) {
        ++scans;
      }
    });
    benchmark::DoNotOptimize(scan.ranges.data());
  }
  if (scans != state.iterations()) state.SkipWithError("a telegram was not decoded");
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes.size()));
}
BENCHMARK(BM_StreamDecode361);

// The same telegram arriving in 32-byte reads, as from a serial port at 500 kbaud.
void BM_StreamDecode361Chunked(benchmark::State& state) {
  const std::vector<uint8_t> bytes = Telegram361();
  StreamDecoder decoder;
  LaserScan scan;
  for (auto _ : state) {
    for (std::size_t at = 0; at < bytes.size(); at += 32) {
      decoder.FeedAll(std::span(bytes).subspan(at, std::min<std::size_t>(32, bytes.size() - at)),
                      [&](const StreamEvent& e) {
                        DecodeMeasuredValues(e.telegram, Time{}, ScanOptions{}, &scan, nullptr);
                      });
    }
    benchmark::DoNotOptimize(scan.ranges.data());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes.size()));
}
BENCHMARK(BM_StreamDecode361Chunked);

}  // namespace
}  // namespace atlas::sick
