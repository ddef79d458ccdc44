#pragma once
// Pioneer P2OS packets (docs/devices.md, section 3): checksum, framing and an
// incremental stream decoder. Pure: bytes in, packet views out; no file descriptors.
//
//   0xFA 0xFB | N | payload (N - 2 bytes) | checksum hi | checksum lo
// Checksum: the payload as big-endian 16-bit words summed to 16 bits; an odd last byte is
// XORed in. The same framing carries host commands and controller packets (SIPs, SYNC echoes).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "drivers/framing/framed_stream_decoder.h"

namespace atlas::p2os {

inline constexpr uint8_t kHeader0 = 0xFA;
inline constexpr uint8_t kHeader1 = 0xFB;
inline constexpr std::size_t kMinCount = 3;    // N: one payload byte + checksum
inline constexpr std::size_t kMaxCount = 255;  // N is one byte
inline constexpr std::size_t kMaxPayload = kMaxCount - 2;
inline constexpr std::size_t kMaxPacketSize = 3 + kMaxCount;

uint16_t Checksum(std::span<const uint8_t> payload);

// Whole packet. payload must have 1..253 bytes (asserted).
std::vector<uint8_t> EncodePacket(std::span<const uint8_t> payload);

struct PacketView {
  std::span<const uint8_t> payload;  // never empty
  std::span<const uint8_t> raw;      // FA FB ... checksum lo
};

enum class PacketParse { kOk, kTooShort, kNoHeader, kBadCount, kBadChecksum, kTrailingBytes };
// Checks exactly one whole packet in `bytes`.
PacketParse ParsePacket(std::span<const uint8_t> bytes, PacketView* out);

// Every byte fed is accounted exactly once:
//   bytes_fed == packet_bytes + garbage_bytes + buffered()
// A rejected packet start (N < 3 or a bad checksum) counts one event in bad_count /
// bad_checksum and its two header bytes as garbage; decoding resumes after them.
struct StreamCounters {
  uint64_t bytes_fed = 0;
  uint64_t packets = 0;
  uint64_t packet_bytes = 0;
  uint64_t bad_checksum = 0;
  uint64_t bad_count = 0;
  uint64_t garbage_bytes = 0;
};

// Incremental decoder over a byte stream cut at arbitrary places; resynchronises on FA FB.
// Memory is bounded by a fixed window. From the base: Feed(bytes) -> bytes taken,
// FeedAll(bytes, on_packet), buffered(), counters(), Reset().
//   decoder.FeedAll(bytes, [&](const PacketView& p) { ... });
class StreamDecoder
    : public FramedStreamDecoder<StreamDecoder, StreamCounters, 2 * kMaxPacketSize> {
 public:
  // The next checked packet, or nullopt when more bytes are needed. Spans valid until Feed().
  std::optional<PacketView> Next();
};

}  // namespace atlas::p2os
