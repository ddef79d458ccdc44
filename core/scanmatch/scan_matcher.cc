#include "core/scanmatch/scan_matcher.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace atlas {
namespace {

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }

// atan2 to about 1e-5 rad (a minimax polynomial on [0, 1]); the beam lookup needs far less than
// a beam's width and this is called for every point in every iteration.
double FastAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay);
  if (hi == 0.0) return 0.0;
  const double a = std::min(ax, ay) / hi;
  const double s = a * a;
  double r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
  if (ay > ax) r = 1.57079632679489661923 - r;
  if (x < 0.0) r = 3.14159265358979323846 - r;
  return y < 0.0 ? -r : r;
}

}  // namespace

std::string ScanMatchOptions::Validate() const {
  if (!(min_range >= 0.0) || !(max_range > min_range) || !std::isfinite(max_range))
    return "scan_match: need 0 <= min_range < max_range (finite)";
  if (!Positive(point_sigma)) return "scan_match: point_sigma must be > 0";
  if (!Positive(information_scale) || information_scale > 1.0)
    return "scan_match: information_scale must be in (0, 1]";
  if (!Positive(huber_k)) return "scan_match: huber_k must be > 0";
  if (normal_beams < 1 || normal_beams > kMaxNormalBeams)
    return "scan_match: normal_beams must be 1 to " + std::to_string(kMaxNormalBeams);
  if (!Positive(normal_radius)) return "scan_match: normal_radius must be > 0";
  if (!Positive(max_normal_rms)) return "scan_match: max_normal_rms must be > 0";
  if (!(min_normal_extent >= 0.0) || min_normal_extent >= normal_radius)
    return "scan_match: min_normal_extent must be 0 or more and below normal_radius";
  if (!(min_point_spacing >= 0.0) || min_point_spacing > 1.0)
    return "scan_match: min_point_spacing must be 0 to 1 m";
  if (search_beams < 0 || search_beams > 64) return "scan_match: search_beams must be 0 to 64";
  if (!Positive(final_distance) || !(max_distance >= final_distance))
    return "scan_match: need 0 < final_distance <= max_distance";
  if (coarse_iterations < 0 || max_iterations < 1 || coarse_iterations >= max_iterations)
    return "scan_match: need 0 <= coarse_iterations < max_iterations";
  if (max_iterations > 100) return "scan_match: max_iterations must be at most 100";
  if (!(heading_search >= 0.0) || heading_search > 1.0)
    return "scan_match: heading_search must be 0 to 1 rad";
  if ((heading_search > 0.0 || recovery_heading_search > 0.0) && !Positive(heading_step))
    return "scan_match: heading_step must be > 0 (the heading searches step by it)";
  if (heading_search > 0.0 && heading_search / heading_step > 200.0)
    return "scan_match: heading_step must be at least heading_search / 200";
  if (!Positive(coarse_distance)) return "scan_match: coarse_distance must be > 0";
  if (!(recovery_heading_search >= 0.0) || recovery_heading_search > 1.6)
    return "scan_match: recovery_heading_search must be 0 to 1.6 rad";
  if (recovery_heading_search > 0.0 && recovery_heading_search / heading_step > 200.0)
    return "scan_match: recovery_heading_search must be at most 200 heading_steps";
  if (!Positive(recovery_sigma_xy)) return "scan_match: recovery_sigma_xy must be > 0";
  if (min_pairs < 3) return "scan_match: min_pairs must be at least 3";
  if (!(min_pair_fraction >= 0.0) || min_pair_fraction > 1.0)
    return "scan_match: min_pair_fraction must be 0 to 1";
  return "";
}

const char* ToString(ScanMatchOutcome o) {
  switch (o) {
    case ScanMatchOutcome::kMatched:
      return "matched";
    case ScanMatchOutcome::kTooFewPoints:
      return "too few points";
    case ScanMatchOutcome::kTooFewPairs:
      return "too few pairs";
    case ScanMatchOutcome::kNotConverged:
      return "not converged";
  }
  return "?";
}

const std::vector<Vec2>& BeamDirections::Of(const LaserScan& scan) {
  if (scan.ranges.size() != directions_.size() || scan.angle_min != angle_min_ ||
      scan.angle_increment != angle_increment_) {
    angle_min_ = scan.angle_min;
    angle_increment_ = scan.angle_increment;
    directions_.resize(scan.ranges.size());
    for (size_t i = 0; i < directions_.size(); ++i) {
      const double phi = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
      directions_[i] = Vec2(std::cos(phi), std::sin(phi));
    }
  }
  return directions_;
}

void ScanPointsInRobotFrame(const LaserScan& scan, const std::vector<Vec2>& directions,
                            double min_range, double max_range, std::vector<Vec2>* points) {
  points->clear();
  const RigidTransform sensor(scan.sensor_pose);
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    const double r = scan.ranges[i];
    if (!(r >= min_range && r <= max_range)) continue;
    points->push_back(sensor.Apply(Vec2(r * directions[i].x(), r * directions[i].y())));
  }
}

