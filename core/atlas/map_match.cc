#include "core/atlas/map_match.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace atlas {

std::string MapMatchOptions::Validate() const {
  if (max_lines < 2 || max_lines > 64) return "map_match.max_lines must lie in [2, 64]";
  if (min_support < 2) return "map_match.min_support must be at least 2";
  if (self_min_support < min_support)
    return "map_match.self_min_support must be at least min_support";
  if (min_lead < 1) return "map_match.min_lead must be at least 1";
  if (!(parallel_tolerance > 0 && parallel_tolerance < std::numbers::pi / 2))
    return "map_match.parallel_tolerance must lie in (0, pi/2)";
  if (!(pair_angle_tolerance > 0)) return "map_match.pair_angle_tolerance must be positive";
  if (!(line_gate_chi2 > 0 && prior_gate_chi2 > 0)) return "map_match gates must be positive";
  if (!(sigma_rho_floor >= 0 && sigma_alpha_floor >= 0))
    return "map_match sigma floors must be non-negative";
  if (!(distinct_translation > 0 && distinct_rotation > 0))
    return "map_match distinct thresholds must be positive";
  if (gauss_newton_iterations < 1) return "map_match.gauss_newton_iterations must be >= 1";
  if (max_line_checks < 1) return "map_match.max_line_checks must be at least 1";
  if (!(redundancy_sigma >= 0)) return "map_match.redundancy_sigma must be >= 0 (0: off)";
  if (!(redundancy_prior_halfwidth >= 0))
    return "map_match.redundancy_prior_halfwidth must be >= 0 (0: never)";
  if (!(alternative_sigmas >= 0)) return "map_match.alternative_sigmas must be >= 0 (0: off)";
  if (point_min_hits < 1) return "map_match.point_min_hits must be at least 1";
  if (!(point_rival_ratio > 0 && point_rival_ratio < 1))
    return "map_match.point_rival_ratio must lie in (0, 1)";
  if (!(point_max_shift > 0 && point_max_shift <= 100))
    return "map_match.point_max_shift must lie in (0, 100] metres";
  return "";
}

const char* MapMatchResultName(MapMatchResult r) {
  switch (r) {
    case MapMatchResult::kAccepted:
      return "accepted";
    case MapMatchResult::kRejected:
      return "rejected";
    case MapMatchResult::kAmbiguous:
      return "ambiguous";
  }
  return "unknown";
}

MapMatchOptions LaserMapMatchOptions(MapMatchOptions o) {
  o.unknown_line_correlation = true;
  o.alternative_sigmas = 3.0;
  o.redundancy_prior_halfwidth = 1.0;
  o.sigma_alpha_floor = 0.02;
  return o;
}

MapMatchOptions SonarMapMatchOptions(MapMatchOptions o) {
  o.unknown_line_correlation = true;
  o.redundancy_sigma = 0.25;
  o.redundancy_prior_halfwidth = 0.5;
  o.alternative_sigmas = 3.0;
  return o;
}

const char* MapMatchReasonName(MapMatchReason r) {
  switch (r) {
    case MapMatchReason::kMatched:
      return "matched";
    case MapMatchReason::kTooFewLines:
      return "too-few-lines";
    case MapMatchReason::kTooLittleSupport:
      return "too-little-support";
    case MapMatchReason::kDegenerate:
      return "degenerate";
    case MapMatchReason::kOutsidePrior:
      return "outside-prior";
    case MapMatchReason::kRepetitive:
      return "repetitive";
    case MapMatchReason::kRivalTransform:
      return "rival-transform";
    case MapMatchReason::kWorkBound:
      return "work-bound";
    case MapMatchReason::kSinglePair:
      return "single-pair";
    case MapMatchReason::kFreeSpace:
      return "free-space";
  }
  return "unknown";
}

