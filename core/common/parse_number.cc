#include "core/common/parse_number.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

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

bool ParseIntegerIn(const char* text, long lo, long hi, long* value) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || v < lo || v > hi) return false;
  *value = v;
  return true;
}

}  // namespace atlas
