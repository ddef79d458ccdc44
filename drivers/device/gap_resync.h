#pragma once
// Truncation handling shared by the serial readers (LMS telegrams, P2OS packets). A stream
// decoder holding a partial frame while the line stays silent for a gap has seen a truncated
// frame (or a false frame start). Dropping all it holds would also drop any real frame that a
// false start swallowed, so instead the frame start is abandoned: the decoder is reset and the
// bytes it held, minus that first byte, are fed again. The reader keeps the last bytes it fed
// (a ring as large as the decoder's window) to be able to do that.
//
// Counting: Reset() counts the held bytes as garbage and refeeding counts them again; the
// `double_counted` total says how many bytes to subtract from the decoder's bytes_fed and
// garbage_bytes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace atlas {

template <std::size_t kCapacity>
class GapResync {
 public:
  void Record(std::span<const uint8_t> bytes) {
    for (uint8_t b : bytes) {
      ring_[head_] = b;
      head_ = (head_ + 1) % kCapacity;
    }
    total_ += bytes.size();
  }

  // Abandons the decoder's partial frame; `on_event` receives what refeeding finds. Returns
  // false when there was nothing held.
  template <typename Decoder, typename OnEvent>
  bool Resync(Decoder& decoder, OnEvent&& on_event) {
    const std::size_t held = decoder.buffered();
    if (held == 0) return false;
    std::array<uint8_t, kCapacity> copy;
    const std::size_t n = std::min<std::size_t>({held, kCapacity, total_});
    for (std::size_t i = 0; i < n; ++i) copy[i] = ring_[(head_ + kCapacity - n + i) % kCapacity];
    decoder.Reset();
    if (n > 1) {
      double_counted_ += n - 1;
      decoder.FeedAll(std::span<const uint8_t>(copy.data() + 1, n - 1), on_event);
    }
    return true;
  }

  void Clear() { total_ = 0; }
  uint64_t double_counted() const { return double_counted_; }

 private:
  std::array<uint8_t, kCapacity> ring_{};
  std::size_t head_ = 0;
  uint64_t total_ = 0;
  uint64_t double_counted_ = 0;
};

}  // namespace atlas
