#include "core/grid/branch_and_bound.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace atlas {
namespace {

// The sum of `level`'s values at the n binned points moved by (x, y) cells.
int64_t PlacementSum(const PrecomputationGrid& level, const CellIndex* cells, int n, int x, int y) {
  int64_t sum = 0;
  for (int i = 0; i < n; ++i) sum += level.At(CellIndex{cells[i].x + x, cells[i].y + y});
  return sum;
}

SearchWindow WindowFor(const PrecomputationGridStack& grids, const std::vector<Vec2>& points,
                       const BranchAndBoundOptions& options) {
  const double r = grids.limits().resolution;
  return MakeSearchWindow(options.linear_window, options.angular_window, r,
                          AngularSearchStep(points, r, 0.0));
}

// The smallest sum whose mean probability over `points` points is at least `min_score`.
int64_t MinimumSum(const PrecomputationGridStack& grids, double min_score, int points) {
  const double t =
      (min_score - grids.min_probability()) / (grids.max_probability() - grids.min_probability());
  return std::max<int64_t>(0, static_cast<int64_t>(std::ceil(t * 255.0 * points - 1e-9)));
}

void SetPlacement(const PrecomputationGridStack& grids, const Pose2& center,
                  const SearchWindow& window, int points, const Placement& p, int64_t sum,
                  MatchPlacement* m) {
  m->found = true;
  m->placement = p;
  m->sum = sum;
  m->pose = PlacementPose(p, center, window, grids.limits().resolution);
  m->score = grids.MeanProbability(sum, points);
}

void SetMargin(const PrecomputationGridStack& grids, BranchAndBoundResult* r) {
  if (!r->best.found) return;
  r->margin = r->best.score - (r->runner_up.found ? r->runner_up.score : grids.min_probability());
}

}  // namespace

BranchAndBoundSearch::BranchAndBoundSearch(const PrecomputationGridStack& grids,
                                           const std::vector<Vec2>& points, const Pose2& center,
                                           const BranchAndBoundOptions& options,
                                           const Placement* outside_of)
    : grids_(grids),
      options_(options),
      center_(center),
      window_(WindowFor(grids, points, options)) {
  assert(options_.Validate().empty());
  assert(grids.complete());
  DiscretizeScans(grids.limits(), points, center, window_, &scans_);
  min_sum_ = MinimumSum(grids, options.min_score, scans_.points);
  if (outside_of != nullptr) {
    outside_ = true;
    peak_ = MakePeak(*outside_of, options_.peak_distance, options_.peak_angle,
                     grids.limits().resolution, window_);
  }
  stack_.resize(grids.depth());
  if (scans_.points == 0) {
    phase_ = Phase::kDone;
    return;
  }
  PushChildren(nullptr);
}

int64_t BranchAndBoundSearch::Score(const Node& node) const {
  return PlacementSum(grids_.Level(node.level), scans_.Heading(node.placement.heading),
                      scans_.points, node.placement.x, node.placement.y);
}

void BranchAndBoundSearch::PushChildren(const Node* node) {
  Frame& f = stack_[depth_++];
  f.nodes.clear();
  f.scored = 0;
  f.sorted = false;
  f.next = 0;
  const int limit = window_.linear_cells;
  if (node == nullptr) {
    const int level = grids_.depth() - 1, width = 1 << level;
    for (int h = 0; h < window_.headings(); ++h) {
      for (int y = -limit; y <= limit; y += width) {
        for (int x = -limit; x <= limit; x += width) f.nodes.push_back(Node{{h, x, y}, level, 0});
      }
    }
    return;
  }
  const int level = node->level - 1, half = 1 << level;
  const Placement& p = node->placement;
  for (int dy : {0, half}) {
    for (int dx : {0, half}) {
      if (p.x + dx <= limit && p.y + dy <= limit) {
        f.nodes.push_back(Node{{p.heading, p.x + dx, p.y + dy}, level, 0});
      }
    }
  }
}

