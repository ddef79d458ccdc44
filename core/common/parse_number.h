#pragma once
// Strict parsing of numbers in text (the tools' options, the data files' fields): the whole text
// must be the number (no spaces, no trailing characters, not empty), finite, and within [lo, hi].
// atof / atoi read "abc" as 0 and "1.5" as 1; a value out of any range (1e300, nan) can overflow
// a later conversion.
//
// NumberArgument, IntegerArgument and SeedArgument are the same checks with the message every
// tool prints for a bad option value: it names the option, the range and the text given.

#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

namespace atlas {

// Each returns false, leaving `value` unchanged, when the text is not such a number.

// A finite decimal floating-point number, the whole text (std::from_chars, chars_format::general,
// independent of the locale): an optional leading '-', digits with an optional '.' (digits may
// be on one side only: ".5", "5."), an optional exponent 'e' or 'E' with an optional sign
// ("-1.5", "2e-3", "1E+3", "0", "-0", "007"). Refused: empty text, leading or trailing spaces
// or other characters, a leading '+', hex ("0x10"), "1,5", "inf" / "nan" in any spelling, and
// values too large or too small to represent ("1e999", "1e-400"; subnormals such as "4e-320"
// are taken).
bool ParseNumber(std::string_view text, double* value);
// ParseNumber within [lo, hi].
bool ParseNumberIn(std::string_view text, double lo, double hi, double* value);
// A decimal integer, the whole text: digits with an optional leading '-' (std::from_chars: no
// '+', spaces, fraction or exponent, so "1.5" and "1e3" are not integers); false when it does
// not fit the type.
bool ParseInteger(std::string_view text, int64_t* value);
bool ParseInteger(std::string_view text, uint64_t* value);
bool ParseInteger(std::string_view text, int* value);
// ParseInteger within [lo, hi].
bool ParseIntegerIn(std::string_view text, long lo, long hi, long* value);

// `value` of `option` as a number (ParseNumberIn) or an integer (ParseInteger) in [lo, hi] into
// `out`; else false with `error` = "OPTION must be a number (an integer) in [LO, HI], got
// 'VALUE'". `out` is unchanged on error.
bool NumberArgument(std::string_view option, const char* value, double lo, double hi, double& out,
                    std::string& error);
bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi,
                     int64_t& out, std::string& error);
// A random seed: any integer in [0, 18446744073709551615].
bool SeedArgument(std::string_view option, const char* value, uint64_t& out, std::string& error);

// An integer option into a narrower type; [lo, hi] must lie within the type.
template <std::integral Int>
bool IntegerArgument(std::string_view option, const char* value, int64_t lo, int64_t hi, Int& out,
                     std::string& error) requires(!std::same_as<Int, int64_t>) {
  static_assert(sizeof(Int) < sizeof(int64_t) || std::is_signed_v<Int>);
  int64_t v = 0;
  if (!IntegerArgument(option, value, lo, hi, v, error)) return false;
  if (v < static_cast<int64_t>(std::numeric_limits<Int>::min()) ||
      v > static_cast<int64_t>(std::numeric_limits<Int>::max())) {
    error = std::string(option) + ": " + value + " does not fit";
    return false;
  }
  out = static_cast<Int>(v);
  return true;
}

}  // namespace atlas