namespace {

using Mat2 = Eigen::Matrix2d;
using Mat23 = Eigen::Matrix<double, 2, 3>;

struct Line {
  double rho = 0, alpha = 0;
  double cos_alpha = 1, sin_alpha = 0;
  Mat2 cov = Mat2::Zero();
  Vec2 p = Vec2::Zero(), q = Vec2::Zero();
};

std::vector<Line> Prepare(const std::vector<MapLine>& lines, const MapMatchOptions& o) {
  std::vector<std::pair<double, int>> order;
  for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
    const MapLine& l = lines[i];
    const double len = (l.endpoint_a - l.endpoint_b).norm();
    if (!(len >= o.min_line_length) || !std::isfinite(l.rho) || !std::isfinite(l.alpha) ||
        !l.cov.allFinite())
      continue;
    order.push_back({-len, i});
  }
  std::stable_sort(order.begin(), order.end());
  if (static_cast<int>(order.size()) > o.max_lines) order.resize(o.max_lines);
  std::vector<Line> out;
  out.reserve(order.size());
  for (const auto& [neg_len, i] : order) {
    const MapLine& l = lines[i];
    Line p;
    p.rho = l.rho;
    p.alpha = l.alpha;
    p.cos_alpha = std::cos(l.alpha);
    p.sin_alpha = std::sin(l.alpha);
    p.cov = 0.5 * (l.cov + l.cov.transpose());
    p.cov(0, 0) += o.sigma_rho_floor * o.sigma_rho_floor;
    p.cov(1, 1) += o.sigma_alpha_floor * o.sigma_alpha_floor;
    p.p = l.endpoint_a;
    p.q = l.endpoint_b;
    out.push_back(p);
  }
  return out;
}

// Difference of two line directions modulo pi, in [-pi/2, pi/2].
double AngleModPi(double a) { return 0.5 * WrapAngle(2.0 * a); }

// Line b of B transformed by t (pose of B in A): the part of the residual that does not depend
// on the line of A it is compared with (one sin/cos per line and transform).
struct MovedLine {
  double alpha, c, s, rho, drho;
};

MovedLine Move(const Line& b, const Pose2& t) {
  MovedLine m;
  m.alpha = b.alpha + t.theta;
  m.c = std::cos(m.alpha);
  m.s = std::sin(m.alpha);
  m.rho = b.rho + t.x * m.c + t.y * m.s;
  m.drho = -t.x * m.s + t.y * m.c;
  return m;
}

// a - b for angles within a few turns of each other, in (-pi, pi].
double AngleDifference(double a, double b) {
  constexpr double kPi = std::numbers::pi;
  double d = a - b;
  while (d > kPi) d -= 2.0 * kPi;
  while (d <= -kPi) d += 2.0 * kPi;
  return d;
}

// Residual of line a (in A) against line b (in B) moved by t (pose of B in A), its Jacobian
// with respect to t, and its covariance.
struct PairResidual {
  Vec2 r;
  Mat23 jt;
  Mat2 s;
  double chi2;
};

// The signed residual's angle part and the sign (which of b's two representations is meant).
double AngleResidual(const Line& a, const MovedLine& m, double* sign) {
  *sign = m.c * a.cos_alpha + m.s * a.sin_alpha >= 0.0 ? 1.0 : -1.0;
  return AngleDifference(a.alpha, m.alpha + (*sign < 0 ? std::numbers::pi : 0.0));
}

PairResidual Residual(const Line& a, const Line& b, const MovedLine& m) {
  double sign;
  const double r_alpha = AngleResidual(a, m, &sign);
  PairResidual out;
  out.r = Vec2(a.rho - sign * m.rho, r_alpha);
  out.jt << -sign * m.c, -sign * m.s, -sign * m.drho, 0, 0, -1;
  Mat2 jb;
  jb << sign, sign * m.drho, 0, 1;
  out.s = a.cov + jb * b.cov * jb.transpose();
  out.chi2 = out.r.dot(out.s.inverse() * out.r);
  return out;
}

PairResidual Residual(const Line& a, const Line& b, const Pose2& t) {
  return Residual(a, b, Move(b, t));
}

// A transform with its rotation's cosine and sine computed once.
bool SegmentsOverlap(const Line& a, const Line& b, const RigidTransform& t, double slack) {
  const Vec2 d(-a.sin_alpha, a.cos_alpha);
  double a0 = d.dot(a.p), a1 = d.dot(a.q);
  double b0 = d.dot(t.Apply(b.p)), b1 = d.dot(t.Apply(b.q));
  if (a0 > a1) std::swap(a0, a1);
  if (b0 > b1) std::swap(b0, b1);
  return b0 <= a1 + slack && b1 >= a0 - slack;
}

struct Support {
  int count = 0;
  double chi2 = 0.0;
  uint64_t lines_a = 0, lines_b = 0;
  // Matched (line of A, line of B) pairs, at most one per line of B (max_lines <= 64): a fixed
  // array, so verifying a hypothesis allocates nothing.
  std::array<std::pair<uint8_t, uint8_t>, 64> pairs;
};

