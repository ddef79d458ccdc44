#pragma once
// A fake LocalMap for the atlas's unit tests and benchmarks: no scan processing, scripted
// outcomes. Stands in for the EKF line map (core/localmap) so that the atlas can be tested on
// its own.
//
// Behaviour:
// - Predict composes the odometry increment and grows the covariance (first order, noise
//   proportional to distance and turn).
// - Update reports `observations` = the number of beams with a return (or the script's count)
//   and `matched` from the script (default: min(observations, Complexity())). When new
//   features are allowed and the map is below capacity, it adds one line every
//   `scans_per_feature` scans, placed 2 m from the robot. With matched >= 2 the pose
//   covariance shrinks by `update_shrink` (a crude measurement update).
// - A world script lets a test make a map explain observations only near its origin, so that
//   q falls when the robot leaves it (traversal, Genesis, loops).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/atlas/hypothesis.h"
#include "core/localmap/local_map.h"

namespace atlas {

struct FakeWorldScript {
  // Matched observations for a map tagged `tag` with the robot at `pose` (map frame).
  std::function<int(int tag, const Pose2& pose, int observations, int complexity)> matched;
  int observations = -1;  // >= 0 overrides the count of returns
  // Lines a map reports (in its own frame), by tag; empty = the map's own grown lines.
  std::function<std::vector<MapLine>(int tag)> lines;
  // Where a map puts the robot after an update (a mislocalisation), by tag; empty = unchanged.
  std::function<Pose2(int tag, const Pose2& pose)> relocate;
};

struct FakeLocalMapOptions {
  int capacity = 10;
  int scans_per_feature = 1;
  double sigma_per_metre = 0.05;
  double sigma_theta_per_radian = 0.05;
  double sigma_theta_per_metre = 0.01;
  double update_shrink = 0.5;
  // Bytes appended to the map's image (as large an image as a grid frame's, for benchmarks).
  int image_padding = 0;
};

class FakeLocalMap : public LocalMap {
 public:
  using Options = FakeLocalMapOptions;

  explicit FakeLocalMap(Options o = Options(),
                        std::shared_ptr<const FakeWorldScript> script = nullptr, int tag = 0)
      : o_(o), script_(std::move(script)), tag_(tag) {}

  std::unique_ptr<LocalMap> Clone() const override { return std::make_unique<FakeLocalMap>(*this); }

  void Predict(const Pose2& d) override {
    const double dist = std::hypot(d.x, d.y);
    const Vec3 q(
        std::pow(o_.sigma_per_metre * dist, 2), std::pow(o_.sigma_per_metre * dist, 2),
        std::pow(o_.sigma_theta_per_radian * std::abs(d.theta) + o_.sigma_theta_per_metre * dist,
                 2));
    Predict(d, Mat3(q.asDiagonal()));
  }

  void Predict(const Pose2& d, const Mat3& q) override {
    const Mat3 j1 = ComposeJacobianA(pose_.mean, d);
    const Mat3 j2 = ComposeJacobianB(pose_.mean);
    pose_.cov = j1 * pose_.cov * j1.transpose() + j2 * q * j2.transpose();
    pose_.mean = Compose(pose_.mean, d);
    ++predicts_;
  }

  using LocalMap::Update;
  ScanUpdate Update(const LaserScan& scan, bool allow_new_features) override {
    ScanUpdate u;
    if (script_ && script_->observations >= 0) {
      u.observations = script_->observations;
    } else {
      u.observations = static_cast<int>(std::count_if(scan.ranges.begin(), scan.ranges.end(),
                                                      [](float r) { return IsReturn(r); }));
    }
    if (script_ && script_->matched)
      u.matched = script_->matched(tag_, pose_.mean, u.observations, Complexity());
    else
      u.matched = std::min(u.observations, Complexity());
    u.matched = std::clamp(u.matched, 0, u.observations);
    ++scans_;
    if (allow_new_features && Complexity() < o_.capacity && scans_ % o_.scans_per_feature == 0) {
      MapLine l;
      l.id = static_cast<int>(lines_.size());
      const double a = pose_.mean.theta + (l.id % 4) * 1.5707963267948966;
      const Vec2 n(std::cos(a), std::sin(a));
      const Vec2 c = Vec2(pose_.mean.x, pose_.mean.y) + 2.0 * n;
      l.alpha = WrapAngle(a);
      l.rho = c.dot(n);
      if (l.rho < 0) {
        l.rho = -l.rho;
        l.alpha = WrapAngle(l.alpha + 3.141592653589793);
      }
      l.cov = Eigen::Matrix2d::Identity() * 1e-4;
      const Vec2 dir(-n.y(), n.x());
      l.endpoint_a = c - dir;
      l.endpoint_b = c + dir;
      lines_.push_back(l);
      ++u.added;
    }
    if (u.matched >= 2) pose_.cov *= o_.update_shrink;
    if (script_ && script_->relocate) pose_.mean = script_->relocate(tag_, pose_.mean);
    ++updates_;
    last_allow_new_ = allow_new_features;
    return u;
  }

