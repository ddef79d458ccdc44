#pragma once
// g2o's text graph format for planar pose graphs (docs/formats.md, "g2o"), as g2o_viewer,
// g2o's solvers and most pose-graph tools read it:
//
//   VERTEX_SE2 id x y theta
//   EDGE_SE2 from to dx dy dtheta i11 i12 i13 i22 i23 i33
//   FIX id
//
// An edge's measurement is the pose of `to` in `from` (an atlas edge's b_in_a); i.. is the upper
// triangle of its information matrix (the inverse covariance) over (x, y, theta), row by row,
// g2o's order. FIX holds a vertex (the reference frame) in place.

#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::formats {

struct G2oVertex {
  int id = 0;
  Pose2 pose;
};
struct G2oEdge {
  int from = 0;
  int to = 0;
  Pose2 measurement;                    // `to` in `from`
  Mat3 information = Mat3::Identity();  // symmetric
};
struct G2oGraph {
  std::vector<G2oVertex> vertices;
  std::vector<G2oEdge> edges;
  std::vector<int> fixed;
};

// The file: "# <comment>", the vertices, the edges, then FIX lines. Poses with 6 decimals,
// information with %.9g.
std::string FormatG2o(const G2oGraph& graph, std::string_view comment);

// Reads the three tags above ('#' lines are comments); "" or "<source>:<line>: <what>".
// Refused: another tag, a wrong field count, a bad number, a vertex id given twice, an edge or
// FIX naming a vertex not given before it, and an information matrix that is not positive
// definite.
std::string ParseG2o(std::string_view text, const std::string& source, G2oGraph* out);

// The information matrix of a covariance: its inverse; false (and `info` untouched) when the
// covariance is not positive definite (core/geometry/covariance.h).
bool InformationOf(const Mat3& covariance, Mat3* info);

}  // namespace atlas::formats