Support Verify(const std::vector<Line>& a, uint64_t usable_a, const std::vector<Line>& b,
               uint64_t usable_b, const RigidTransform& rigid, const MapMatchOptions& o) {
  const Pose2& t = rigid.pose;
  Support s;
  for (int k = 0; k < static_cast<int>(b.size()); ++k) {
    if (!(usable_b >> k & 1)) continue;
    const MovedLine m = Move(b[k], t);
    int best = -1;
    double best_chi2 = o.line_gate_chi2;
    for (int i = 0; i < static_cast<int>(a.size()); ++i) {
      if (!(usable_a >> i & 1) || (s.lines_a >> i & 1)) continue;
      // The angle alone bounds the joint chi2 from below (r' S^-1 r >= r_1^2 / S_11).
      double sign;
      const double r_alpha = AngleResidual(a[i], m, &sign);
      if (r_alpha * r_alpha > best_chi2 * (a[i].cov(1, 1) + b[k].cov(1, 1))) continue;
      const double chi2 = Residual(a[i], b[k], m).chi2;
      if (chi2 <= best_chi2 && SegmentsOverlap(a[i], b[k], rigid, o.overlap_slack)) {
        best = i;
        best_chi2 = chi2;
      }
    }
    if (best < 0) continue;
    ++s.count;
    s.chi2 += best_chi2;
    s.lines_a |= uint64_t{1} << best;
    s.lines_b |= uint64_t{1} << k;
    s.pairs[s.count - 1] = {static_cast<uint8_t>(best), static_cast<uint8_t>(k)};
  }
  return s;
}

struct Cluster {
  Pose2 t;
  Support support;
};

bool SameTransform(const Pose2& x, const Pose2& y, const MapMatchOptions& o) {
  return std::hypot(x.x - y.x, x.y - y.y) < o.distinct_translation &&
         std::abs(WrapAngle(x.theta - y.theta)) < o.distinct_rotation;
}

bool Better(const Support& x, const Support& y) {
  return x.count > y.count || (x.count == y.count && x.chi2 < y.chi2);
}

constexpr int kMaxClusters = 64;

void AddToClusters(const Pose2& t, Support s, const MapMatchOptions& o,
                   std::vector<Cluster>* clusters) {
  for (Cluster& c : *clusters) {
    if (!SameTransform(c.t, t, o)) continue;
    if (Better(s, c.support)) c = Cluster{t, std::move(s)};
    return;
  }
  if (static_cast<int>(clusters->size()) < kMaxClusters) {
    clusters->push_back(Cluster{t, std::move(s)});
    return;
  }
  auto worst = std::min_element(
      clusters->begin(), clusters->end(),
      [](const Cluster& x, const Cluster& y) { return Better(y.support, x.support); });
  if (Better(s, worst->support)) *worst = Cluster{t, std::move(s)};
}

struct Enumeration {
  int verified = 0;
  bool complete = true;  // false when max_line_checks stopped the enumeration
};

bool InsidePrior(const Pose2& t, const UncertainPose* prior, const MapMatchOptions& o) {
  if (prior == nullptr) return true;
  const Vec3 d(t.x - prior->mean.x, t.y - prior->mean.y, WrapAngle(t.theta - prior->mean.theta));
  const Mat3 cov = prior->cov + Vec3(1e-6, 1e-6, 1e-8).asDiagonal().toDenseMatrix();
  return d.dot(cov.inverse() * d) <= o.prior_gate_chi2;
}

