#include "drivers/sick/lms_telegram.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/sick/lms_messages.h"

namespace atlas::sick {
namespace {

// "02 00 01" -> {0x02, 0x00, 0x01}.
std::vector<uint8_t> Hex(std::string_view s) {
  std::istringstream in{std::string(s)};
  std::vector<uint8_t> out;
  unsigned v = 0;
  while (in >> std::hex >> v) out.push_back(static_cast<uint8_t>(v));
  return out;
}

// The spec's test vectors, whole telegrams with CRC.
const char* const kSpecVectors[] = {
    "02 00 01 00 31 15 12",        // status request
    "02 00 02 00 20 48 58 08",     // 500 kbaud
    "02 00 02 00 20 42 52 08",     // 9600 baud
    "02 00 02 00 30 01 31 18",     // request one scan
    "02 00 02 00 20 24 34 08",     // continuous
    "02 00 02 00 20 25 35 08",     // on request
    "02 80 03 00 A0 00 10 16 0A",  // mode reply after its ACK
};

TEST(LmsCrc, MatchesEverySpecVector) {
  for (const char* hex : kSpecVectors) {
    const std::vector<uint8_t> t = Hex(hex);
    const uint16_t sent = static_cast<uint16_t>(t[t.size() - 2] | (t[t.size() - 1] << 8));
    EXPECT_EQ(Crc16(std::span(t).first(t.size() - 2)), sent) << hex;
  }
}

TEST(LmsCrc, EmptyAndSingleByte) {
  EXPECT_EQ(Crc16({}), 0);
  const uint8_t stx = kStx;
  EXPECT_EQ(Crc16(std::span(&stx, 1)), 0x0002);
}

TEST(LmsTelegram, EncodeGivesSpecBytes) {
  EXPECT_EQ(EncodeTelegram(kHostAddress, 0x31, {}), Hex(kSpecVectors[0]));
  const std::vector<uint8_t> data{0x00};
  EXPECT_EQ(EncodeTelegram(kScannerAddress, 0xA0, data, 0x10), Hex(kSpecVectors[6]));
}

TEST(LmsTelegram, ParsesSpecVectors) {
  for (const char* hex : kSpecVectors) {
    const std::vector<uint8_t> t = Hex(hex);
    TelegramView v;
    ASSERT_EQ(ParseTelegram(t, &v), TelegramParse::kOk) << hex;
    EXPECT_EQ(v.command, t[4]);
    EXPECT_EQ(v.raw.size(), t.size());
  }
  const std::vector<uint8_t> reply = Hex(kSpecVectors[6]);
  TelegramView v;
  ASSERT_EQ(ParseTelegram(reply, &v), TelegramParse::kOk);
  EXPECT_TRUE(v.is_reply());
  ASSERT_TRUE(v.status.has_value());
  EXPECT_EQ(*v.status, 0x10);
  ASSERT_EQ(v.data.size(), 1u);
  EXPECT_EQ(v.data[0], 0x00);
  const std::vector<uint8_t> request = Hex(kSpecVectors[3]);
  ASSERT_EQ(ParseTelegram(request, &v), TelegramParse::kOk);
  EXPECT_FALSE(v.status.has_value());
  ASSERT_EQ(v.data.size(), 1u);
  EXPECT_EQ(v.data[0], 0x01);
}

TEST(LmsTelegram, ParseRejectsDamage) {
  TelegramView v;
  std::vector<uint8_t> t = Hex(kSpecVectors[1]);
  t[5] ^= 0x01;
  EXPECT_EQ(ParseTelegram(t, &v), TelegramParse::kBadCrc);
  EXPECT_EQ(ParseTelegram(Hex("02 00 02"), &v), TelegramParse::kTooShort);
  EXPECT_EQ(ParseTelegram(Hex("03 00 01 00 31 15 12"), &v), TelegramParse::kNoStx);
  EXPECT_EQ(ParseTelegram(Hex("02 00 00 00 31 15 12"), &v), TelegramParse::kBadLength);
  EXPECT_EQ(ParseTelegram(Hex("02 00 2D 03 31 15 12"), &v), TelegramParse::kBadLength);  // 813
  EXPECT_EQ(ParseTelegram(Hex("02 80 01 00 A0 00 00"), &v),
            TelegramParse::kBadLength);  // no STATUS
  std::vector<uint8_t> longer = Hex(kSpecVectors[0]);
  longer.push_back(0x00);
  EXPECT_EQ(ParseTelegram(longer, &v), TelegramParse::kTrailingBytes);
}

struct Collected {
  std::vector<StreamEventKind> kinds;
  std::vector<std::vector<uint8_t>> telegrams;
};

Collected FeedInChunks(StreamDecoder* d, const std::vector<uint8_t>& bytes, std::size_t chunk) {
  Collected c;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    const std::size_t n = std::min(chunk, bytes.size() - at);
    d->FeedAll(std::span(bytes).subspan(at, n), [&](const StreamEvent& e) {
      c.kinds.push_back(e.kind);
      if (e.kind == StreamEventKind::kTelegram) {
        c.telegrams.emplace_back(e.telegram.raw.begin(), e.telegram.raw.end());
      }
    });
  }
  return c;
}

void ExpectBytesAccounted(const StreamDecoder& d) {
  const StreamCounters& c = d.counters();
  EXPECT_EQ(c.bytes_fed, c.telegram_bytes + c.acks + c.naks + c.garbage_bytes + d.buffered());
}

TEST(LmsStream, AllSpecVectorsAtEveryChunkSize) {
  std::vector<uint8_t> stream;
  for (std::size_t i = 0; i < std::size(kSpecVectors); ++i) {
    if (i == 6) stream.push_back(kAck);  // the mode reply comes after its ACK
    const std::vector<uint8_t> t = Hex(kSpecVectors[i]);
    stream.insert(stream.end(), t.begin(), t.end());
  }
  for (std::size_t chunk = 1; chunk <= stream.size(); ++chunk) {
    StreamDecoder d;
    const Collected c = FeedInChunks(&d, stream, chunk);
    ASSERT_EQ(c.telegrams.size(), 7u) << "chunk " << chunk;
    for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(c.telegrams[i], Hex(kSpecVectors[i]));
    ASSERT_EQ(c.kinds.size(), 8u);
    EXPECT_EQ(c.kinds[6], StreamEventKind::kAck);
    EXPECT_EQ(d.counters().garbage_bytes, 0u);
    EXPECT_EQ(d.buffered(), 0u);
    ExpectBytesAccounted(d);
  }
}

TEST(LmsStream, SkipsGarbageAndCountsIt) {
  std::vector<uint8_t> stream = Hex("41 42 43 FF");
  const std::vector<uint8_t> t = Hex(kSpecVectors[0]);
  stream.insert(stream.end(), t.begin(), t.end());
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, stream.size());
  ASSERT_EQ(c.telegrams.size(), 1u);
  EXPECT_EQ(d.counters().garbage_bytes, 4u);
  ExpectBytesAccounted(d);
}

