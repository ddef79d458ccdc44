// libFuzzer target: random bytes through the LMS stream decoder (cut into chunks whose sizes
// come from the input), every telegram through the message decoders, and each decoded scan
// back through the encoder. Invariants are checked with traps.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "drivers/framing/fuzz_check.h"
#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

namespace {

using namespace atlas::sick;

void CheckScan(const atlas::LaserScan& scan, const ScanInfo& info) {
  FUZZ_CHECK(static_cast<int>(scan.ranges.size()) == info.count);
  const double unit = UnitMetres(info.unit);
  int no_return = 0;
  for (float r : scan.ranges) {
    if (atlas::IsReturn(r)) {
      FUZZ_CHECK(r >= 0.0f && r < 8192 * unit);
    } else {
      FUZZ_CHECK(r == atlas::kNoReturn);
      ++no_return;
    }
  }
  FUZZ_CHECK(no_return == info.no_return_beams);
}

void CheckTelegram(const TelegramView& t) {
  TelegramView again;
  FUZZ_CHECK(ParseTelegram(t.raw, &again) == TelegramParse::kOk);
  FUZZ_CHECK(again.command == t.command && again.data.size() == t.data.size());
  FUZZ_CHECK(t.raw.size() <= kMaxTelegramSize);

  atlas::LaserScan scan;
  ScanInfo info;
  if (DecodeMeasuredValues(t, atlas::Time{}, ScanOptions{}, &scan, &info) == ScanDecode::kOk) {
    CheckScan(scan, info);
    // The fake scanner's encoder must give back the same beams.
    const auto bytes = EncodeMeasuredValues(scan, info.unit, info.status.raw);
    FUZZ_CHECK(bytes.has_value());
    TelegramView t2;
    FUZZ_CHECK(ParseTelegram(*bytes, &t2) == TelegramParse::kOk);
    atlas::LaserScan scan2;
    ScanInfo info2;
    FUZZ_CHECK(DecodeMeasuredValues(t2, atlas::Time{}, ScanOptions{}, &scan2, &info2) ==
               ScanDecode::kOk);
    FUZZ_CHECK(scan2.ranges.size() == scan.ranges.size());
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      FUZZ_CHECK(atlas::IsReturn(scan.ranges[i]) == atlas::IsReturn(scan2.ranges[i]));
      if (atlas::IsReturn(scan.ranges[i])) FUZZ_CHECK(scan.ranges[i] == scan2.ranges[i]);
    }
  }
  (void)DecodeHostCommand(t);
  (void)DecodeModeReply(t);
  (void)DecodeVariantReply(t);
  if (auto s = DecodeStatusReply(t)) FUZZ_CHECK(s->software_version.size() <= 7);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::span<const uint8_t> in(data, size);
  TelegramView whole;
  if (ParseTelegram(in, &whole) == TelegramParse::kOk) CheckTelegram(whole);

  // The first byte chooses the chunk size the stream is cut into.
  const std::size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  StreamDecoder decoder;
  std::size_t events = 0;
  for (std::size_t at = 0; at < in.size(); at += chunk) {
    decoder.FeedAll(in.subspan(at, std::min(chunk, in.size() - at)), [&](const StreamEvent& e) {
      ++events;
      if (e.kind == StreamEventKind::kTelegram) CheckTelegram(e.telegram);
    });
  }
  const StreamCounters& c = decoder.counters();
  FUZZ_CHECK(c.bytes_fed == size);
  FUZZ_CHECK(c.bytes_fed ==
             c.telegram_bytes + c.acks + c.naks + c.garbage_bytes + decoder.buffered());
  FUZZ_CHECK(events == c.telegrams + c.acks + c.naks);
  FUZZ_CHECK(decoder.buffered() < kMaxTelegramSize);
  FUZZ_CHECK(c.bad_crc + c.bad_length <= c.garbage_bytes);
  return 0;
}
