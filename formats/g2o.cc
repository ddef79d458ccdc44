#include "formats/g2o.h"

#include <Eigen/Cholesky>
#include <set>

#include "core/common/quote_for_message.h"
#include "core/geometry/covariance.h"
#include "formats/text_rows.h"

namespace atlas::formats {
namespace {

std::string IdField(std::string_view text, size_t field, int* id) {
  FrameId f = kNoFrame;
  if (std::string e = FrameField(text, field, false, &f); !e.empty()) return e;
  *id = f;
  return "";
}

}  // namespace

bool InformationOf(const Mat3& covariance, Mat3* info) {
  if (!IsPositiveDefiniteCovariance(covariance)) return false;
  const Mat3 inverse = covariance.ldlt().solve(Mat3::Identity());
  *info = 0.5 * (inverse + inverse.transpose());
  return true;
}

std::string FormatG2o(const G2oGraph& graph, std::string_view comment) {
  std::string text = "# " + std::string(comment) + "\n";
  for (const G2oVertex& v : graph.vertices)
    AppendF(&text, "VERTEX_SE2 %d %.6f %.6f %.6f\n", v.id, v.pose.x, v.pose.y, v.pose.theta);
  for (const G2oEdge& e : graph.edges) {
    const Mat3& i = e.information;
    AppendF(&text, "EDGE_SE2 %d %d %.6f %.6f %.6f %.9g %.9g %.9g %.9g %.9g %.9g\n", e.from, e.to,
            e.measurement.x, e.measurement.y, e.measurement.theta, i(0, 0), i(0, 1), i(0, 2),
            i(1, 1), i(1, 2), i(2, 2));
  }
  for (int id : graph.fixed) AppendF(&text, "FIX %d\n", id);
  return text;
}

std::string ParseG2o(std::string_view text, const std::string& source, G2oGraph* out) {
  std::set<int> ids;
  return ForEachRow(
      text, source, kAnyFieldCount, "a g2o SE2 line",
      [&](std::span<const std::string_view> f, int64_t) {
        const auto count = [&](size_t n, const char* columns) {
          return f.size() == n ? std::string()
                               : "expected " + std::to_string(n) + " fields (" + columns +
                                     "), found " + std::to_string(f.size());
        };
        const auto known = [&](int id, size_t field) {
          return ids.count(id) != 0
                     ? std::string()
                     : "field " + std::to_string(field) + " names vertex " + std::to_string(id) +
                           ", not given by a VERTEX_SE2 line before";
        };
        if (f[0] == "VERTEX_SE2") {
          if (std::string e = count(5, "VERTEX_SE2 id x y theta"); !e.empty()) return e;
          G2oVertex v;
          if (std::string e = IdField(f[1], 2, &v.id); !e.empty()) return e;
          if (std::string e = PoseFields(f, 2, &v.pose); !e.empty()) return e;
          if (!ids.insert(v.id).second) return "vertex " + std::to_string(v.id) + " given twice";
          out->vertices.push_back(v);
        } else if (f[0] == "EDGE_SE2") {
          if (std::string e = count(12, "EDGE_SE2 from to dx dy dtheta i11 i12 i13 i22 i23 i33");
              !e.empty())
            return e;
          G2oEdge g;
          if (std::string e = IdField(f[1], 2, &g.from); !e.empty()) return e;
          if (std::string e = IdField(f[2], 3, &g.to); !e.empty()) return e;
          if (std::string e = known(g.from, 2); !e.empty()) return e;
          if (std::string e = known(g.to, 3); !e.empty()) return e;
          if (std::string e = PoseFields(f, 3, &g.measurement); !e.empty()) return e;
          double v[6];
          for (size_t k = 0; k < 6; ++k)
            if (std::string e = NumberField(f[6 + k], 7 + k, &v[k]); !e.empty()) return e;
          g.information << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
          if (!IsPositiveDefiniteCovariance(g.information))
            return "the information matrix of edge " + std::to_string(g.from) + "-" +
                   std::to_string(g.to) + " (fields 7-12) is not positive definite";
          out->edges.push_back(g);
        } else if (f[0] == "FIX") {
          if (std::string e = count(2, "FIX id"); !e.empty()) return e;
          int id = 0;
          if (std::string e = IdField(f[1], 2, &id); !e.empty()) return e;
          if (std::string e = known(id, 2); !e.empty()) return e;
          out->fixed.push_back(id);
        } else {
          return "tag " + QuoteForMessage(f[0]) + " is not VERTEX_SE2, EDGE_SE2 or FIX";
        }
        return std::string();
      });
}

}  // namespace atlas::formats
