#pragma once
// A fixed-capacity window over a byte stream, shared by the stream decoders of the serial
// protocols (SICK LMS telegrams, P2OS packets). Bytes are appended at the back and consumed at
// the front; the storage never grows, so a decoder's memory is bounded by its capacity.
//
// Views returned by data() stay valid until the next Append() (which may move the bytes to the
// front of the storage).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace atlas {

template <std::size_t kCapacity>
class ByteWindow {
 public:
  // Appends as many bytes as fit; returns how many were taken.
  std::size_t Append(std::span<const uint8_t> bytes) {
    if (begin_ > 0 && kCapacity - end_ < bytes.size()) {
      std::memmove(storage_.data(), storage_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    const std::size_t n = std::min(bytes.size(), kCapacity - end_);
    if (n > 0) std::memcpy(storage_.data() + end_, bytes.data(), n);
    end_ += n;
    return n;
  }
  // The bytes not yet consumed.
  std::span<const uint8_t> data() const { return {storage_.data() + begin_, end_ - begin_}; }
  std::size_t size() const { return end_ - begin_; }
  // Drops n bytes (n <= size()) from the front.
  void Consume(std::size_t n) {
    begin_ += std::min(n, size());
    if (begin_ == end_) begin_ = end_ = 0;
  }
  void Clear() { begin_ = end_ = 0; }
  static constexpr std::size_t capacity() { return kCapacity; }

 private:
  std::array<uint8_t, kCapacity> storage_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
};

}  // namespace atlas
