#include "drivers/sick/lms_telegram.h"

#include <cassert>

namespace atlas::sick {
namespace {

std::size_t LenField(std::span<const uint8_t> b) {
  return static_cast<std::size_t>(b[2]) | (static_cast<std::size_t>(b[3]) << 8);
}

// LEN must hold CMD, and a reply's STATUS too.
bool LenValid(uint8_t address, std::size_t len) {
  const std::size_t min_len = (address & 0x80) ? 2 : 1;
  return len >= min_len && len <= kMaxLen;
}

TelegramView ViewOf(std::span<const uint8_t> whole) {
  TelegramView v;
  v.address = whole[1];
  v.command = whole[4];
  const std::size_t len = LenField(whole);
  if (v.is_reply()) {
    v.data = whole.subspan(5, len - 2);
    v.status = whole[kHeaderSize + len - 1];
  } else {
    v.data = whole.subspan(5, len - 1);
  }
  v.raw = whole;
  return v;
}

bool CrcMatches(std::span<const uint8_t> whole) {
  const std::size_t n = whole.size();
  const uint16_t sent = static_cast<uint16_t>(whole[n - 2] | (whole[n - 1] << 8));
  return Crc16(whole.first(n - 2)) == sent;
}

}  // namespace

uint16_t Crc16(std::span<const uint8_t> bytes) {
  uint16_t crc = 0;
  uint8_t cur = 0;
  uint8_t prev = 0;
  for (uint8_t b : bytes) {
    prev = cur;
    cur = b;
    if (crc & 0x8000) {
      crc = static_cast<uint16_t>(((crc & 0x7fff) << 1) ^ 0x8005);
    } else {
      crc = static_cast<uint16_t>(crc << 1);
    }
    crc ^= static_cast<uint16_t>(cur | (prev << 8));
  }
  return crc;
}

std::vector<uint8_t> EncodeTelegram(uint8_t address, uint8_t command, std::span<const uint8_t> data,
                                    std::optional<uint8_t> status) {
  const std::size_t len = 1 + data.size() + (status ? 1 : 0);
  assert(len <= kMaxLen);
  assert(status.has_value() == ((address & 0x80) != 0));
  std::vector<uint8_t> out;
  out.reserve(kHeaderSize + len + 2);
  out.push_back(kStx);
  out.push_back(address);
  out.push_back(static_cast<uint8_t>(len & 0xFF));
  out.push_back(static_cast<uint8_t>(len >> 8));
  out.push_back(command);
  out.insert(out.end(), data.begin(), data.end());
  if (status) out.push_back(*status);
  const uint16_t crc = Crc16(out);
  out.push_back(static_cast<uint8_t>(crc & 0xFF));
  out.push_back(static_cast<uint8_t>(crc >> 8));
  return out;
}

TelegramParse ParseTelegram(std::span<const uint8_t> bytes, TelegramView* out) {
  if (bytes.size() < kHeaderSize) return TelegramParse::kTooShort;
  if (bytes[0] != kStx) return TelegramParse::kNoStx;
  const std::size_t len = LenField(bytes);
  if (!LenValid(bytes[1], len)) return TelegramParse::kBadLength;
  const std::size_t total = kHeaderSize + len + 2;
  if (bytes.size() < total) return TelegramParse::kTooShort;
  if (bytes.size() > total) return TelegramParse::kTrailingBytes;
  if (!CrcMatches(bytes)) return TelegramParse::kBadCrc;
  *out = ViewOf(bytes);
  return TelegramParse::kOk;
}

std::optional<StreamEvent> StreamDecoder::Next() {
  while (window_.size() > 0) {
    const std::span<const uint8_t> b = window_.data();
    if (b[0] == kAck || b[0] == kNak) {
      StreamEvent e;
      e.kind = b[0] == kAck ? StreamEventKind::kAck : StreamEventKind::kNak;
      ++(b[0] == kAck ? counters_.acks : counters_.naks);
      window_.Consume(1);
      return e;
    }
    if (b[0] != kStx) {
      std::size_t skip = 1;
      while (skip < b.size() && b[skip] != kStx && b[skip] != kAck && b[skip] != kNak) ++skip;
      SkipGarbage(skip);
      continue;
    }
    if (b.size() < kHeaderSize) return std::nullopt;
    const uint64_t position = counters_.bytes_fed - window_.size();
    const bool counted = position >= failed_end_;
    const std::size_t len = LenField(b);
    if (!LenValid(b[1], len)) {
      if (counted) ++counters_.bad_length;
      SkipGarbage(1);
      continue;
    }
    const std::size_t total = kHeaderSize + len + 2;
    if (b.size() < total) return std::nullopt;
    const std::span<const uint8_t> whole = b.first(total);
    if (!CrcMatches(whole)) {
      if (counted) {
        ++counters_.bad_crc;
        failed_end_ = position + total;
      }
      SkipGarbage(1);
      continue;
    }
    failed_end_ = 0;
    StreamEvent e;
    e.kind = StreamEventKind::kTelegram;
    e.telegram = ViewOf(whole);
    ++counters_.telegrams;
    counters_.telegram_bytes += total;
    window_.Consume(total);
    return e;
  }
  return std::nullopt;
}

}  // namespace atlas::sick