  UncertainPose RobotPose() const override { return pose_; }
  void ResetRobotPose(const UncertainPose& pose) override { pose_ = pose; }
  int Complexity() const override { return static_cast<int>(lines_.size()); }
  int Capacity() const override { return o_.capacity; }
  std::vector<MapLine> Lines() const override {
    if (script_ && script_->lines) return script_->lines(tag_);
    return lines_;
  }

  std::string Serialize() const override {
    std::string s = "FAKE";
    Put(&s, tag_);
    Put(&s, scans_);
    for (double v : {pose_.mean.x, pose_.mean.y, pose_.mean.theta}) Put(&s, v);
    for (int k = 0; k < 9; ++k) Put(&s, pose_.cov.data()[k]);
    Put(&s, static_cast<int>(lines_.size()));
    for (const MapLine& l : lines_) {
      Put(&s, l.id);
      for (double v : {l.rho, l.alpha, l.cov(0, 0), l.cov(0, 1), l.cov(1, 0), l.cov(1, 1),
                       l.endpoint_a.x(), l.endpoint_a.y(), l.endpoint_b.x(), l.endpoint_b.y()})
        Put(&s, v);
    }
    s.append(static_cast<size_t>(o_.image_padding), 'p');
    return s;
  }
  bool Deserialize(const std::string& bytes) override {
    if (bytes.size() < 4 || bytes.compare(0, 4, "FAKE") != 0) return false;
    size_t at = 4;
    FakeLocalMap copy = *this;
    int n = 0;
    if (!Get(bytes, &at, &copy.tag_) || !Get(bytes, &at, &copy.scans_) ||
        !Get(bytes, &at, &copy.pose_.mean.x) || !Get(bytes, &at, &copy.pose_.mean.y) ||
        !Get(bytes, &at, &copy.pose_.mean.theta) || !GetMat(bytes, &at, &copy.pose_.cov) ||
        !Get(bytes, &at, &n) || n < 0 || n > 100000)
      return false;
    copy.lines_.assign(n, MapLine{});
    for (MapLine& l : copy.lines_) {
      double* fields[] = {
          &l.rho,       &l.alpha,          &l.cov(0, 0),      &l.cov(0, 1),      &l.cov(1, 0),
          &l.cov(1, 1), &l.endpoint_a.x(), &l.endpoint_a.y(), &l.endpoint_b.x(), &l.endpoint_b.y()};
      if (!Get(bytes, &at, &l.id)) return false;
      for (double* f : fields)
        if (!Get(bytes, &at, f)) return false;
    }
    if (bytes.size() - at != static_cast<size_t>(o_.image_padding)) return false;
    *this = copy;
    return true;
  }

  int tag() const { return tag_; }
  int updates() const { return updates_; }
  int predicts() const { return predicts_; }
  bool last_allow_new() const { return last_allow_new_; }
  void AddLine(const MapLine& l) { lines_.push_back(l); }

 private:
  template <typename T>
  static void Put(std::string* s, const T& v) {
    s->append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  static bool Get(const std::string& s, size_t* at, T* v) {
    if (s.size() - *at < sizeof(T)) return false;
    std::memcpy(static_cast<void*>(v), s.data() + *at, sizeof(T));
    *at += sizeof(T);
    return true;
  }

  static bool GetMat(const std::string& s, size_t* at, Mat3* m) {
    for (int k = 0; k < 9; ++k)
      if (!Get(s, at, &m->data()[k])) return false;
    return true;
  }

  Options o_;
  std::shared_ptr<const FakeWorldScript> script_;
  int tag_ = 0;
  int scans_ = 0;
  int updates_ = 0;
  int predicts_ = 0;
  bool last_allow_new_ = false;
  UncertainPose pose_;
  std::vector<MapLine> lines_;
};

// w (eq. 12) for tests: solved when Z holds at least `min_matched` matched observations (else
// `unsolved`: kFailed, or kUndetermined to make the atlas accumulate Z); the pose is the map's
// current estimate.
class FakeBootstrapper : public PoseBootstrapper {
 public:
  explicit FakeBootstrapper(int min_matched = 1,
                            BootstrapOutcome unsolved = BootstrapOutcome::kFailed,
                            bool from_sonar = false)
      : min_matched_(min_matched), unsolved_(unsolved), from_sonar_(from_sonar) {}
  bool FromSonar() const override { return from_sonar_; }
  PoseBootstrap Solve(const LocalMap& map, const LocalMap& /*frame_map*/,
                      const std::vector<JuvenileScan>& z,
                      const UncertainPose& /*seed*/) const override {
    ++calls_;
    max_z_ = std::max(max_z_, static_cast<int>(z.size()));
    int matched = 0;
    for (const JuvenileScan& s : z) matched += s.update.matched;
    PoseBootstrap r;
    if (matched < min_matched_) {
      r.outcome = unsolved_;
      return r;
    }
    r.outcome = BootstrapOutcome::kSolved;
    r.pose = map.RobotPose();
    return r;
  }
  int calls() const { return calls_; }
  int max_z() const { return max_z_; }  // the largest Z passed to Solve

 private:
  int min_matched_;
  BootstrapOutcome unsolved_;
  bool from_sonar_;
  mutable int calls_ = 0;
  mutable int max_z_ = 0;
};

}  // namespace atlas
