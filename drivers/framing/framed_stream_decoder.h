#pragma once
// The part every framed-serial-protocol stream decoder shares: a bounded window of bytes,
// Feed() / FeedAll() / Reset(), and the two counters of every byte stream (bytes fed, garbage
// bytes skipped). The protocol (Derived) provides Next(), which finds the next checked frame in
// window_ and accounts for what it consumed in counters_.
//
// Derived must have: std::optional<Event> Next();
// Counters must have: uint64_t bytes_fed, garbage_bytes.

#include <cstddef>
#include <cstdint>
#include <span>

#include "drivers/framing/byte_window.h"

namespace atlas {

template <typename Derived, typename Counters, std::size_t kWindowCapacity>
class FramedStreamDecoder {
 public:
  static constexpr std::size_t kWindow = kWindowCapacity;

  // Takes as many bytes as fit in the window; returns how many (0 only when bytes is empty or
  // the window is full, which calling Next() until nullopt resolves).
  std::size_t Feed(std::span<const uint8_t> bytes) {
    const std::size_t n = window_.Append(bytes);
    counters_.bytes_fed += n;
    return n;
  }

  // Feeds all of `bytes`, calling on_event(event) for every event Next() yields.
  template <typename OnEvent>
  void FeedAll(std::span<const uint8_t> bytes, OnEvent&& on_event) {
    Derived& self = static_cast<Derived&>(*this);
    while (!bytes.empty()) {
      bytes = bytes.subspan(Feed(bytes));
      while (auto e = self.Next()) on_event(*e);
    }
  }

  // Bytes held back because they may start a frame not yet complete.
  std::size_t buffered() const { return window_.size(); }
  const Counters& counters() const { return counters_; }
  // Drops the buffered bytes (e.g. after the line was reopened at another rate), counted as
  // garbage.
  void Reset() {
    counters_.garbage_bytes += window_.size();
    window_.Clear();
  }

 protected:
  // Drops n bytes from the front of the window as garbage.
  void SkipGarbage(std::size_t n) {
    counters_.garbage_bytes += n;
    window_.Consume(n);
  }

  ByteWindow<kWindowCapacity> window_;
  Counters counters_;
};

}  // namespace atlas
