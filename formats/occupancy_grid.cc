#include "formats/occupancy_grid.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "core/common/parse_number.h"
#include "core/common/quote_for_message.h"
#include "formats/text_rows.h"

namespace atlas::formats {
namespace {

constexpr uint8_t kOccupiedPixel = 0;
constexpr uint8_t kFreePixel = 254;
constexpr uint8_t kUnknownPixel = 205;

uint8_t PixelOf(Occupancy o) {
  switch (o) {
    case Occupancy::kOccupied:
      return kOccupiedPixel;
    case Occupancy::kFree:
      return kFreePixel;
    case Occupancy::kUnknown:
      break;
  }
  return kUnknownPixel;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

}  // namespace

bool OccupancyGrid::CellOf(const Vec2& p, int* ix, int* iy) const {
  const double fx = std::floor((p.x() - origin.x()) / resolution);
  const double fy = std::floor((p.y() - origin.y()) / resolution);
  if (!(fx >= 0 && fy >= 0 && fx < width && fy < height)) return false;
  *ix = static_cast<int>(fx);
  *iy = static_cast<int>(fy);
  return true;
}

OccupancyGrid OccupiedCellsGrid(std::span<const Vec2> points, double resolution, double margin) {
  OccupancyGrid grid;
  grid.resolution = resolution;
  if (points.empty()) return grid;
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // The origin on a whole multiple of the resolution, so that two exports agree cell for cell.
  grid.origin = ((lo.array() - margin) / resolution).floor().matrix() * resolution;
  grid.width = static_cast<int>(std::ceil((hi.x() + margin - grid.origin.x()) / resolution)) + 1;
  grid.height = static_cast<int>(std::ceil((hi.y() + margin - grid.origin.y()) / resolution)) + 1;
  grid.cells.assign(static_cast<size_t>(grid.width) * grid.height, Occupancy::kUnknown);
  for (const Vec2& p : points) {
    int ix = 0, iy = 0;
    if (grid.CellOf(p, &ix, &iy))
      grid.cells[static_cast<size_t>(iy) * grid.width + ix] = Occupancy::kOccupied;
  }
  return grid;
}

std::string FormatPgm(const OccupancyGrid& grid, std::string_view comment) {
  std::string bytes = "P5\n# " + std::string(comment) + "\n";
  AppendF(&bytes, "%d %d\n255\n", grid.width, grid.height);
  bytes.reserve(bytes.size() + grid.cells.size());
  for (int row = grid.height - 1; row >= 0; --row)
    for (int ix = 0; ix < grid.width; ++ix) bytes += static_cast<char>(PixelOf(grid.At(ix, row)));
  return bytes;
}

std::string FormatMapYaml(const OccupancyGrid& grid, std::string_view image) {
  std::string text;
  AppendF(&text,
          "image: %.*s\nmode: trinary\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\n"
          "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
          static_cast<int>(image.size()), image.data(), grid.resolution, grid.origin.x(),
          grid.origin.y());
  return text;
}

std::string ParsePgm(std::string_view bytes, const std::string& source, PgmImage* out) {
  size_t pos = 0;
  // The next header token, skipping whitespace and '#' comments to the end of their line.
  const auto token = [&](std::string_view* t) {
    while (pos < bytes.size()) {
      if (bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else if (std::isspace(static_cast<unsigned char>(bytes[pos]))) {
        ++pos;
      } else {
        break;
      }
    }
    const size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    *t = bytes.substr(start, pos - start);
    return !t->empty();
  };
  std::string_view magic;
  if (!token(&magic) || magic != "P5")
    return source + ": not a binary PGM (the file does not begin with P5)";
  const char* names[] = {"width", "height", "maxval"};
  int* values[] = {&out->width, &out->height, &out->maxval};
  for (int k = 0; k < 3; ++k) {
    std::string_view t;
    int64_t v = 0;
    if (!token(&t) || !ParseInteger(t, &v) || v < 1 || v > (k == 2 ? 255 : 1 << 20))
      return source + ": the header's " + names[k] + " is " + QuoteForMessage(t) +
             ", not a whole number in range";
    *values[k] = static_cast<int>(v);
  }
  // One whitespace byte ends the header; the pixels follow.
  if (pos >= bytes.size()) return source + ": no pixels after the header";
  ++pos;
  const size_t want = static_cast<size_t>(out->width) * out->height;
  const size_t have = bytes.size() - pos;
  if (have != want)
    return source + ": the header says " + std::to_string(out->width) + " x " +
           std::to_string(out->height) + " = " + std::to_string(want) + " pixels, the file has " +
           std::to_string(have) + " bytes of them";
  out->pixels.assign(bytes.begin() + static_cast<std::ptrdiff_t>(pos), bytes.end());
  return "";
}

std::string ParseMapYaml(std::string_view text, const std::string& source, MapYaml* out) {
  std::map<std::string, int64_t> seen;
  size_t pos = 0;
  int64_t line_no = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view raw = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    const std::string_view line = Trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    const std::string where = source + ":" + std::to_string(line_no) + ": ";
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) return where + "expected 'key: value'";
    const std::string key(Trim(line.substr(0, colon)));
    const std::string_view value = Trim(line.substr(colon + 1));
    if (const auto it = seen.find(key); it != seen.end())
      return where + "key " + key + " repeats line " + std::to_string(it->second);
    seen.emplace(key, line_no);
    const auto number = [&](double* v) {
      return ParseNumber(value, v)
                 ? std::string()
                 : where + key + " is " + QuoteForMessage(value) + ", not a number";
    };
    std::string e;
    if (key == "image") {
      out->image = std::string(value);
      if (out->image.empty()) e = where + "image is empty";
    } else if (key == "mode") {
      out->mode = std::string(value);
      if (out->mode != "trinary" && out->mode != "scale" && out->mode != "raw")
        e = where + "mode is " + QuoteForMessage(value) + ", not trinary, scale or raw";
    } else if (key == "resolution") {
      e = number(&out->resolution);
      if (e.empty() && !(out->resolution > 0)) e = where + "resolution must be above 0";
    } else if (key == "negate") {
      if (value != "0" && value != "1") e = where + "negate must be 0 or 1";
      out->negate = value == "1";
    } else if (key == "occupied_thresh") {
      e = number(&out->occupied_thresh);
    } else if (key == "free_thresh") {
      e = number(&out->free_thresh);
    } else if (key == "origin") {
      if (value.size() < 2 || value.front() != '[' || value.back() != ']')
        return where + "origin must be [x, y, yaw]";
      double v[3];
      std::string_view rest = value.substr(1, value.size() - 2);
      for (int k = 0; k < 3; ++k) {
        const size_t comma = k < 2 ? rest.find(',') : rest.size();
        if (comma == std::string_view::npos || !ParseNumber(Trim(rest.substr(0, comma)), &v[k]))
          return where + "origin must be [x, y, yaw], three numbers";
        rest = k < 2 ? rest.substr(comma + 1) : std::string_view();
      }
      out->origin = Pose2{v[0], v[1], v[2]};
    } else {
      e = where + "unknown key " + QuoteForMessage(key);
    }
    if (!e.empty()) return e;
  }
  for (const char* key :
       {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"})
    if (seen.count(key) == 0) return source + ": no key " + key;
  return "";
}

}  // namespace atlas::formats
