#pragma once
// Strict parsing of the numbers given to the tools' options: the whole text must be the number
// (no trailing characters, not empty), finite, and within [lo, hi]. atof / atoi read "abc" as 0
// and "1.5" as 1; a value out of any range (1e300, nan) can overflow a later conversion.

#include <cstdint>

namespace atlas {

// A finite floating-point number (strtod's syntax), the whole text.
bool ParseNumber(const char* text, double* value);
// ParseNumber within [lo, hi].
bool ParseNumberIn(const char* text, double lo, double hi, double* value);
// A decimal integer, the whole text: digits with an optional leading '-' (std::from_chars: no
// '+', spaces, fraction or exponent, so "1.5" and "1e3" are not integers); false when it does
// not fit the type.
bool ParseInteger(const char* text, int64_t* value);
bool ParseInteger(const char* text, uint64_t* value);
// ParseInteger within [lo, hi].
bool ParseIntegerIn(const char* text, long lo, long hi, long* value);

}  // namespace atlas
