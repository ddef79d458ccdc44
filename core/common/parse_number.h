#pragma once
// Strict parsing of the numbers given to the tools' options: the whole text must be the number
// (no trailing characters, not empty), finite, and within [lo, hi]. atof / atoi read "abc" as 0
// and "1.5" as 1; a value out of any range (1e300, nan) can overflow a later conversion.

namespace atlas {

// A finite floating-point number (strtod's syntax), the whole text.
bool ParseNumber(const char* text, double* value);
// ParseNumber within [lo, hi].
bool ParseNumberIn(const char* text, double lo, double hi, double* value);
// A decimal integer within [lo, hi], the whole text ("1.5", "1e3" are not integers).
bool ParseIntegerIn(const char* text, long lo, long hi, long* value);

}  // namespace atlas
