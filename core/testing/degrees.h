#pragma once
// Angles in tests, written in degrees: 30 * kDeg is 30 degrees in radians.

#include <numbers>

namespace atlas {

inline constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace atlas
