// libFuzzer target: random bytes through the P2OS stream decoder (cut into chunks whose sizes
// come from the input), every packet through the SIP, SYNC and command decoders, and each
// decoded SIP back through the encoder. Invariants are checked with traps.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "drivers/framing/fuzz_check.h"
#include "drivers/p2os/p2os_messages.h"
#include "drivers/p2os/p2os_packet.h"

namespace {

using namespace atlas::p2os;

const SonarOptions& Options() {
  static const SonarOptions options;
  return options;
}

void CheckPacket(const PacketView& p) {
  PacketView again;
  FUZZ_CHECK(ParsePacket(p.raw, &again) == PacketParse::kOk);
  FUZZ_CHECK(!p.payload.empty() && p.payload.size() <= kMaxPayload);

  StandardSip sip;
  if (DecodeStandardSip(p, &sip) == SipDecode::kOk) {
    const auto bytes = EncodeStandardSip(sip);
    FUZZ_CHECK(bytes.has_value());
    PacketView p2;
    FUZZ_CHECK(ParsePacket(*bytes, &p2) == PacketParse::kOk);
    StandardSip sip2;
    FUZZ_CHECK(DecodeStandardSip(p2, &sip2) == SipDecode::kOk);
    FUZZ_CHECK(sip2 == sip);

    atlas::SonarReading reading;
    const SonarConversion c = ToSonarReading(sip, atlas::Time{}, Options(), &reading);
    FUZZ_CHECK(c.returns + c.unknown_transducer == static_cast<int>(sip.sonars.size()));
    FUZZ_CHECK(static_cast<int>(reading.returns.size()) == c.returns);
    for (const atlas::SonarReturn& r : reading.returns) {
      FUZZ_CHECK(r.transducer >= 0 && r.transducer < static_cast<int>(Options().ring.size()));
      FUZZ_CHECK(r.range == atlas::kNoReturn || (r.range >= 0.0f && std::isfinite(r.range)));
    }
  }
  if (auto id = DecodeSync2Reply(p)) {
    FUZZ_CHECK(id->name.size() + id->robot_class.size() + id->subclass.size() < p.payload.size());
  }
  (void)SyncEcho(p);
  if (auto cmd = DecodeHostCommand(p)) {
    if (cmd->argument) FUZZ_CHECK(std::abs(*cmd->argument) <= 0xFFFF);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::span<const uint8_t> in(data, size);
  PacketView whole;
  if (ParsePacket(in, &whole) == PacketParse::kOk) CheckPacket(whole);

  const std::size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  StreamDecoder decoder;
  std::size_t packets = 0;
  for (std::size_t at = 0; at < in.size(); at += chunk) {
    decoder.FeedAll(in.subspan(at, std::min(chunk, in.size() - at)), [&](const PacketView& p) {
      ++packets;
      CheckPacket(p);
    });
  }
  const StreamCounters& c = decoder.counters();
  FUZZ_CHECK(c.bytes_fed == size);
  FUZZ_CHECK(c.bytes_fed == c.packet_bytes + c.garbage_bytes + decoder.buffered());
  FUZZ_CHECK(packets == c.packets);
  FUZZ_CHECK(decoder.buffered() < kMaxPacketSize);
  FUZZ_CHECK(2 * (c.bad_checksum + c.bad_count) <= c.garbage_bytes);
  return 0;
}
