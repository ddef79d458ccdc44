#pragma once
// The page's data: one JSON object built from a ViewState (pure; the page draws it as is).
//
// The frames are placed by a Dijkstra projection (core/atlas/dijkstra_projection.h, paper
// Section III-A), computed here from ATLAS_GRAPH's edges, from the dominant frame: the frame of
// the latest pose when the graph holds it, else the graph's dominant frame. Everything is sent in
// that frame's coordinates (metres, radians): each drawn frame's origin, its projected
// uncertainty and its remembered lines; the edges between drawn frames with their kind; the
// robot's pose and the hypotheses, composed from their own frame. Ellipses are 95 % regions of
// the (x, y) marginal. At most `max_frames` frames are drawn, those of smallest rho first; the
// edges, pose and hypotheses of frames not drawn are left out. Non-finite numbers are null.
//
// {"source": F, "frames": [{"id", "x", "y", "th", "hops", "ell": [a, b, angle], "lines":
//  [[x0, y0, x1, y1], ...]}], "frames_total", "frames_drawn", "edges": [{"a", "b", "kind"}],
//  "pose": {"frame", "x", "y", "th", "ell", "q", "placed", "age_s"} | null,
//  "hypotheses": [{"id", "frame", "state", "q", "steps", "placed", "x", "y", "th", "ell"}],
//  "map": {"frame", "lines", "capacity", "age_s"} | null, "health": {...} | null,
//  "graph_error": "..." (only when ATLAS_GRAPH's edges do not form a graph),
//  "graph_age_s", "hypotheses_age_s"} ("age_s": seconds since the message arrived; null if never)

#include <string>
#include <string_view>

#include "core/common/time.h"
#include "tools/view/view_state.h"

namespace atlas::view {

// The semi-axes (a >= b) and the angle of a's axis, radians, of the ellipse
// [x y] C^-1 [x y]^T = scale^2 for the 2x2 covariance C = [[sxx, sxy], [sxy, syy]].
struct Ellipse {
  double a = 0, b = 0, angle = 0;
};
Ellipse CovarianceEllipse(double sxx, double sxy, double syy, double scale);
// sqrt of the 95 % quantile of chi-square with 2 degrees of freedom.
inline constexpr double kEllipse95 = 2.4477468306808161;

// `text` as a JSON string literal, quotes included: " and \ escaped, control characters as
// \u00XX; other bytes as they are.
std::string JsonString(std::string_view text);

std::string BuildViewJson(const ViewState& state, Time now, int max_frames);

// "stopped", "connecting", "running", "stalled", "reconnecting", "failed" (driver_health_t);
// "juvenile", "mature", "dominant", "retired" (hypothesis_t); "genesis", "map-match", "refined"
// (atlas_edge_t). "unknown" for other codes.
const char* DriverStateName(int8_t state);
const char* HypothesisStateName(int8_t state);
const char* EdgeKindCodeName(int8_t kind);

}  // namespace atlas::view
