#include "formats/text_rows.h"

#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/common/parse_number.h"
#include "core/common/quote_for_message.h"

namespace atlas::formats {

TextFile ReadTextFile(const std::string& path) {
  TextFile out;
  errno = 0;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    out.missing = errno == ENOENT;
    out.error = path + ": cannot open (" + std::strerror(errno != 0 ? errno : ENOMEM) + ")";
    return out;
  }
  char buf[1 << 16];
  int n = 0;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.text.append(buf, static_cast<size_t>(n));
  if (n < 0) {
    int zerr = 0;
    out.error = path + ": read error (" + gzerror(f, &zerr) + ")";
  }
  gzclose(f);
  return out;
}

std::string WriteTextFile(const std::string& path, std::string_view text) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return "cannot write " + path + ": " + std::strerror(errno);
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int write_errno = errno;
  // A write error (a full disk) shows at the latest when the file is closed.
  if (std::fclose(f) != 0 || !written)
    return "cannot write " + path + ": " + std::strerror(written ? errno : write_errno);
  return "";
}

std::string ForEachRow(std::string_view text, const std::string& source, size_t field_count,
                       std::string_view columns, const RowFunction& row) {
  std::vector<std::string_view> fields;
  size_t pos = 0;
  int64_t line_no = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    fields.clear();
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      fields.push_back(line.substr(i, j - i));
      i = j;
    }
    if (fields.empty() || fields[0][0] == '#') continue;
    const std::string where = source + ":" + std::to_string(line_no) + ": ";
    if (field_count != kAnyFieldCount && fields.size() != field_count)
      return where + "expected " + std::to_string(field_count) + " fields (" +
             std::string(columns) + "), found " + std::to_string(fields.size());
    if (std::string e = row(fields, line_no); !e.empty()) return where + e;
  }
  return "";
}

std::string NumberField(std::string_view text, size_t field, double* value) {
  std::string_view digits = text;
  if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
  if (!ParseNumber(digits, value))
    return "field " + std::to_string(field) + " is " + QuoteForMessage(text) + ", not a number";
  return "";
}

std::string FrameField(std::string_view text, size_t field, bool allow_none, FrameId* frame) {
  int64_t v = 0;
  if (!ParseInteger(text, &v) || v < (allow_none ? -1 : 0) || v > 100000000)
    return "field " + std::to_string(field) + " is " + QuoteForMessage(text) +
           ", not a frame id (" + (allow_none ? "-1 or " : "") + "an integer 0..1e8)";
  *frame = static_cast<FrameId>(v);
  return "";
}

namespace {

std::string Short(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

std::string StampField(std::string_view text, size_t field, Time* stamp) {
  double t = 0.0;
  if (std::string e = NumberField(text, field, &t); !e.empty()) return e;
  if (std::abs(t) > kMaxAbsStampS)
    return "field " + std::to_string(field) + " (a timestamp) is " + Short(t) +
           ", out of range (|t| <= 4e9 s)";
  *stamp = FromSeconds(t);
  return "";
}

std::string CoordinateField(std::string_view text, size_t field, bool angle, double* value) {
  if (std::string e = NumberField(text, field, value); !e.empty()) return e;
  if (std::abs(*value) > (angle ? kMaxAbsAngleRad : kMaxAbsPositionM))
    return "field " + std::to_string(field) + " is " + Short(*value) +
           (angle ? ", out of range for an angle (|theta| <= 1e3 rad)"
                  : ", out of range for a position (|x|, |y| <= 1e7 m)");
  return "";
}

std::string PoseFields(std::span<const std::string_view> fields, size_t first, Pose2* pose) {
  double v[3];
  for (size_t k = 0; k < 3; ++k)
    if (std::string e = CoordinateField(fields[first + k], first + k + 1, k == 2, &v[k]);
        !e.empty())
      return e;
  *pose = Pose2{v[0], v[1], WrapAngle(v[2])};
  return "";
}

void AppendF(std::string* out, const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  if (n > 0) out->append(buf, static_cast<size_t>(std::min<int>(n, sizeof buf - 1)));
}

}  // namespace atlas::formats
