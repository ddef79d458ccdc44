#include "core/gridmap/grid_local_map.h"

#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include "core/atlas/byte_image.h"
#include "core/gridmap/dense_search.h"
#include "core/localmap/line_ekf_map.h"

namespace atlas {
namespace {

constexpr uint32_t kMagic = 0x44524741;  // "AGRD"
constexpr uint32_t kVersion = 1;

uint64_t NewMapId() {
  static std::atomic<uint64_t> next{1};
  return next++;
}

Mat3 Symmetric(const Mat3& m) { return 0.5 * (m + m.transpose()); }

}  // namespace

std::string GridSearchOptions::Validate() const {
  if (!(min_linear_window > 0.0 && max_linear_window >= min_linear_window))
    return "linear window: need 0 < min <= max";
  if (!(min_angular_window > 0.0 && max_angular_window >= min_angular_window))
    return "angular window: need 0 < min <= max";
  if (max_points < 1 || max_nodes < 1 || work_per_step < 1)
    return "max_points, max_nodes and work_per_step must be >= 1";
  if (!(max_point_range > 0.0)) return "max_point_range: must be positive";
  if (!(min_score >= 0.0 && min_score <= 1.0) || !(min_margin >= 0.0))
    return "min_score in [0, 1], min_margin >= 0";
  if (!(max_repetition_window >= 0.0 && max_repetition_window <= 50.0))
    return "max_repetition_window: must be 0 to 50 m";
  return "";
}

std::string GridLocalMapOptions::Validate() const {
  if (std::string e = grid.Validate(); !e.empty()) return e;
  if (std::string e = bootstrap.Validate(); !e.empty()) return "bootstrap: " + e;
  if (std::string e = match.Validate(); !e.empty()) return "match: " + e;
  if (!(max_free_space_conflict >= 0.0 && max_free_space_conflict <= 1.0))
    return "max_free_space_conflict: must be in [0, 1]";
  if (std::string e = odometry.Validate(); !e.empty()) return "odometry: " + e;
  if (max_scans < 1) return "max_scans: must be at least 1";
  if (!(max_extent > 0.0)) return "max_extent: must be positive";
  if (!(insert_min_distance >= 0.0)) return "insert_min_distance: must not be negative";
  if (!(insert_min_angle >= 0.0)) return "insert_min_angle: must not be negative";
  if (!(match_max_range > grid.range.min_range)) return "match_max_range: must exceed min_range";
  if (max_points < grid.alignment.min_points) return "max_points: below alignment.min_points";
  if (!(information_scale > 0.0 && information_scale <= 1.0))
    return "information_scale: must be in (0, 1]";
  if (!(min_sigma_xy > 0.0) || !(min_sigma_theta > 0.0)) return "min_sigma: must be positive";
  if (!(gate_chi2 > 0.0)) return "gate_chi2: must be positive";
  return "";
}

GridLocalMap::GridLocalMap(const GridLocalMapOptions& options)
    : options_(options),
      id_(NewMapId()),
      grid_(options.grid.grid),
      inserter_(options.grid.grid),
      aligner_(options.grid.alignment) {}

std::unique_ptr<LocalMap> GridLocalMap::Clone() const {
  return std::make_unique<GridLocalMap>(*this);
}

void GridLocalMap::PredictWith(const Pose2& u, const Mat3& q) {
  const Mat3 j1 = ComposeJacobianA(x_, u), j2 = ComposeJacobianB(x_);
  x_ = Compose(x_, u);
  p_rel_ = Symmetric(j1 * p_rel_ * j1.transpose() + j2 * q * j2.transpose());
}

void GridLocalMap::Predict(const Pose2& odometry_delta) {
  PredictWith(odometry_delta, LineEkfMap::OdometryNoise(odometry_delta, options_.odometry));
}

void GridLocalMap::Predict(const Pose2& odometry_delta, const Mat3& covariance) {
  PredictWith(odometry_delta, covariance);
}

std::vector<Vec2> GridLocalMap::AlignmentPoints(const LaserScan& scan) const {
  RangeScanOptions range = options_.grid.range;
  range.max_range = std::min(range.max_range, options_.match_max_range);
  range.no_return_free_range = 0.0;
  RangeScan robot_frame;
  RangeScanFromLaser(scan, Pose2{}, range, &robot_frame);
  const size_t n = robot_frame.returns.size(), max = static_cast<size_t>(options_.max_points);
  if (n <= max) return robot_frame.returns;
  std::vector<Vec2> out;
  out.reserve(max);
  for (size_t k = 0; k < max; ++k) out.push_back(robot_frame.returns[k * n / max]);
  return out;
}

int GridLocalMap::ExplainedPoints(const std::vector<Vec2>& points, const Pose2& robot) const {
  const RigidTransform t(robot);
  const GridLimits& limits = grid_.limits();
  int explained = 0;
  for (const Vec2& q : points) {
    const CellIndex c = limits.CellOf(t.Apply(q));
    bool hit = false;
    for (int dy = -1; dy <= 1 && !hit; ++dy) {
      for (int dx = -1; dx <= 1 && !hit; ++dx) {
        const CellIndex n{c.x + dx, c.y + dy};
        hit = grid_.IsKnown(n) && grid_.Probability(n) > 0.5;
      }
    }
    explained += hit ? 1 : 0;
  }
  return explained;
}

ScanUpdate GridLocalMap::Update(const LaserScan& scan, bool allow_new_features) {
  last_matched_ = false;
  last_alignment_ = AlignmentResult{};
  last_points_ = AlignmentPoints(scan);
  const std::vector<Vec2>& points = last_points_;
  ScanUpdate out;
  out.observations = static_cast<int>(points.size());
  if (grid_.known_cells() > 0) {
    last_alignment_ = aligner_.Align(grid_, points, x_);
    const AlignmentOutcome o = last_alignment_.outcome;
    if (o == AlignmentOutcome::kAligned || o == AlignmentOutcome::kUnconstrained) {
      const Pose2& z = last_alignment_.pose.mean;
      Mat3 r = last_alignment_.pose.cov / options_.information_scale;
      r.diagonal() += Vec3(options_.min_sigma_xy * options_.min_sigma_xy,
                           options_.min_sigma_xy * options_.min_sigma_xy,
                           options_.min_sigma_theta * options_.min_sigma_theta);
      const Vec3 v(z.x - x_.x, z.y - x_.y, WrapAngle(z.theta - x_.theta));
      const Mat3 s = p_rel_ + r;
      const Mat3 s_inv = s.inverse();
      if (s_inv.allFinite() && v.dot(s_inv * v) <= options_.gate_chi2) {
        const Mat3 k = p_rel_ * s_inv;
        const Vec3 dx = k * v;
        x_ = Pose2{x_.x + dx(0), x_.y + dx(1), WrapAngle(x_.theta + dx(2))};
        const Mat3 i_k = Mat3::Identity() - k;
        p_rel_ = Symmetric(i_k * p_rel_ * i_k.transpose() + k * r * k.transpose());
        last_matched_ = true;
      }
    }
    out.matched = ExplainedPoints(points, x_);
  }
  if (allow_new_features) Insert(scan);
  return out;
}

void GridLocalMap::Insert(const LaserScan& scan) {
  if (full_ || static_cast<int>(inserted_.size()) >= options_.max_scans) return;
  if (!inserted_.empty()) {
    const Pose2 d = Between(inserted_.back().pose, x_);
    if (std::hypot(d.x, d.y) < options_.insert_min_distance &&
        std::abs(d.theta) < options_.insert_min_angle)
      return;
  }
  if (std::hypot(x_.x, x_.y) > options_.max_extent) {
    full_ = true;
    return;
  }
  const Mat3 cov = RobotPose().cov;
  RangeScanFromLaser(scan, x_, options_.grid.range, &scratch_);
  inserter_.Insert(scratch_, &grid_);
  inserted_.push_back(Inserted{x_, cov});
}

Mat3 GridLocalMap::GridCovarianceNear(const Vec2& p) const {
  const Inserted* nearest = nullptr;
  const Inserted* surest = nullptr;
  double best = 0.0;
  for (const Inserted& s : inserted_) {
    const double d = std::hypot(s.pose.x - p.x(), s.pose.y - p.y());
    if (nearest == nullptr || d < best) {
      nearest = &s;
      best = d;
    }
    if (d <= options_.grid_cov_radius && (surest == nullptr || s.cov.trace() < surest->cov.trace()))
      surest = &s;
  }
  if (surest != nullptr) return surest->cov;
  return nearest != nullptr ? nearest->cov : Mat3::Zero();
}

UncertainPose GridLocalMap::RobotPose() const {
  return UncertainPose{x_, Symmetric(p_rel_ + GridCovarianceNear(Vec2(x_.x, x_.y)))};
}

void GridLocalMap::ResetRobotPose(const UncertainPose& pose) {
  x_ = pose.mean;
  p_rel_ = Symmetric(pose.cov);
}

int GridLocalMap::Complexity() const {
  return full_ ? options_.max_scans : static_cast<int>(inserted_.size());
}

std::vector<Vec2> GridLocalMap::Points(int max_points) const {
  return EvenSubsample(OccupiedCellCenters(grid_, kOccupiedProbability), max_points);
}

bool GridLocalMap::Reaches(const Vec2& point, double reach) const {
  for (const Inserted& s : inserted_) {
    if (std::hypot(s.pose.x - point.x(), s.pose.y - point.y()) <= reach) return true;
  }
  return false;
}

std::string GridLocalMap::Serialize() const {
  ByteWriter w;
  w.Put(kMagic);
  w.Put(kVersion);
  w.PutPose(x_);
  w.PutMat3(p_rel_);
  w.Put<uint8_t>(full_ ? 1 : 0);
  w.Put<int32_t>(static_cast<int32_t>(inserted_.size()));
  for (const Inserted& s : inserted_) {
    w.PutPose(s.pose);
    w.PutMat3(s.cov);
  }
  const GridLimits& l = grid_.limits();
  w.Put(l.resolution);
  w.Put<int32_t>(l.offset.x);
  w.Put<int32_t>(l.offset.y);
  w.Put<int32_t>(l.width);
  w.Put<int32_t>(l.height);
  w.PutArray(grid_.values().data(), grid_.values().size());
  return std::move(w.bytes());
}

bool GridLocalMap::Deserialize(const std::string& bytes) {
  ByteReader r(bytes);
  uint32_t magic = 0, version = 0;
  if (!r.Get(&magic) || magic != kMagic || !r.Get(&version) || version != kVersion) return false;
  Pose2 x;
  Mat3 p;
  uint8_t full = 0;
  int32_t n = 0;
  if (!r.GetPose(&x) || !r.GetMat3(&p) || !r.Get(&full) || full > 1 || !r.Get(&n) || n < 0 ||
      n > options_.max_scans)
    return false;
  if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.theta) || !p.allFinite())
    return false;
  std::vector<Inserted> inserted(n);
  for (Inserted& s : inserted) {
    if (!r.GetPose(&s.pose) || !r.GetMat3(&s.cov) || !s.cov.allFinite()) return false;
  }
  double resolution = 0.0;
  int32_t ox = 0, oy = 0, width = 0, height = 0;
  if (!r.Get(&resolution) || resolution != options_.grid.grid.resolution || !r.Get(&ox) ||
      !r.Get(&oy) || !r.Get(&width) || !r.Get(&height) || width < 0 || height < 0 ||
      width > options_.grid.grid.max_cells || height > options_.grid.grid.max_cells)
    return false;
  std::vector<uint16_t> values(static_cast<size_t>(width) * height);
  if (!r.GetArray(values.data(), values.size()) || !r.AtEnd()) return false;
  // The window as it was written (not regrown around the cells), so that the map reads back
  // byte for byte and grows on as it would have.
  ProbabilityGrid grid(options_.grid.grid);
  if (width > 0 && height > 0 && !grid.Restore(CellIndex{ox, oy}, width, height, std::move(values)))
    return false;
  id_ = NewMapId();
  x_ = x;
  p_rel_ = Symmetric(p);
  full_ = full == 1;
  inserted_ = std::move(inserted);
  grid_ = std::move(grid);
  last_alignment_ = AlignmentResult{};
  last_matched_ = false;
  return true;
}

}  // namespace atlas
