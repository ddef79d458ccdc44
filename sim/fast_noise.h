#pragma once
// Fast seeded standard-normal and uniform draws for the sensor models: one 64-bit engine draw
// yields four 16-bit numbers; a normal draw takes the top 12 bits as an index into a table of
// the standard normal's quantiles at (i + 0.5) / 4096 (exact up to that quantisation; tails end
// at about +-3.5 sigma; the table is 32 KB so that it stays in cache), a uniform draw uses all
// 16 bits. A simulated scan needs hundreds of draws; std::normal_distribution
// costs a log and a sqrt each.

#include <array>
#include <cstdint>
#include <random>

namespace atlas::sim {

class FastNoise {
 public:
  explicit FastNoise(uint64_t seed);
  // N(0, 1).
  double Normal() { return Table()[Next16() >> 4]; }
  // Uniform in [0, 1), 16-bit resolution.
  double Uniform() { return (Next16() + 0.5) * (1.0 / 65536.0); }
  // True with probability p (resolution 2^-16; p <= 0 never, p >= 1 always).
  bool Chance(double p) { return p >= 1.0 || (p > 0.0 && Next16() < p * 65536.0); }

 private:
  uint32_t Next16() {
    if (left_ == 0) {
      bits_ = engine_();
      left_ = 4;
    }
    const uint32_t v = static_cast<uint32_t>(bits_ & 0xffff);
    bits_ >>= 16;
    --left_;
    return v;
  }
  static const std::array<double, 4096>& Table();

  std::mt19937_64 engine_;
  uint64_t bits_ = 0;
  int left_ = 0;
};

}  // namespace atlas::sim
