#pragma once
// Tab- or space-separated text files (docs/formats.md, "Text files"): reading whole files, plain
// or gzip-compressed; iterating over their data rows; the field checks every format shares, with
// errors "<file>:<line>: <what>".
//
// A row is a line split at runs of spaces and tabs (a trailing '\r' is dropped); blank lines
// and lines whose first field begins with '#' are not rows.

#include <cstdarg>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "core/atlas/atlas_graph.h"
#include "core/geometry/se2.h"

namespace atlas::formats {

struct TextFile {
  std::string text;
  std::string error;     // "<path>: cannot open (<why>)" or "<path>: read error (<why>)"; "" read
  bool missing = false;  // the file does not exist
};
// Reads a whole file, plain or gzip-compressed (zlib).
TextFile ReadTextFile(const std::string& path);

// Writes `text` to `path` (replacing it); "" or "cannot write <path>: <why>".
std::string WriteTextFile(const std::string& path, std::string_view text);

// Calls `row(fields, line)` for every row; stops at the first error it returns and gives it as
// "<source>:<line>: <error>". A row with a field count other than `field_count` is the error
// "expected N fields (<columns>), found M"; with `field_count` kAnyFieldCount every row is
// passed on (formats whose rows differ by tag, such as g2o, check the count themselves).
inline constexpr size_t kAnyFieldCount = 0;
using RowFunction = std::function<std::string(std::span<const std::string_view>, int64_t line)>;
std::string ForEachRow(std::string_view text, const std::string& source, size_t field_count,
                       std::string_view columns, const RowFunction& row);

// Limits on values read: a stamp beyond 4e9 s overflows the nanosecond clock; positions beyond
// 10,000 km or angles beyond 1000 rad are damage, not data.
inline constexpr double kMaxAbsStampS = 4e9;
inline constexpr double kMaxAbsPositionM = 1e7;
inline constexpr double kMaxAbsAngleRad = 1e3;

// Each returns "" or what is wrong with the field, naming it by its 1-based `field` number.
// A finite number (core/common/parse_number.h; a leading '+' is allowed).
std::string NumberField(std::string_view text, size_t field, double* value);
// A frame id, 0 .. 1e8 (-1 too with `allow_none`: "no frame").
std::string FrameField(std::string_view text, size_t field, bool allow_none, FrameId* frame);
// A timestamp in seconds within kMaxAbsStampS.
std::string StampField(std::string_view text, size_t field, Time* stamp);
// A position (m, within kMaxAbsPositionM) or an angle (rad, within kMaxAbsAngleRad; not wrapped).
std::string CoordinateField(std::string_view text, size_t field, bool angle, double* value);
// Three fields x y theta within the limits above; theta is wrapped to (-pi, pi].
std::string PoseFields(std::span<const std::string_view> fields, size_t first, Pose2* pose);

// Appends printf-formatted text to `out` (a row of a file).
[[gnu::format(printf, 2, 3)]] void AppendF(std::string* out, const char* format, ...);

}  // namespace atlas::formats
