#include "sim/fast_noise.h"

#include <cmath>
#include <numbers>

#include "core/common/normal_quantile.h"

namespace atlas::sim {

FastNoise::FastNoise(uint64_t seed) : engine_(seed) {}

const std::array<double, 4096>& FastNoise::Table() {
  static const std::array<double, 4096> table = [] {
    std::array<double, 4096> t{};
    for (int i = 0; i < 4096; ++i) t[i] = NormalQuantile((i + 0.5) / 4096.0);
    return t;
  }();
  return table;
}

}  // namespace atlas::sim