// Enumerates pair hypotheses and collects verified transforms with support >= 2. With
// `self` set, a and b are the same map and the identity hypotheses are skipped. With `gate`
// set, hypotheses outside its gate are not verified (nor kept).
Enumeration Hypothesise(const std::vector<Line>& a, uint64_t usable_a, const std::vector<Line>& b,
                        uint64_t usable_b, bool self, const MapMatchOptions& o,
                        std::vector<Cluster>* clusters, const UncertainPose* gate = nullptr) {
  Enumeration out;
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  const int64_t checks_per_hypothesis =
      std::max<int64_t>(1, int64_t{std::popcount(usable_a)} * std::popcount(usable_b));
  const int64_t max_verified = o.max_line_checks / checks_per_hypothesis;
  // Angle tables: the angle between every two lines of B, computed once (not per pair of A).
  std::array<std::array<double, 64>, 64> angle_b;
  for (int k = 0; k < nb; ++k)
    for (int l = 0; l < nb; ++l) angle_b[k][l] = AngleModPi(b[l].alpha - b[k].alpha);
  for (int i = 0; i < na; ++i) {
    if (!(usable_a >> i & 1)) continue;
    for (int j = i + 1; j < na; ++j) {
      if (!(usable_a >> j & 1)) continue;
      const double angle_a = AngleModPi(a[j].alpha - a[i].alpha);
      if (std::abs(angle_a) < o.parallel_tolerance) continue;
      Mat2 m;
      m << std::cos(a[i].alpha), std::sin(a[i].alpha), std::cos(a[j].alpha), std::sin(a[j].alpha);
      const Mat2 m_inv = m.inverse();
      for (int k = 0; k < nb; ++k) {
        if (!(usable_b >> k & 1)) continue;
        for (int l = 0; l < nb; ++l) {
          if (l == k || !(usable_b >> l & 1)) continue;
          if (self && k == i && l == j) continue;
          // Distance modulo pi of two angles that lie in [-pi/2, pi/2].
          const double d = std::abs(angle_a - angle_b[k][l]);
          if (std::min(d, std::numbers::pi - d) > o.pair_angle_tolerance) continue;
          for (int flip = 0; flip < 2; ++flip) {
            const double theta =
                WrapAngle(a[i].alpha - b[k].alpha + (flip ? std::numbers::pi : 0.0));
            const double si = std::cos(b[k].alpha + theta - a[i].alpha) >= 0 ? 1.0 : -1.0;
            const double sj = std::cos(b[l].alpha + theta - a[j].alpha) >= 0 ? 1.0 : -1.0;
            const Vec2 xy = m_inv * Vec2(a[i].rho - si * b[k].rho, a[j].rho - sj * b[l].rho);
            const Pose2 t{xy.x(), xy.y(), theta};
            const RigidTransform rigid(t);
            if (!SegmentsOverlap(a[i], b[k], rigid, o.overlap_slack) ||
                !SegmentsOverlap(a[j], b[l], rigid, o.overlap_slack))
              continue;
            if (gate != nullptr && !InsidePrior(t, gate, o)) continue;
            if (out.verified >= max_verified) {
              out.complete = false;
              return out;
            }
            ++out.verified;
            Support s = Verify(a, usable_a, b, usable_b, rigid, o);
            if (s.count >= 2) AddToClusters(t, std::move(s), o, clusters);
          }
        }
      }
    }
  }
  return out;
}

uint64_t AllLines(int n) { return n >= 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1; }

// The square of how far the prior's gate reaches either side of its mean along `direction`.
double GateReachSquared(const UncertainPose& prior, const Vec2& direction,
                        const MapMatchOptions& o) {
  return o.prior_gate_chi2 * direction.dot(prior.cov.topLeftCorner<2, 2>() * direction);
}

// Placements of B in A scored by the frames' points (frame_points.h; map_match.h, "Points").
struct PointPlacements {
  PointPlacements(const FramePoints* a, const FramePoints* b) : a(a), b(b), near(a->Near()) {}
  const FramePoints* a;
  const FramePoints* b;
  FramePoints::NearCells near;  // a's
  int Hits(const Pose2& t) const { return a->HitsNear(near, *b, t); }
  // Whether every shift of t along `direction` by at least distinct_translation, in steps of
  // a cell, out to the prior's gate (or 3 m without a prior), has at most point_rival_ratio of
  // t's hits.
  // `t_hits` is Hits(t).
  bool FixesDirection(const Pose2& t, int t_hits, const Vec2& direction, const UncertainPose* prior,
                      const MapMatchOptions& o) const;
};

// The translation direction that information `h` over t fixes worst, and t's standard deviation
// along it (from the marginal information of the translation, the Schur complement of the
// rotation); infinite when h leaves a direction free.
struct WeakDirection {
  Vec2 direction = Vec2::UnitX();
  double sigma = std::numeric_limits<double>::infinity();
};

