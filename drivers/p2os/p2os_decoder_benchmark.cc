// One standard SIP with 8 sonar returns fed through the stream decoder, decoded and converted
// to a SonarReading, the work the sonar reader thread does per SIP (10 Hz on a P3-DX).

#include <benchmark/benchmark.h>

#include "drivers/p2os/p2os_messages.h"
#include "drivers/p2os/p2os_packet.h"

namespace atlas::p2os {
namespace {

void BM_StreamDecodeSip(benchmark::State& state) {
  StandardSip sip;
  for (uint8_t i = 0; i < 8; ++i) sip.sonars.push_back(SonarRaw{i, static_cast<uint16_t>(400 * i)});
  const std::vector<uint8_t> bytes = *EncodeStandardSip(sip);
  const SonarOptions options;
  StreamDecoder decoder;
  StandardSip decoded;
  SonarReading reading;
  int64_t readings = 0;
  for (auto _ : state) {
    decoder.FeedAll(bytes, [&](const PacketView& p) {
      if (DecodeStandardSip(p, &decoded) == SipDecode::kOk) {
        ToSonarReading(decoded, Time{}, options, &reading);
        ++readings;
      }
    });
    benchmark::DoNotOptimize(reading.returns.data());
  }
  if (readings != state.iterations()) state.SkipWithError("a SIP was not decoded");
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes.size()));
}
BENCHMARK(BM_StreamDecodeSip);

}  // namespace
}  // namespace atlas::p2os