TEST(LmsStream, BadCrcIsCountedAndTheNextTelegramFound) {
  std::vector<uint8_t> bad = Hex(kSpecVectors[1]);
  bad[bad.size() - 1] ^= 0xFF;
  std::vector<uint8_t> stream = bad;
  const std::vector<uint8_t> good = Hex(kSpecVectors[2]);
  stream.insert(stream.end(), good.begin(), good.end());
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, 3);
  ASSERT_EQ(c.telegrams.size(), 1u);
  EXPECT_EQ(c.telegrams[0], good);
  EXPECT_EQ(d.counters().bad_crc, 1u);
  EXPECT_EQ(d.counters().garbage_bytes, bad.size());
  ExpectBytesAccounted(d);
}

TEST(LmsStream, BadLengthIsCountedAndResynchronises) {
  // LEN 0x0400 > 812, then a good telegram.
  std::vector<uint8_t> stream = Hex("02 80 00 04 B0");
  const std::vector<uint8_t> good = Hex(kSpecVectors[6]);
  stream.insert(stream.end(), good.begin(), good.end());
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, 1);
  ASSERT_EQ(c.telegrams.size(), 1u);
  EXPECT_EQ(c.telegrams[0], good);
  EXPECT_EQ(d.counters().bad_length, 1u);
  ExpectBytesAccounted(d);
}

TEST(LmsStream, FalseStxWithPlausibleLengthDoesNotHideTheRealTelegram) {
  // A false STX announcing 10 bytes swallows the real telegram's start; its CRC fails and the
  // decoder rescans from the byte after it.
  std::vector<uint8_t> stream = Hex("02 00 0A 00");
  const std::vector<uint8_t> good = Hex(kSpecVectors[3]);
  stream.insert(stream.end(), good.begin(), good.end());
  stream.insert(stream.end(), good.begin(), good.end());
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, 1);
  ASSERT_EQ(c.telegrams.size(), 2u);
  EXPECT_EQ(d.counters().bad_crc, 1u);
  EXPECT_EQ(d.counters().garbage_bytes, 4u);
  ExpectBytesAccounted(d);
}