WeakDirection Weakest(const Mat3& h) {
  WeakDirection w;
  // A rotation the pairs do not fix leaves the translation free too.
  const bool rotation_fixed = h(2, 2) > 1e-12 * std::max(1.0, h.norm());
  Mat2 info = h.topLeftCorner<2, 2>();
  if (rotation_fixed) info -= h.topRightCorner<2, 1>() * h.bottomLeftCorner<1, 2>() / h(2, 2);
  const Eigen::SelfAdjointEigenSolver<Mat2> eig(0.5 * (info + info.transpose()));
  w.direction = eig.eigenvectors().col(0);
  const double lambda = eig.eigenvalues()(0);
  if (rotation_fixed && lambda > 1e-12 * std::max(1.0, info.norm()) && std::isfinite(lambda))
    w.sigma = 1.0 / std::sqrt(lambda);
  return w;
}

bool PointPlacements::FixesDirection(const Pose2& t, int t_hits, const Vec2& direction,
                                     const UncertainPose* prior, const MapMatchOptions& o) const {
  if (t_hits < o.point_min_hits) return false;
  const double reach = prior == nullptr ? 3.0 : std::sqrt(GateReachSquared(*prior, direction, o));
  if (!(reach <= o.point_max_shift)) return false;  // too far to search (or not finite)
  const double step = a->options().cell;
  for (double d = o.distinct_translation; d <= reach; d += step)
    for (double sign : {-1.0, 1.0}) {
      const Pose2 moved{t.x + sign * d * direction.x(), t.y + sign * d * direction.y(), t.theta};
      if (Hits(moved) > o.point_rival_ratio * t_hits) return false;
    }
  return true;
}

// Condition 2 against the maps' own alternatives (map_match.h, "Alternative lines"): the matched
// pair `p` of `pairs` could as well pair its line of B with another line of A of (nearly) its
// orientation, or its line of A with another line of B: the placement t' = t + shift that does
// so. True when some t' differs from t by more than `o.alternative_sigmas` of t's covariance
// `cov_t` along the shift, puts the two segments side by side (overlap_slack), lies inside the
// prior's gate, and leaves every other pair inside its line gate: nothing then tells the two
// placements apart.
bool PairHasAlternative(const std::vector<Line>& a, const std::vector<Line>& b,
                        const std::pair<uint8_t, uint8_t>* pairs, int count, int p, const Pose2& t,
                        const Mat3& cov_t, const UncertainPose* prior, const MapMatchOptions& o,
                        const PointPlacements* points, int t_hits) {
  const auto [i, k] = pairs[p];
  const RigidTransform rigid(t);
  const Mat2 info_xy = cov_t.topLeftCorner<2, 2>().inverse();
  // Is t shifted by `shift` an alternative placement, with line ai of A beside line bk of B?
  auto alternative = [&](const Vec2& shift, int ai, int bk) {
    if (!(shift.dot(info_xy * shift) > o.alternative_sigmas * o.alternative_sigmas)) return false;
    const Pose2 moved{t.x + shift.x(), t.y + shift.y(), t.theta};
    if (!SegmentsOverlap(a[ai], b[bk], RigidTransform(moved), o.overlap_slack)) return false;
    if (!InsidePrior(moved, prior, o)) return false;
    if (points != nullptr && points->Hits(moved) <= o.point_rival_ratio * t_hits) return false;
    for (int q = 0; q < count; ++q) {
      if (q == p) continue;
      const auto [iq, kq] = pairs[q];
      if (!(Residual(a[iq], b[kq], moved).chi2 <= o.line_gate_chi2)) return false;
    }
    return true;
  };
  auto near_parallel = [&](double x, double y) {
    return std::abs(AngleModPi(x - y)) < o.parallel_tolerance;
  };
  // Another line of A beside B's line k: shift line k (moved by t) through that line's
  // midpoint, along k's normal.
  const MovedLine mk = Move(b[k], t);
  const Vec2 n_k(mk.c, mk.s);
  for (int j = 0; j < static_cast<int>(a.size()); ++j) {
    if (j == i || !near_parallel(a[j].alpha, a[i].alpha)) continue;
    if (alternative((n_k.dot(0.5 * (a[j].p + a[j].q)) - mk.rho) * n_k, j, k)) return true;
  }
  // Another line of B beside A's line i: shift its midpoint (moved by t) onto line i, along
  // i's normal.
  const Vec2 n_i(a[i].cos_alpha, a[i].sin_alpha);
  for (int l = 0; l < static_cast<int>(b.size()); ++l) {
    if (l == k || !near_parallel(b[l].alpha, b[k].alpha)) continue;
    const Vec2 mid_l = rigid.Apply(0.5 * (b[l].p + b[l].q));
    if (alternative((a[i].rho - n_i.dot(mid_l)) * n_i, i, l)) return true;
  }
  return false;
}

