#include "formats/ply_points.h"

#include "core/common/parse_number.h"
#include "core/common/quote_for_message.h"
#include "formats/text_rows.h"

namespace atlas::formats {
namespace {

constexpr const char* kHeader[] = {"ply",
                                   "format ascii 1.0",
                                   nullptr,  // comment
                                   nullptr,  // element vertex N
                                   "property float x",
                                   "property float y",
                                   "property float z",
                                   "property int frame",
                                   "end_header"};
constexpr size_t kHeaderLines = std::size(kHeader);

}  // namespace

std::string FormatPlyPoints(std::span<const PlyPoint> points, std::string_view comment) {
  std::string text = "ply\nformat ascii 1.0\ncomment " + std::string(comment) + "\n";
  AppendF(&text, "element vertex %zu\n", points.size());
  for (size_t i = 4; i < kHeaderLines; ++i) text += std::string(kHeader[i]) + "\n";
  for (const PlyPoint& p : points) AppendF(&text, "%.3f %.3f 0 %d\n", p.p.x(), p.p.y(), p.frame);
  return text;
}

std::string ParsePlyPoints(std::string_view text, const std::string& source,
                           std::vector<PlyPoint>* out) {
  size_t pos = 0;
  int64_t line_no = 0;
  const auto next_line = [&](std::string_view* line) {
    if (pos >= text.size()) return false;
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    *line = text.substr(pos, end - pos);
    if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
    pos = end + 1;
    ++line_no;
    return true;
  };
  const auto where = [&] { return source + ":" + std::to_string(line_no) + ": "; };
  int64_t count = -1;
  for (size_t i = 0; i < kHeaderLines; ++i) {
    std::string_view line;
    if (!next_line(&line)) return source + ": the PLY header ends early (no end_header)";
    if (i == 2) {
      if (line.rfind("comment", 0) == 0) continue;
      ++i;  // no comment: this is the element line
    }
    if (i == 3) {
      constexpr std::string_view kElement = "element vertex ";
      if (line.rfind(kElement, 0) != 0 || !ParseInteger(line.substr(kElement.size()), &count) ||
          count < 0)
        return where() + "expected 'element vertex N', found " + QuoteForMessage(line);
      continue;
    }
    if (line != kHeader[i])
      return where() + "expected '" + kHeader[i] + "', found " + QuoteForMessage(line);
  }
  const size_t first = out->size();
  const int64_t header_lines = line_no;
  // The whole text, so that errors name the file's lines; the header's lines are skipped.
  const std::string error =
      ForEachRow(text, source, kAnyFieldCount, "x y z frame",
                 [&](std::span<const std::string_view> f, int64_t line) {
                   if (line <= header_lines) return std::string();
                   if (f.size() != 4)
                     return "expected 4 fields (x y z frame), found " + std::to_string(f.size());
                   PlyPoint p;
                   double v[3];
                   for (size_t k = 0; k < 3; ++k)
                     if (std::string e = CoordinateField(f[k], k + 1, false, &v[k]); !e.empty())
                       return e;
                   if (std::string e = FrameField(f[3], 4, false, &p.frame); !e.empty()) return e;
                   p.p = Vec2(v[0], v[1]);
                   out->push_back(p);
                   return std::string();
                 });
  if (!error.empty()) return error;
  const int64_t read = static_cast<int64_t>(out->size() - first);
  if (read != count)
    return source + ": the header says " + std::to_string(count) + " vertices, the file has " +
           std::to_string(read);
  return "";
}

}  // namespace atlas::formats
