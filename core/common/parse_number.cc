#include "core/common/parse_number.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

namespace atlas {

bool ParseNumber(std::string_view text, double* value) {
  const char* end = text.data() + text.size();
  double v = 0;
  const auto [p, ec] = std::from_chars(text.data(), end, v, std::chars_format::general);
  if (ec != std::errc() || p != end || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool ParseNumberIn(std::string_view text, double lo, double hi, double* value) {
  double v = 0;
  if (!ParseNumber(text, &v) || v < lo || v > hi) return false;
  *value = v;
  return true;
}

namespace {

template <typename T>
bool ParseWholeInteger(std::string_view text, T* value) {
  const char* end = text.data() + text.size();
  T v{};
  const auto [p, ec] = std::from_chars(text.data(), end, v, 10);
  if (ec != std::errc() || p != end) return false;
  *value = v;
  return true;
}

std::string Shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

}  // namespace

bool ParseInteger(std::string_view text, int64_t* value) { return ParseWholeInteger(text, value); }
bool ParseInteger(std::string_view text, uint64_t* value) { return ParseWholeInteger(text, value); }
bool ParseInteger(std::string_view text, int* value) { return ParseWholeInteger(text, value); }

bool ParseIntegerIn(std::string_view text, long lo, long hi, long* value) {
  int64_t v = 0;
  if (!ParseInteger(text, &v) || v < lo || v > hi) return false;
  *value = static_cast<long>(v);
  return true;
}

bool NumberArgument(std::string_view option, const char* value, double lo, double hi, double& out,
                    std::string& error) {
  if (!ParseNumberIn(value, lo, hi, &out)) {
    error = std::string(option) + " must be a number in [" + Shortest(lo) + ", " + Shortest(hi) +
            "], got '" + value + "'";
    return false;
  }
  return true;
}

bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi,
                     int64_t& out, std::string& error) {
  int64_t v = 0;
  if (!ParseInteger(value, &v) || v < lo || v > hi) {
    error = std::string(option) + " must be an integer in [" + std::to_string(lo) + ", " +
            std::to_string(hi) + "], got '" + value + "'";
    return false;
  }
  out = v;
  return true;
}

bool SeedArgument(std::string_view option, const char* value, uint64_t& out, std::string& error) {
  if (!ParseInteger(value, &out)) {
    error = std::string(option) + " must be an integer in [0, " +
            std::to_string(std::numeric_limits<uint64_t>::max()) + "], got '" + value + "'";
    return false;
  }
  return true;
}

}  // namespace atlas