// t and its covariance from the matched pairs of `support` (Gauss-Newton from `start`), then
// Condition 2 per direction and against alternative lines. `points`, when set, scores
// alternative placements (map_match.h, "Points").
void Finish(const std::vector<Line>& a, const std::vector<Line>& b, const Support& support,
            const Pose2& start, const UncertainPose* prior, const MapMatchOptions& o,
            const PointPlacements* points, MapMatch* out) {
  // t and its covariance from all matched lines (Gauss-Newton).
  Pose2 t = start;
  Mat3 h = Mat3::Zero();
  std::array<Mat3, 64> h_pair;  // each pair's information at the final t
  const int pairs = support.count;
  for (int it = 0; it <= o.gauss_newton_iterations; ++it) {
    h.setZero();
    Vec3 g = Vec3::Zero();
    for (int p = 0; p < pairs; ++p) {
      const auto [i, k] = support.pairs[p];
      const PairResidual r = Residual(a[i], b[k], t);
      const Mat2 s_inv = r.s.inverse();
      h_pair[p] = r.jt.transpose() * s_inv * r.jt;
      h += h_pair[p];
      g += r.jt.transpose() * s_inv * r.r;
    }
    if (it == o.gauss_newton_iterations) break;
    const Eigen::FullPivLU<Mat3> lu(h);
    if (!lu.isInvertible()) break;
    const Vec3 delta = -lu.solve(g);
    t = Pose2::FromVector(t.ToVector() + delta);
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(h);
  const Vec3 ev = eig.eigenvalues();
  if (!(ev(0) > 1e-10 * ev(2)) || !ev.allFinite()) {
    out->reason = MapMatchReason::kDegenerate;
    return;
  }
  const int t_hits = points != nullptr ? points->Hits(t) : 0;
  // Condition 2 per direction: t must stay fixed without any one pair, or the direction that
  // pair alone fixes rests on one unverified correspondence (e.g. the only jamb of a corridor).
  if (o.redundancy_sigma > 0) {
    for (int p = 0; p < pairs; ++p) {
      const WeakDirection w = Weakest(h - h_pair[p]);
      if (w.sigma <= o.redundancy_sigma) continue;
      // The prior alone tells the pair's alternatives apart along that direction (Condition 2).
      if (prior != nullptr && GateReachSquared(*prior, w.direction, o) <=
                                  o.redundancy_prior_halfwidth * o.redundancy_prior_halfwidth)
        continue;
      // Or the points do: no shift along it inside the prior's gate explains them as well.
      if (points != nullptr && points->FixesDirection(t, t_hits, w.direction, prior, o)) continue;
      out->result = MapMatchResult::kAmbiguous;
      out->reason = MapMatchReason::kSinglePair;
      return;
    }
  }
  out->b_in_a.mean = t;
  out->b_in_a.cov = h.inverse();
  if (o.unknown_line_correlation) out->b_in_a.cov *= static_cast<double>(support.count);
  out->b_in_a.cov = 0.5 * (out->b_in_a.cov + out->b_in_a.cov.transpose());
  if (o.alternative_sigmas > 0) {
    for (int p = 0; p < pairs; ++p) {
      if (!PairHasAlternative(a, b, support.pairs.data(), pairs, p, t, out->b_in_a.cov, prior, o,
                              points, t_hits))
        continue;
      out->b_in_a = UncertainPose{};
      out->result = MapMatchResult::kAmbiguous;
      out->reason = MapMatchReason::kSinglePair;
      return;
    }
  }
  out->result = MapMatchResult::kAccepted;
  out->reason = MapMatchReason::kMatched;
}

}  // namespace

SelfMatch SelfMatchMap(const std::vector<MapLine>& lines, const MapMatchOptions& o) {
  const std::vector<Line> p = Prepare(lines, o);
  SelfMatch out;
  out.usable_lines = static_cast<int>(p.size());
  std::vector<Cluster> clusters;
  clusters.reserve(kMaxClusters);
  const uint64_t all = AllLines(out.usable_lines);
  out.complete = Hypothesise(p, all, p, all, /*self=*/true, o, &clusters).complete;
  for (const Cluster& c : clusters) {
    if (c.support.count < o.min_support || SameTransform(c.t, Pose2{}, o)) continue;
    out.repetitions.push_back({c.t, c.support.lines_a | c.support.lines_b, c.support.count});
  }
  return out;
}