ScanMatcher::ScanMatcher(const ScanMatchOptions& options) : options_(options) {}

void ScanMatcher::SetReference(const LaserScan& scan) {
  const size_t n = scan.ranges.size();
  ref_.assign(n, RefPoint{});
  ref_sensor_inverse_ = RigidTransform(Inverse(scan.sensor_pose));
  const RigidTransform sensor(scan.sensor_pose);
  ref_angle_min_ = scan.angle_min;
  ref_increment_ = scan.angle_increment;
  has_reference_ = n > 0 && ref_increment_ != 0.0 && std::isfinite(ref_increment_);
  const std::vector<Vec2>& directions = directions_.Of(scan);
  for (size_t i = 0; i < n; ++i) {
    const double r = scan.ranges[i];
    if (!(r >= options_.min_range && r <= options_.max_range)) continue;
    ref_[i].p = sensor.Apply(Vec2(r * directions[i].x(), r * directions[i].y()));
    ref_[i].valid = true;
  }
  const int k = options_.normal_beams;
  const double r2 = options_.normal_radius * options_.normal_radius;
  for (size_t i = 0; i < n; ++i) {
    if (!ref_[i].valid) continue;
    Vec2 mean = Vec2::Zero();
    int count = 0;
    size_t near[2 * kMaxNormalBeams + 1];
    const size_t lo = i >= static_cast<size_t>(k) ? i - k : 0;
    const size_t hi = std::min(n - 1, i + k);
    for (size_t j = lo; j <= hi; ++j) {
      if (!ref_[j].valid || (ref_[j].p - ref_[i].p).squaredNorm() > r2) continue;
      mean += ref_[j].p;
      near[count++] = j;
    }
    if (count < 3) continue;
    mean /= count;
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (int m = 0; m < count; ++m) {
      const Vec2 d = ref_[near[m]].p - mean;
      cov += d * d.transpose();
    }
    cov /= count;
    // Eigen-decomposition of the symmetric 2x2 scatter, closed form: the normal is the
    // eigenvector of the smaller eigenvalue.
    const double a = cov(0, 0), b = cov(0, 1), d = cov(1, 1);
    const double half_trace = 0.5 * (a + d);
    const double root = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
    const double small = half_trace - root, large = half_trace + root;
    if (!(std::sqrt(std::max(0.0, small)) <= options_.max_normal_rms)) continue;
    if (!(std::sqrt(std::max(0.0, large)) >= options_.min_normal_extent)) continue;
    const Vec2 u1(b, small - a), u2(small - d, b);
    const Vec2 n = u1.squaredNorm() >= u2.squaredNorm() ? u1 : u2;
    if (!(n.squaredNorm() > 0.0)) continue;
    ref_[i].n = n.normalized();
    ref_[i].has_normal = true;
  }
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  with_normal_.assign(n, Vec2(kInfinity, kInfinity));
  for (size_t i = 0; i < n; ++i)
    if (ref_[i].has_normal) with_normal_[i] = ref_[i].p;
}

const ScanMatcher::RefPoint* ScanMatcher::Nearest(const Vec2& w, double max_distance) const {
  const Vec2 s = ref_sensor_inverse_.Apply(w);
  const double beam = (FastAtan2(s.y(), s.x()) - ref_angle_min_) / ref_increment_;
  if (!(std::abs(beam) < 1e6)) return nullptr;  // NaN, or an absurd beam spacing
  const long n = static_cast<long>(ref_.size());
  const long centre = std::lround(beam);
  const long lo = std::max(0L, centre - options_.search_beams);
  const long hi = std::min(n - 1, centre + options_.search_beams);
  long best = -1;
  double best_d2 = max_distance * max_distance;
  for (long j = lo; j <= hi; ++j) {
    const double d2 = (w - with_normal_[j]).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = j;
    }
  }
  return best >= 0 ? &ref_[best] : nullptr;
}

int ScanMatcher::CountPairs(const Pose2& x, const std::vector<Vec2>& points,
                            double max_distance) const {
  const RigidTransform rigid(x);
  int count = 0;
  for (size_t i = 0; i < points.size(); i += 2)
    if (Nearest(rigid.Apply(points[i]), max_distance) != nullptr) ++count;
  return count;
}

Pose2 ScanMatcher::SearchHeading(const Pose2& u, double half_width) const {
  Pose2 x = u;
  if (!(half_width > 0.0)) return x;
  const int steps = static_cast<int>(half_width / options_.heading_step);
  int best = -1;
  for (int k = 0; k <= steps; ++k) {
    for (int sign : {1, -1}) {
      if (k == 0 && sign < 0) continue;
      Pose2 trial = u;
      trial.theta = WrapAngle(u.theta + sign * k * options_.heading_step);
      const int count = CountPairs(trial, points_, options_.coarse_distance);
      if (count > best) {
        best = count;
        x = trial;
      }
    }
  }
  return x;
}