void BranchAndBoundSearch::StartRunnerUp() {
  phase_ = Phase::kRunnerUp;
  if (options_.rival_margin > 0.0) {
    // The smallest sum s with best.score - MeanProbability(s) < rival_margin (monotone in s).
    const auto rival = [&](int64_t sum) {
      return result_.best.score - grids_.MeanProbability(sum, scans_.points) <
             options_.rival_margin;
    };
    int64_t lo = 0, hi = result_.best.sum;
    while (lo < hi) {
      const int64_t mid = lo + (hi - lo) / 2;
      if (rival(mid)) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    rival_floor_ = lo - 1;
  }
  peak_ = MakePeak(result_.best.placement, options_.peak_distance, options_.peak_angle,
                   grids_.limits().resolution, window_);
  stack_[0].next = 0;  // the top level's nodes keep their scores and order
  depth_ = 1;
}

SearchStatus BranchAndBoundSearch::Run(int64_t max_nodes) {
  int64_t budget = std::max<int64_t>(1, max_nodes);
  while (phase_ != Phase::kDone) {
    if (depth_ == 0) {
      if (phase_ == Phase::kBest && result_.best.found && !outside_) {
        StartRunnerUp();
      } else {
        phase_ = Phase::kDone;
        SetMargin(grids_, &result_);
      }
      continue;
    }
    Frame& f = stack_[depth_ - 1];
    if (f.scored < f.nodes.size()) {
      if (budget == 0) return SearchStatus::kRunning;
      f.nodes[f.scored].score = Score(f.nodes[f.scored]);
      ++f.scored;
      --budget;
      ++result_.nodes;
      continue;
    }
    if (!f.sorted) {
      std::stable_sort(f.nodes.begin(), f.nodes.end(),
                       [](const Node& a, const Node& b) { return a.score > b.score; });
      f.sorted = true;
      continue;
    }
    if (f.next == f.nodes.size()) {
      --depth_;
      continue;
    }
    const Node node = f.nodes[f.next++];
    const bool best_phase = phase_ == Phase::kBest;
    const MatchPlacement& incumbent = best_phase ? result_.best : result_.runner_up;
    const int64_t threshold =
        incumbent.found ? incumbent.sum : (best_phase ? min_sum_ - 1 : rival_floor_);
    if (node.score <= threshold) {
      --depth_;  // the rest of the frame scores no more
      continue;
    }
    if ((!best_phase || outside_) && peak_.ContainsBlock(node.placement, 1 << node.level)) continue;
    if (node.level == 0) {
      SetPlacement(grids_, center_, window_, scans_.points, node.placement, node.score,
                   best_phase ? &result_.best : &result_.runner_up);
      if (options_.rival_margin > 0.0 && (!best_phase || outside_)) {
        phase_ = Phase::kDone;  // a decision: one rival (or one placement outside) answers it
        SetMargin(grids_, &result_);
        return SearchStatus::kDone;
      }
      continue;
    }
    PushChildren(&node);
  }
  return SearchStatus::kDone;
}

BranchAndBoundResult ExhaustiveSearch(const PrecomputationGridStack& grids,
                                      const std::vector<Vec2>& points, const Pose2& center,
                                      const BranchAndBoundOptions& options) {
  BranchAndBoundResult r;
  const SearchWindow window = WindowFor(grids, points, options);
  DiscreteScans scans;
  DiscretizeScans(grids.limits(), points, center, window, &scans);
  if (scans.points == 0) return r;
  const int64_t min_sum = MinimumSum(grids, options.min_score, scans.points);
  const PrecomputationGrid& level = grids.Level(0);
  const int limit = window.linear_cells;
  std::vector<int64_t> sums;
  sums.reserve(static_cast<size_t>(window.headings()) * (2 * limit + 1) * (2 * limit + 1));
  for (int h = 0; h < window.headings(); ++h) {
    for (int y = -limit; y <= limit; ++y) {
      for (int x = -limit; x <= limit; ++x) {
        sums.push_back(PlacementSum(level, scans.Heading(h), scans.points, x, y));
        ++r.nodes;
        if (sums.back() >= min_sum && (!r.best.found || sums.back() > r.best.sum)) {
          SetPlacement(grids, center, window, scans.points, Placement{h, x, y}, sums.back(),
                       &r.best);
        }
      }
    }
  }
  if (r.best.found) {
    const Peak peak = MakePeak(r.best.placement, options.peak_distance, options.peak_angle,
                               grids.limits().resolution, window);
    size_t i = 0;
    for (int h = 0; h < window.headings(); ++h) {
      for (int y = -limit; y <= limit; ++y) {
        for (int x = -limit; x <= limit; ++x, ++i) {
          if (peak.Contains(Placement{h, x, y})) continue;
          if (!r.runner_up.found || sums[i] > r.runner_up.sum) {
            SetPlacement(grids, center, window, scans.points, Placement{h, x, y}, sums[i],
                         &r.runner_up);
          }
        }
      }
    }
  }
  SetMargin(grids, &r);
  return r;
}

}  // namespace atlas