namespace {

// The match by the lines alone (map_match.h), of maps prepared by Prepare().
MapMatch MatchLines(const std::vector<Line>& a, const SelfMatch& self_a, const std::vector<Line>& b,
                    const SelfMatch& self_b, const UncertainPose* prior, const MapMatchOptions& o) {
  MapMatch out;
  uint64_t usable_a = AllLines(static_cast<int>(a.size()));
  uint64_t usable_b = AllLines(static_cast<int>(b.size()));
  const int count_a = static_cast<int>(a.size()), count_b = static_cast<int>(b.size());
  if (count_a < o.min_support || count_b < o.min_support) {
    out.reason = MapMatchReason::kTooFewLines;
    return out;
  }
  if (o.self_match) {
    if (!self_a.complete || !self_b.complete) {
      out.reason = MapMatchReason::kWorkBound;
      return out;
    }
    // Structure that repeats within a map, where the prior cannot tell the repetition apart,
    // is not used (III-D).
    for (const SelfMatch::Repetition& r : self_a.repetitions)
      if (r.support >= o.self_min_support &&
          (prior == nullptr || InsidePrior(Compose(r.transform, prior->mean), prior, o)))
        usable_a &= ~r.lines;
    for (const SelfMatch::Repetition& r : self_b.repetitions)
      if (r.support >= o.self_min_support &&
          (prior == nullptr || InsidePrior(Compose(prior->mean, r.transform), prior, o)))
        usable_b &= ~r.lines;
    if (std::popcount(usable_a) < o.min_support || std::popcount(usable_b) < o.min_support) {
      out.result = MapMatchResult::kAmbiguous;
      out.reason = MapMatchReason::kRepetitive;
      return out;
    }
  }
  std::vector<Cluster> clusters;
  clusters.reserve(kMaxClusters);
  const Enumeration e = Hypothesise(a, usable_a, b, usable_b, /*self=*/false, o, &clusters);
  out.hypotheses = e.verified;
  if (!e.complete) {
    out.reason = MapMatchReason::kWorkBound;
    return out;
  }

  const Cluster* best = nullptr;
  bool gated_away = false;
  for (const Cluster& c : clusters) {
    if (!InsidePrior(c.t, prior, o)) {
      gated_away |= c.support.count >= o.min_support;
      continue;
    }
    if (best == nullptr || Better(c.support, best->support)) best = &c;
  }
  if (best == nullptr || best->support.count < o.min_support) {
    out.reason = gated_away ? MapMatchReason::kOutsidePrior : MapMatchReason::kTooLittleSupport;
    out.support = best ? best->support.count : 0;
    return out;
  }
  out.support = best->support.count;
  for (const Cluster& c : clusters) {
    if (&c == best || SameTransform(c.t, best->t, o) || !InsidePrior(c.t, prior, o)) continue;
    out.rival_support = std::max(out.rival_support, c.support.count);
  }
  if (out.rival_support > out.support - o.min_lead) {
    out.result = MapMatchResult::kAmbiguous;
    out.reason = MapMatchReason::kRivalTransform;
    return out;
  }
  // Condition 2 with the maps' own repetitions: a self-transform S of A (or S_b of B) makes
  // S (+) T (or T (+) S_b) a rival placement of B. It matters when it lies inside the prior's
  // gate and explains B (nearly) as well as T does, counted exactly.
  if (o.self_match) {
    int self_rival = 0;
    auto consider = [&](const Pose2& rival) {
      if (SameTransform(rival, best->t, o) || !InsidePrior(rival, prior, o)) return;
      self_rival =
          std::max(self_rival, Verify(a, usable_a, b, usable_b, RigidTransform(rival), o).count);
    };
    for (const SelfMatch::Repetition& r : self_a.repetitions)
      consider(Compose(r.transform, best->t));
    for (const SelfMatch::Repetition& r : self_b.repetitions)
      consider(Compose(best->t, r.transform));
    if (self_rival > out.support - o.min_lead) {
      out.rival_support = std::max(out.rival_support, self_rival);
      out.result = MapMatchResult::kAmbiguous;
      out.reason = MapMatchReason::kRepetitive;
      return out;
    }
  }

  Finish(a, b, best->support, best->t, prior, o, nullptr, &out);
  return out;
}

// The placement the points single out among those the lines leave open (map_match.h, "Points").
MapMatch MatchByPoints(const std::vector<Line>& a, const SelfMatch& self_a,
                       const std::vector<Line>& b, const SelfMatch& self_b,
                       const UncertainPose* prior, const MapMatchOptions& o,
                       const PointPlacements& points) {
  MapMatch out;
  out.result = MapMatchResult::kAmbiguous;
  out.reason = MapMatchReason::kRepetitive;
  const uint64_t usable_a = AllLines(static_cast<int>(a.size()));
  const uint64_t usable_b = AllLines(static_cast<int>(b.size()));
  std::vector<Cluster> clusters;
  clusters.reserve(kMaxClusters);
  const Enumeration e = Hypothesise(a, usable_a, b, usable_b, /*self=*/false, o, &clusters, prior);
  out.hypotheses = e.verified;
  if (!e.complete) return out;
  const Cluster* winner = nullptr;
  std::array<int, kMaxClusters> hits;
  int winner_hits = -1;
  for (size_t c = 0; c < clusters.size(); ++c) {
    hits[c] = -1;
    if (clusters[c].support.count < o.min_support) continue;
    hits[c] = points.Hits(clusters[c].t);
    if (hits[c] > winner_hits ||
        (hits[c] == winner_hits && Better(clusters[c].support, winner->support))) {
      winner = &clusters[c];
      winner_hits = hits[c];
    }
  }
  if (winner == nullptr) return out;
  out.support = winner->support.count;
  out.point_hits = winner_hits;
  // Every other placement inside the gate: the lines' other transforms, and the maps' own
  // repetitions of the winner (the rivals MatchLines verified on lines).
  int rival_hits = 0;
  for (size_t c = 0; c < clusters.size(); ++c)
    if (hits[c] >= 0 && !SameTransform(clusters[c].t, winner->t, o))
      rival_hits = std::max(rival_hits, hits[c]);
  auto consider = [&](const Pose2& rival) {
    if (SameTransform(rival, winner->t, o) || !InsidePrior(rival, prior, o)) return;
    rival_hits = std::max(rival_hits, points.Hits(rival));
  };
  for (const SelfMatch::Repetition& r : self_a.repetitions)
    consider(Compose(r.transform, winner->t));
  for (const SelfMatch::Repetition& r : self_b.repetitions)
    consider(Compose(winner->t, r.transform));
  out.point_rival_hits = rival_hits;
  if (winner_hits < o.point_min_hits || rival_hits > o.point_rival_ratio * winner_hits) return out;
  Finish(a, b, winner->support, winner->t, prior, o, &points, &out);
  out.by_points = out.result == MapMatchResult::kAccepted;
  return out;
}

}  // namespace

