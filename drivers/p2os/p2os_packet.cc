#include "drivers/p2os/p2os_packet.h"

#include <cassert>

namespace atlas::p2os {
namespace {

bool ChecksumMatches(std::span<const uint8_t> whole) {
  const std::size_t n = whole.size();
  const uint16_t sent = static_cast<uint16_t>((whole[n - 2] << 8) | whole[n - 1]);
  return Checksum(whole.subspan(3, n - 5)) == sent;
}

PacketView ViewOf(std::span<const uint8_t> whole) {
  return PacketView{whole.subspan(3, whole.size() - 5), whole};
}

}  // namespace

uint16_t Checksum(std::span<const uint8_t> payload) {
  uint16_t sum = 0;
  std::size_t i = 0;
  for (; i + 1 < payload.size(); i += 2) {
    sum = static_cast<uint16_t>(sum + ((payload[i] << 8) | payload[i + 1]));
  }
  if (i < payload.size()) sum ^= payload[i];
  return sum;
}

std::vector<uint8_t> EncodePacket(std::span<const uint8_t> payload) {
  assert(!payload.empty() && payload.size() <= kMaxPayload);
  std::vector<uint8_t> out;
  out.reserve(payload.size() + 5);
  out.push_back(kHeader0);
  out.push_back(kHeader1);
  out.push_back(static_cast<uint8_t>(payload.size() + 2));
  out.insert(out.end(), payload.begin(), payload.end());
  const uint16_t sum = Checksum(payload);
  out.push_back(static_cast<uint8_t>(sum >> 8));
  out.push_back(static_cast<uint8_t>(sum & 0xFF));
  return out;
}

PacketParse ParsePacket(std::span<const uint8_t> bytes, PacketView* out) {
  if (bytes.size() < 3) return PacketParse::kTooShort;
  if (bytes[0] != kHeader0 || bytes[1] != kHeader1) return PacketParse::kNoHeader;
  const std::size_t count = bytes[2];
  if (count < kMinCount) return PacketParse::kBadCount;
  const std::size_t total = 3 + count;
  if (bytes.size() < total) return PacketParse::kTooShort;
  if (bytes.size() > total) return PacketParse::kTrailingBytes;
  if (!ChecksumMatches(bytes)) return PacketParse::kBadChecksum;
  *out = ViewOf(bytes);
  return PacketParse::kOk;
}

std::optional<PacketView> StreamDecoder::Next() {
  while (window_.size() > 0) {
    const std::span<const uint8_t> b = window_.data();
    if (b[0] != kHeader0 || (b.size() >= 2 && b[1] != kHeader1)) {
      std::size_t skip = 1;
      while (skip < b.size() && b[skip] != kHeader0) ++skip;
      SkipGarbage(skip);
      continue;
    }
    if (b.size() < 3) return std::nullopt;
    const std::size_t count = b[2];
    if (count < kMinCount) {
      ++counters_.bad_count;
      SkipGarbage(2);
      continue;
    }
    const std::size_t total = 3 + count;
    if (b.size() < total) return std::nullopt;
    const std::span<const uint8_t> whole = b.first(total);
    if (!ChecksumMatches(whole)) {
      ++counters_.bad_checksum;
      SkipGarbage(2);
      continue;
    }
    ++counters_.packets;
    counters_.packet_bytes += total;
    window_.Consume(total);
    return ViewOf(whole);
  }
  return std::nullopt;
}

}  // namespace atlas::p2os
