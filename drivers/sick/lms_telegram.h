#pragma once
// SICK LMS 2xx telegrams (docs/devices.md, section 1): CRC16, framing and an
// incremental stream decoder. Pure: bytes in, telegram views out; no file descriptors.
//
// Frame, both directions:
//   STX(0x02) | ADDR | LEN lo | LEN hi | CMD | DATA ... | [STATUS, replies only] | CRC lo | CRC hi
// LEN counts CMD + DATA (+ STATUS) and is at most 812. A telegram is a reply (it carries a
// STATUS byte) when ADDR has bit 7 set (scanner -> host is 0x80). Before a reply the scanner
// sends one ACK (0x06) or NAK (0x15) byte.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "drivers/framing/framed_stream_decoder.h"

namespace atlas::sick {

inline constexpr uint8_t kStx = 0x02;
inline constexpr uint8_t kAck = 0x06;
inline constexpr uint8_t kNak = 0x15;
inline constexpr uint8_t kHostAddress = 0x00;
inline constexpr uint8_t kScannerAddress = 0x80;
inline constexpr std::size_t kMaxLen = 812;    // LEN field maximum
inline constexpr std::size_t kHeaderSize = 4;  // STX ADDR LEN(2)
inline constexpr std::size_t kMaxTelegramSize = kHeaderSize + kMaxLen + 2;

// The spec's CRC16 over `bytes` (every byte from STX to the last one before the CRC).
uint16_t Crc16(std::span<const uint8_t> bytes);

// One checked telegram. Spans point into the decoder's window (or the caller's buffer) and stay
// valid until the next Feed() of the decoder that produced them.
struct TelegramView {
  uint8_t address = 0;
  uint8_t command = 0;
  std::span<const uint8_t> data;  // between CMD and STATUS (or CRC)
  std::optional<uint8_t> status;  // replies only (ADDR bit 7 set and LEN >= 2)
  std::span<const uint8_t> raw;   // the whole telegram, STX to CRC hi
  bool is_reply() const { return (address & 0x80) != 0; }
};

// Whole telegram, CRC included. `status` must be given for replies (address bit 7 set) and
// omitted for host commands. data.size() + 1 (+ 1) must not exceed kMaxLen (asserted).
std::vector<uint8_t> EncodeTelegram(uint8_t address, uint8_t command, std::span<const uint8_t> data,
                                    std::optional<uint8_t> status = std::nullopt);

enum class TelegramParse { kOk, kTooShort, kNoStx, kBadLength, kBadCrc, kTrailingBytes };
// Checks exactly one whole telegram in `bytes` (no ACK byte in front).
TelegramParse ParseTelegram(std::span<const uint8_t> bytes, TelegramView* out);

// What the stream decoder found: a checked telegram, or a lone ACK / NAK byte. Every 0x06 /
// 0x15 outside a checked telegram is reported, also one inside garbage, so a driver should act
// on them only while it waits for the answer to a command.
enum class StreamEventKind { kTelegram, kAck, kNak };
struct StreamEvent {
  StreamEventKind kind = StreamEventKind::kTelegram;
  TelegramView telegram;  // kTelegram only
};

// Counters of the stream decoder. Every byte fed is accounted exactly once:
//   bytes_fed == telegram_bytes + acks + naks + garbage_bytes + buffered()
// A rejected frame start (bad length or bad CRC) counts one event in bad_length / bad_crc,
// and its STX byte counts as garbage; decoding resumes at the next byte, so a real telegram
// hidden behind a false STX (or behind a telegram cut short by lost bytes) is still found.
// Frame starts inside the span of a telegram that failed its CRC (0x02 bytes in its range
// data) are not counted again: one damaged telegram is one bad_crc.
struct StreamCounters {
  uint64_t bytes_fed = 0;
  uint64_t telegrams = 0;
  uint64_t telegram_bytes = 0;
  uint64_t acks = 0;
  uint64_t naks = 0;
  uint64_t bad_crc = 0;
  uint64_t bad_length = 0;  // LEN == 0, LEN > 812, or a reply too short for its STATUS
  uint64_t garbage_bytes = 0;
};

// Incremental decoder over a byte stream cut at arbitrary places. Resynchronises on STX,
// checks LEN <= 812 and the CRC. Memory is bounded by a fixed window. From the base:
// Feed(bytes) -> bytes taken, FeedAll(bytes, on_event), buffered(), counters(), Reset().
//
//   decoder.FeedAll(bytes, [&](const StreamEvent& e) { ... });
// or, without a callback:
//   while (!bytes.empty()) {
//     bytes = bytes.subspan(decoder.Feed(bytes));
//     while (auto e = decoder.Next()) { ... }
//   }
class StreamDecoder
    : public FramedStreamDecoder<StreamDecoder, StreamCounters, 2 * kMaxTelegramSize> {
 public:
  // The next event, or nullopt if more bytes are needed. The event's spans stay valid until the
  // next Feed().
  std::optional<StreamEvent> Next();

 private:
  // Stream position just past the last counted telegram that failed its CRC.
  uint64_t failed_end_ = 0;
};

}  // namespace atlas::sick