MapMatch MatchMaps(const std::vector<MapLine>& lines_a, const SelfMatch& self_a,
                   const std::vector<MapLine>& lines_b, const SelfMatch& self_b,
                   const UncertainPose* prior, const MapMatchOptions& o,
                   const FramePoints* points_a, const FramePoints* points_b) {
  const std::vector<Line> a = Prepare(lines_a, o), b = Prepare(lines_b, o);
  MapMatch lines = MatchLines(a, self_a, b, self_b, prior, o);
  const bool open_to_points = lines.result == MapMatchResult::kAmbiguous &&
                              (lines.reason == MapMatchReason::kRepetitive ||
                               lines.reason == MapMatchReason::kRivalTransform) &&
                              o.self_match && points_a != nullptr && points_b != nullptr &&
                              points_a->Size() >= o.point_min_hits &&
                              points_b->Size() >= o.point_min_hits;
  if (!open_to_points) return lines;
  MapMatch by_points =
      MatchByPoints(a, self_a, b, self_b, prior, o, PointPlacements{points_a, points_b});
  by_points.hypotheses += lines.hypotheses;
  if (by_points.result == MapMatchResult::kAccepted) return by_points;
  lines.hypotheses = by_points.hypotheses;
  lines.point_hits = by_points.point_hits;
  lines.point_rival_hits = by_points.point_rival_hits;
  return lines;
}

}  // namespace atlas