TEST(LmsStream, OneDamagedTelegramCountsOnceWhateverItsDataHolds) {
  // Range data full of 0x02 bytes with plausible lengths behind them: each damaged telegram
  // is one bad_crc, not one per false start inside it.
  std::vector<uint8_t> data;
  for (int i = 0; i < 60; ++i) {
    const uint8_t chunk[] = {0x02, 0x80, 0x05, 0x00, 0x02, 0x00, 0x01, 0x00};
    data.insert(data.end(), std::begin(chunk), std::end(chunk));
  }
  std::vector<uint8_t> stream;
  for (int i = 0; i < 50; ++i) {
    std::vector<uint8_t> t = EncodeTelegram(0x80, 0xB0, data, uint8_t{0x10});
    t[t.size() - 1] ^= 0x5A;
    stream.insert(stream.end(), t.begin(), t.end());
  }
  const std::vector<uint8_t> good = EncodeTelegram(0x80, 0xB0, data, uint8_t{0x10});
  stream.insert(stream.end(), good.begin(), good.end());
  for (std::size_t chunk : {std::size_t{1}, std::size_t{7}, stream.size()}) {
    StreamDecoder d;
    const Collected c = FeedInChunks(&d, stream, chunk);
    ASSERT_EQ(c.telegrams.size(), 1u) << "chunk " << chunk;
    EXPECT_EQ(c.telegrams[0], good);
    EXPECT_EQ(d.counters().bad_crc, 50u) << "chunk " << chunk;
    EXPECT_EQ(d.counters().bad_length, 0u) << "chunk " << chunk;
    ExpectBytesAccounted(d);
  }
}

TEST(LmsStream, TelegramCutShortDoesNotHideTheNextOne) {
  // A telegram that lost bytes on the line fails its CRC; the next telegram, which starts inside
  // the span the damaged one announced, is still found.
  std::vector<uint8_t> cut = Hex(kSpecVectors[6]);
  cut.erase(cut.begin() + 5, cut.begin() + 7);
  const std::vector<uint8_t> good = Hex(kSpecVectors[3]);
  std::vector<uint8_t> stream = cut;
  stream.insert(stream.end(), good.begin(), good.end());
  stream.insert(stream.end(), good.begin(), good.end());
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, 1);
  ASSERT_EQ(c.telegrams.size(), 2u);
  EXPECT_EQ(d.counters().bad_crc, 1u);
  ExpectBytesAccounted(d);
}

TEST(LmsStream, AckAndNakBytesAreEvents) {
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, Hex("06 15 06"), 1);
  ASSERT_EQ(c.kinds.size(), 3u);
  EXPECT_EQ(c.kinds[0], StreamEventKind::kAck);
  EXPECT_EQ(c.kinds[1], StreamEventKind::kNak);
  EXPECT_EQ(d.counters().acks, 2u);
  EXPECT_EQ(d.counters().naks, 1u);
}

TEST(LmsStream, TruncatedTelegramWaitsThenResetCountsItAsGarbage) {
  const std::vector<uint8_t> t = Hex(kSpecVectors[1]);
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, std::vector<uint8_t>(t.begin(), t.end() - 2), 4);
  EXPECT_TRUE(c.kinds.empty());
  EXPECT_EQ(d.buffered(), t.size() - 2);
  d.Reset();
  EXPECT_EQ(d.buffered(), 0u);
  EXPECT_EQ(d.counters().garbage_bytes, t.size() - 2);
  ExpectBytesAccounted(d);
}

TEST(LmsStream, LargeInputBeyondTheWindowIsDecodedWhole) {
  LaserScan scan;
  scan.ranges.assign(361, 1.5f);
  const std::vector<uint8_t> t = *EncodeMeasuredValues(scan, Unit::kMillimetre, 0x10);
  std::vector<uint8_t> stream;
  for (int i = 0; i < 20; ++i) stream.insert(stream.end(), t.begin(), t.end());
  ASSERT_GT(stream.size(), StreamDecoder::kWindow);
  StreamDecoder d;
  const Collected c = FeedInChunks(&d, stream, stream.size());
  EXPECT_EQ(c.telegrams.size(), 20u);
  EXPECT_EQ(d.counters().garbage_bytes, 0u);
  ExpectBytesAccounted(d);
}

}  // namespace
}  // namespace atlas::sick
