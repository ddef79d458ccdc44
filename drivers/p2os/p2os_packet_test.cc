#include "drivers/p2os/p2os_packet.h"

#include <gtest/gtest.h>

#include <vector>

#include "drivers/p2os/p2os_messages.h"

namespace atlas::p2os {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(P2osChecksum, EvenOddAndOverflow) {
  EXPECT_EQ(Checksum(Bytes{0x04, 0x3B, 0x01, 0x00}), 0x053B);   // the ENABLE example
  EXPECT_EQ(Checksum(Bytes{0x01, 0x02, 0x03}), 0x0102 ^ 0x03);  // odd: last byte XORed
  EXPECT_EQ(Checksum(Bytes{0xFF, 0xFF, 0xFF, 0xFF}), 0xFFFE);   // kept to 16 bits
  EXPECT_EQ(Checksum(Bytes{0x00}), 0x0000);
  EXPECT_EQ(Checksum(Bytes{0x02}), 0x0002);
}

TEST(P2osPacket, SpecExamples) {
  EXPECT_EQ(EncodeCommandInt(kCmdEnable, 1),
            (Bytes{0xFA, 0xFB, 0x06, 0x04, 0x3B, 0x01, 0x00, 0x05, 0x3B}));
  EXPECT_EQ(EncodeSync(0), (Bytes{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  EXPECT_EQ(EncodeSync(1), (Bytes{0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01}));
  EXPECT_EQ(EncodeSync(2), (Bytes{0xFA, 0xFB, 0x03, 0x02, 0x00, 0x02}));
}

TEST(P2osPacket, ParseAndRejections) {
  PacketView v;
  const Bytes enable{0xFA, 0xFB, 0x06, 0x04, 0x3B, 0x01, 0x00, 0x05, 0x3B};
  ASSERT_EQ(ParsePacket(enable, &v), PacketParse::kOk);
  EXPECT_EQ(Bytes(v.payload.begin(), v.payload.end()), (Bytes{0x04, 0x3B, 0x01, 0x00}));
  Bytes bad = enable;
  bad[8] ^= 1;
  EXPECT_EQ(ParsePacket(bad, &v), PacketParse::kBadChecksum);
  EXPECT_EQ(ParsePacket(Bytes{0xFA, 0xFB}, &v), PacketParse::kTooShort);
  EXPECT_EQ(ParsePacket(Bytes{0xFA, 0xFC, 0x03, 0, 0, 0}, &v), PacketParse::kNoHeader);
  EXPECT_EQ(ParsePacket(Bytes{0xFA, 0xFB, 0x02, 0, 0}, &v), PacketParse::kBadCount);
  Bytes longer = enable;
  longer.push_back(0);
  EXPECT_EQ(ParsePacket(longer, &v), PacketParse::kTrailingBytes);
}

struct Result {
  std::vector<Bytes> packets;
};

Result FeedInChunks(StreamDecoder* d, const Bytes& bytes, std::size_t chunk) {
  Result r;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    d->FeedAll(std::span(bytes).subspan(at, std::min(chunk, bytes.size() - at)),
               [&](const PacketView& p) { r.packets.emplace_back(p.raw.begin(), p.raw.end()); });
  }
  return r;
}

void ExpectBytesAccounted(const StreamDecoder& d) {
  const StreamCounters& c = d.counters();
  EXPECT_EQ(c.bytes_fed, c.packet_bytes + c.garbage_bytes + d.buffered());
}

TEST(P2osStream, ResynchronisesOnHeaderAtEveryChunkSize) {
  const Bytes a = EncodeSync(2);
  const Bytes b = EncodeCommandInt(kCmdSonar, 1);
  Bytes bad = EncodeCommandInt(kCmdEnable, 1);
  bad.back() ^= 0x10;
  Bytes stream{0x00, 0xFA, 0x13, 0xFB};  // garbage, including a lone FA
  stream.insert(stream.end(), a.begin(), a.end());
  stream.insert(stream.end(), bad.begin(), bad.end());
  stream.insert(stream.end(), {0xFA, 0xFB, 0x01});  // N < 3
  stream.insert(stream.end(), b.begin(), b.end());
  for (std::size_t chunk = 1; chunk <= stream.size(); ++chunk) {
    StreamDecoder d;
    const Result r = FeedInChunks(&d, stream, chunk);
    ASSERT_EQ(r.packets.size(), 2u) << chunk;
    EXPECT_EQ(r.packets[0], a);
    EXPECT_EQ(r.packets[1], b);
    EXPECT_EQ(d.counters().bad_checksum, 1u);
    EXPECT_EQ(d.counters().bad_count, 1u);
    EXPECT_EQ(d.counters().garbage_bytes, 4u + bad.size() + 3u);
    EXPECT_EQ(d.buffered(), 0u);
    ExpectBytesAccounted(d);
  }
}

TEST(P2osStream, FalseHeaderWithLongCountDoesNotHideRealPackets) {
  Bytes stream{0xFA, 0xFB, 0xC8};  // announces 200 bytes
  for (int i = 0; i < 40; ++i) {
    const Bytes p = EncodePulse();
    stream.insert(stream.end(), p.begin(), p.end());
  }
  StreamDecoder d;
  const Result r = FeedInChunks(&d, stream, 7);
  EXPECT_EQ(r.packets.size(), 40u);
  EXPECT_EQ(d.counters().bad_checksum, 1u);
  ExpectBytesAccounted(d);
}

TEST(P2osStream, TruncatedPacketWaitsAndResetDropsIt) {
  const Bytes p = EncodeCommandInt(kCmdEnable, 1);
  StreamDecoder d;
  EXPECT_TRUE(FeedInChunks(&d, Bytes(p.begin(), p.end() - 1), 2).packets.empty());
  EXPECT_EQ(d.buffered(), p.size() - 1);
  d.Reset();
  EXPECT_EQ(d.counters().garbage_bytes, p.size() - 1);
  ExpectBytesAccounted(d);
}

}  // namespace
}  // namespace atlas::p2os
