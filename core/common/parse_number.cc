#include "core/common/parse_number.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace atlas {

bool ParseNumber(const char* text, double* value) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool ParseNumberIn(const char* text, double lo, double hi, double* value) {
  double v = 0;
  if (!ParseNumber(text, &v) || v < lo || v > hi) return false;
  *value = v;
  return true;
}

namespace {

template <typename T>
bool ParseWholeInteger(const char* text, T* value) {
  const char* end = text + std::strlen(text);
  T v{};
  const auto [p, ec] = std::from_chars(text, end, v, 10);
  if (text == end || ec != std::errc() || p != end) return false;
  *value = v;
  return true;
}

}  // namespace

bool ParseInteger(const char* text, int64_t* value) { return ParseWholeInteger(text, value); }
bool ParseInteger(const char* text, uint64_t* value) { return ParseWholeInteger(text, value); }

bool ParseIntegerIn(const char* text, long lo, long hi, long* value) {
  int64_t v = 0;
  if (!ParseInteger(text, &v) || v < lo || v > hi) return false;
  *value = static_cast<long>(v);
  return true;
}

}  // namespace atlas
