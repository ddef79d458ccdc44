#include "sim/route.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace atlas::sim {
namespace {

double Angle(const Vec2& v) { return std::atan2(v.y(), v.x()); }

}  // namespace

std::vector<int> PlanRoute(const World& world, double length_m, int start, uint64_t seed) {
  const int n = static_cast<int>(world.nodes.size());
  const std::vector<std::vector<int>> adjacent = RouteAdjacency(world);
  std::vector<int> route;
  if (start < 0 || start >= n || adjacent[start].empty()) return route;
  std::mt19937_64 rng(seed);
  std::map<std::pair<int, int>, int> driven;
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  const auto pos = [&](int i) { return world.nodes[i].position; };

  route.push_back(start);
  int previous = -1, current = start;
  double length = 0.0;
  std::vector<double> weights;
  while (length < length_m) {
    const auto& next = adjacent[current];
    weights.assign(next.size(), 0.0);
    for (size_t k = 0; k < next.size(); ++k) {
      if (next[k] == previous && next.size() > 1) continue;
      const int times = driven[key(current, next[k])];
      double w = 1.0 / ((1.0 + times) * (1.0 + times));
      if (previous >= 0) {
        const double turn =
            std::remainder(Angle(pos(next[k]) - pos(current)) - Angle(pos(current) - pos(previous)),
                           2.0 * std::numbers::pi);
        if (std::abs(turn) < 0.5) w *= 2.0;
      }
      weights[k] = w;
    }
    const size_t pick = std::discrete_distribution<size_t>(weights.begin(), weights.end())(rng);
    const int chosen = next[pick];
    ++driven[key(current, chosen)];
    length += (pos(chosen) - pos(current)).norm();
    previous = current;
    current = chosen;
    route.push_back(current);
  }
  return route;
}

std::string MotionOptions::Validate() const {
  if (!(max_speed > 0.0 && max_speed <= 5.0)) return "max_speed must be in (0, 5] m/s";
  if (!(max_turn_rate > 0.0 && max_turn_rate <= 10.0))
    return "max_turn_rate must be in (0, 10] rad/s";
  if (!(max_accel > 0.0) || !(max_turn_accel > 0.0)) return "accelerations must be positive";
  if (!(heading_gain > 0.0)) return "heading_gain must be positive";
  if (!(drive_heading_error > 0.0 && drive_heading_error < 1.5))
    return "drive_heading_error must be in (0, 1.5) rad";
  return "";
}

DiffDriveFollower::DiffDriveFollower(const MotionOptions& options, std::vector<Vec2> waypoints)
    : o_(options), waypoints_(std::move(waypoints)) {
  if (waypoints_.empty()) waypoints_.push_back(Vec2::Zero());
  pose_ = Pose2{waypoints_[0].x(), waypoints_[0].y(), 0.0};
  // Drop repeated points and face the first distinct one.
  std::vector<Vec2> clean{waypoints_[0]};
  for (const Vec2& p : waypoints_)
    if ((p - clean.back()).norm() > 1e-6) clean.push_back(p);
  waypoints_ = std::move(clean);
  if (waypoints_.size() > 1) pose_.theta = Angle(waypoints_[1] - waypoints_[0]);
}

bool DiffDriveFollower::Step(double dt) {
  if (target_ >= waypoints_.size()) {
    v_ = w_ = 0.0;
    return false;
  }
  const Vec2 here(pose_.x, pose_.y);
  Vec2 goal = waypoints_[target_];
  const Vec2 seg_dir = (goal - waypoints_[target_ - 1]).normalized();
  // Reached (or passed the perpendicular through) the waypoint: aim at the next one.
  if ((here - goal).norm() < 0.05 ||
      ((here - goal).dot(seg_dir) > -0.02 && (here - goal).norm() < 0.4)) {
    ++target_;
    if (target_ >= waypoints_.size()) {
      v_ = w_ = 0.0;
      return false;
    }
    goal = waypoints_[target_];
  }
  const Vec2 to_goal = goal - here;
  const double dist = to_goal.norm();
  const double error = std::remainder(Angle(to_goal) - pose_.theta, 2.0 * std::numbers::pi);

  // Speed at the waypoint: slow for a sharp corner, zero at the end.
  double corner_speed = 0.0;
  if (target_ + 1 < waypoints_.size()) {
    const Vec2 next_dir = waypoints_[target_ + 1] - goal;
    const double turn =
        std::abs(std::remainder(Angle(next_dir) - Angle(to_goal), 2.0 * std::numbers::pi));
    corner_speed = o_.max_speed * std::clamp(1.0 - turn / o_.drive_heading_error, 0.0, 1.0);
  }
  double v_des = std::min(o_.max_speed,
                          std::sqrt(corner_speed * corner_speed + 2.0 * 0.8 * o_.max_accel * dist));
  v_des *= std::clamp(1.0 - std::abs(error) / o_.drive_heading_error, 0.0, 1.0);
  double w_des = std::clamp(o_.heading_gain * error, -o_.max_turn_rate, o_.max_turn_rate);
  // Turn-rate change limited, but never so that it overshoots the heading.
  const double w_stop = std::sqrt(2.0 * o_.max_turn_accel * std::abs(error));
  w_des = std::clamp(w_des, -w_stop, w_stop);

  v_ += std::clamp(v_des - v_, -o_.max_accel * dt, o_.max_accel * dt);
  w_ += std::clamp(w_des - w_, -o_.max_turn_accel * dt, o_.max_turn_accel * dt);
  const double ds = v_ * dt, dth = w_ * dt;
  const double h = 0.5 * dth;
  const double chord = std::abs(h) < 1e-9 ? ds : ds * std::sin(h) / h;
  pose_ = Compose(pose_, Pose2{chord * std::cos(h), chord * std::sin(h), dth});
  distance_ += std::abs(ds);
  return true;
}

}  // namespace atlas::sim