ScanMatchResult ScanMatcher::Match(const LaserScan& scan, const UncertainPose& prior) {
  ScanMatchResult out;
  out.increment = prior;
  ScanPointsInRobotFrame(scan, directions_.Of(scan), options_.min_range, options_.max_range,
                         &points_);
  if (options_.min_point_spacing > 0.0 && !points_.empty()) {
    const double d2 = options_.min_point_spacing * options_.min_point_spacing;
    size_t kept = 1;
    for (size_t i = 1; i < points_.size(); ++i)
      if ((points_[i] - points_[kept - 1]).squaredNorm() >= d2) points_[kept++] = points_[i];
    points_.resize(kept);
  }
  out.points = static_cast<int>(points_.size());
  if (!has_reference_ || out.points < options_.min_pairs) return out;
  Solve(SearchHeading(prior.mean, options_.heading_search), prior, &out);
  if (out.outcome == ScanMatchOutcome::kMatched || !(options_.recovery_heading_search > 0.0))
    return out;
  // The scans do not pair at the odometry's increment: the wheels are wrong by more than the
  // prior allows (or the view changed). Search wider, with the odometry as a weak prior.
  UncertainPose weak = prior;
  const double sxy = options_.recovery_sigma_xy, st = options_.recovery_heading_search;
  weak.cov = Vec3(sxy * sxy, sxy * sxy, st * st).asDiagonal();
  ScanMatchResult retry = out;
  Solve(SearchHeading(prior.mean, options_.recovery_heading_search), weak, &retry);
  if (retry.outcome == ScanMatchOutcome::kMatched) {
    retry.recovered = true;
    return retry;
  }
  return out;
}

void ScanMatcher::Solve(const Pose2& start, const UncertainPose& prior,
                        ScanMatchResult* out) const {
  const Pose2& u = prior.mean;
  Pose2 x = start;
  const Mat3 q_inverse = (prior.cov + 1e-12 * Mat3::Identity()).inverse();
  const double inv_var = 1.0 / (options_.point_sigma * options_.point_sigma);
  const double huber = options_.huber_k * options_.point_sigma;
  const double scale = options_.information_scale;
  Mat3 h_icp = Mat3::Zero();
  bool converged = false;
  int pairs = 0;
  double sum_r2 = 0.0;
  for (int it = 0; it < options_.max_iterations; ++it) {
    const bool final_pass = it >= options_.coarse_iterations;
    const double distance = final_pass ? options_.final_distance : options_.max_distance;
    const RigidTransform rigid(x);
    const double c = rigid.c, s = rigid.s;
    h_icp.setZero();
    Vec3 g = Vec3::Zero();
    pairs = 0;
    sum_r2 = 0.0;
    for (const Vec2& q : points_) {
      const Vec2 w = rigid.Apply(q);
      const RefPoint* ref = Nearest(w, distance);
      if (ref == nullptr) continue;
      const double r = ref->n.dot(w - ref->p);
      const Vec2 dw(-s * q.x() - c * q.y(), c * q.x() - s * q.y());
      const Vec3 j(ref->n.x(), ref->n.y(), ref->n.dot(dw));
      const double weight = std::abs(r) <= huber ? 1.0 : huber / std::abs(r);
      h_icp += weight * inv_var * j * j.transpose();
      g += weight * inv_var * r * j;
      ++pairs;
      sum_r2 += r * r;
    }
    const Vec3 e(x.x - u.x, x.y - u.y, WrapAngle(x.theta - u.theta));
    const Mat3 h = scale * h_icp + q_inverse;
    const Vec3 dx = -h.ldlt().solve(scale * g + q_inverse * e);
    if (!dx.allFinite()) break;
    x.x += dx(0);
    x.y += dx(1);
    x.theta = WrapAngle(x.theta + dx(2));
    out->iterations = it + 1;
    // A step of a tenth of a sigma or less: done (the pairing may toggle between two sets
    // one point apart, which moves x by far less than its uncertainty).
    if (final_pass && dx.dot(h * dx) < 1e-2) {
      converged = true;
      break;
    }
  }
  out->pairs = pairs;
  out->rms = pairs > 0 ? std::sqrt(sum_r2 / pairs) : 0.0;
  if (!converged) {
    out->outcome = ScanMatchOutcome::kNotConverged;
    return;
  }
  if (pairs < options_.min_pairs || pairs < options_.min_pair_fraction * out->points) {
    out->outcome = ScanMatchOutcome::kTooFewPairs;
    return;
  }
  Mat3 cov = (scale * h_icp + q_inverse).inverse();
  cov = 0.5 * (cov + cov.transpose());
  out->outcome = ScanMatchOutcome::kMatched;
  out->increment = UncertainPose{x, cov};
}

}  // namespace atlas
