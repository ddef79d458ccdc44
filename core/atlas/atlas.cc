#include "core/atlas/atlas.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/atlas/byte_image.h"
#include "core/atlas/edge_refinement.h"

namespace atlas {

std::string AtlasOptions::Validate() const {
  for (const std::string& e :
       {quality.Validate(), lifecycle.Validate(), match.Validate(), points.Validate()})
    if (!e.empty()) return e;
  if (max_hypotheses < 2 || max_hypotheses > 64) return "max_hypotheses must lie in [2, 64]";
  if (max_degree < 2) return "max_degree must be at least 2";
  if (!(q_traverse >= 0 && q_traverse <= 1)) return "q_traverse must lie in [0, 1]";
  if (max_seeds_per_step < 0) return "max_seeds_per_step must be non-negative";
  if (seed_cooldown_steps < 0) return "seed_cooldown_steps must be non-negative";
  if (traversal_max_hops < 1) return "traversal_max_hops must be at least 1";
  if (!(traversal_reach > 0)) return "traversal_reach must be positive";
  if (!(return_q >= 0 && return_q <= 1)) return "return_q must lie in [0, 1]";
  if (!(return_radius > 0)) return "return_radius must be positive";
  if (!(return_far_radius >= 0 && return_far_radius <= return_radius))
    return "return_far_radius must lie in [0, return_radius]";
  if (!(genesis_cov_scale >= 1.0 && genesis_cov_scale <= 100.0))
    return "genesis_cov_scale must lie in [1, 100]";
  if (projection_max_frames < 2) return "projection_max_frames must be at least 2";
  if (!(projection_max_rho > 0)) return "projection_max_rho must be positive";
  if (match_candidates_per_step < 0) return "match_candidates_per_step must be non-negative";
  if (match_interval_steps < 1) return "match_interval_steps must be at least 1";
  if (min_match_lines < match.min_support) return "min_match_lines must be >= match.min_support";
  if (!(match_radius > 0)) return "match_radius must be positive";
  if (self_match_cache < 2) return "self_match_cache must be at least 2";
  if (match_memory < 1) return "match_memory must be at least 1";
  if (max_refinements_per_step < 0) return "max_refinements_per_step must be non-negative";
  if (refine_interval_steps < 1) return "refine_interval_steps must be at least 1";
  if (!(refine_gate_chi2 > 0)) return "refine_gate_chi2 must be positive";
  if (!(seed_cov_scale_without_w >= 1.0 && seed_cov_scale_without_w <= 100.0))
    return "seed_cov_scale_without_w must lie in [1, 100]";
  if (!(capacity_explanation >= 0 && capacity_explanation <= 1))
    return "capacity_explanation must lie in [0, 1]";
  if (genesis_min_interval_steps < 0) return "genesis_min_interval_steps must be non-negative";
  if (resume_candidates_per_step < 0) return "resume_candidates_per_step must be non-negative";
  if (resume_scan_per_step < 1) return "resume_scan_per_step must be at least 1";
  return "";
}

Atlas::Atlas(const AtlasOptions& options, MapFactory factory,
             std::shared_ptr<const PoseBootstrapper> bootstrapper)
    : options_(options),
      factory_(std::move(factory)),
      bootstrapper_(std::move(bootstrapper)),
      graph_(options.max_degree) {
  assert(options_.Validate().empty());
  assert(factory_);
  hypotheses_.reserve(options_.max_hypotheses + 1);
  self_cache_.resize(options_.self_match_cache);
  tried_.resize(options_.match_memory);
}

LocalMap& Atlas::MapOf(Hypothesis& h) {
  return h.state == HypothesisState::kJuvenile ? *h.trial_map : *graph_.MutableFrame(h.frame).map;
}

UncertainPose Atlas::PoseOf(const Hypothesis& h) const {
  return h.state == HypothesisState::kJuvenile ? h.trial_map->RobotPose()
                                               : graph_.Frame(h.frame).map->RobotPose();
}

bool Atlas::HasHypothesis(FrameId f) const {
  for (const Hypothesis& h : hypotheses_)
    if (h.frame == f) return true;
  return false;
}

DominantOutput Atlas::Dominant() const {
  DominantOutput out;
  const int d = DominantIndex(hypotheses_);
  if (d < 0) return out;
  const Hypothesis& h = hypotheses_[d];
  out.valid = true;
  out.hypothesis = h.id;
  out.frame = h.frame;
  out.pose = PoseOf(h);
  out.q = h.q;
  return out;
}

FrameId Atlas::AddFrame(std::unique_ptr<LocalMap> map) {
  const FrameId id = graph_.AddFrame(std::move(map), step_);
  graph_.MutableFrame(id).points = FramePoints(options_.points);
  components_.AddFrame();
  return id;
}

AddEdgeResult Atlas::AddEdge(FrameId a, FrameId b, const UncertainPose& b_in_a, EdgeKind kind) {
  const AddEdgeResult r = graph_.AddEdge(a, b, b_in_a, kind, step_);
  if (r == AddEdgeResult::kAdded) components_.Join(a, b);
  return r;
}

const StepStats& Atlas::Step(const Pose2& odometry_delta, const LaserScan& scan) {
  LocalizeWith(odometry_delta, nullptr, &scan, nullptr);
  return MaintainGraph();
}

const StepStats& Atlas::Step(const Pose2& odometry_delta, const SonarReading& reading) {
  LocalizeWith(odometry_delta, nullptr, nullptr, &reading);
  return MaintainGraph();
}

const StepStats& Atlas::Localize(const Pose2& odometry_delta, const LaserScan& scan) {
  return LocalizeWith(odometry_delta, nullptr, &scan, nullptr);
}

const StepStats& Atlas::Localize(const Pose2& odometry_delta, const SonarReading& reading) {
  return LocalizeWith(odometry_delta, nullptr, nullptr, &reading);
}

const StepStats& Atlas::Localize(const UncertainPose& increment, const LaserScan& scan) {
  return LocalizeWith(increment.mean, &increment.cov, &scan, nullptr);
}

FrameId Atlas::StartUnconnectedFrame() {
  std::unique_ptr<LocalMap> map = factory_();
  map->ResetRobotPose(UncertainPose{});
  Hypothesis h;
  h.id = next_hypothesis_id_++;
  h.frame = AddFrame(std::move(map));
  h.state = HypothesisState::kMature;
  h.born_step = step_;
  h.window = QualityWindow(options_.quality.window);
  hypotheses_.push_back(std::move(h));
  last_genesis_step_ = step_;
  return hypotheses_.back().frame;
}

FrameId Atlas::ResumeInNewFrame() {
  hypotheses_.clear();
  const FrameId f = StartUnconnectedFrame();
  FindDominant();
  projection_step_ = -1;
  projection_source_ = kNoFrame;
  return f;
}

const StepStats& Atlas::LocalizeWith(const Pose2& odometry_delta, const Mat3* increment_cov,
                                     const LaserScan* scan, const SonarReading* sonar) {
  assert(!graph_pending_);
  graph_pending_ = true;
  stats_ = StepStats{};
  stats_.step = ++step_;
  const bool first = graph_.FrameCount() == 0;
  if (!UsableInput(odometry_delta, increment_cov, scan, first)) {
    ++stats_.rejected_input;
    FindDominant();
    stats_.frames = graph_.FrameCount();
    stats_.hypotheses_alive = static_cast<int>(hypotheses_.size());
    return stats_;
  }
  if (first) StartUnconnectedFrame();
  UpdateHypotheses(odometry_delta, increment_cov, scan, sonar, first);
  JudgeJuveniles();
  HandleFailures();
  int d = FindDominant();
  if (d >= 0) Traverse(d);
  GenesisAtCapacity();
  FindDominant();
  stats_.frames = graph_.FrameCount();
  stats_.hypotheses_alive = static_cast<int>(hypotheses_.size());
  return stats_;
}

bool Atlas::UsableInput(const Pose2& odometry_delta, const Mat3* increment_cov,
                        const LaserScan* scan, bool first) {
  if (scan != nullptr && !scan->sensor_pose.IsFinite()) return false;
  if (first) return true;  // the first step's odometry is not used
  return odometry_delta.IsFinite() &&
         std::hypot(odometry_delta.x, odometry_delta.y) <= kMaxStepTranslation &&
         (increment_cov == nullptr || increment_cov->allFinite());
}

const StepStats& Atlas::MaintainGraph() {
  assert(graph_pending_);
  graph_pending_ = false;
  const int d = DominantIndex(hypotheses_);
  if (d >= 0 && step_ % options_.match_interval_steps == 0) {
    MatchMaps(d);
    MatchUnconnected(d);
  }
  RefineEdges();
  stats_.frames = graph_.FrameCount();
  return stats_;
}

void Atlas::UpdateHypotheses(const Pose2& delta, const Mat3* increment_cov, const LaserScan* scan,
                             const SonarReading* sonar, bool first) {
  bootstrap_failed_.assign(hypotheses_.size(), 0);
  for (size_t i = 0; i < hypotheses_.size(); ++i) {
    Hypothesis& h = hypotheses_[i];
    LocalMap& map = MapOf(h);
    if (!first && increment_cov != nullptr) {
      map.Predict(delta, *increment_cov);
    } else if (!first) {
      map.Predict(delta);
    }
    const bool mature = h.state == HypothesisState::kMature;
    if (scan) {
      h.last_update = map.Update(*scan, mature);
      h.window.Add(h.last_update);
      if (mature && options_.points.enabled)
        graph_.MutableFrame(h.frame).points.AddScan(map.RobotPose().mean, *scan);
    } else {
      h.last_update = map.UpdateWithSonar(*sonar, mature);
      if (h.last_update.observations > 0) h.window.Add(h.last_update);
    }
    ++h.steps;
    // w's Z holds the steps of the sensor it solves from (laser unless FromSonar()).
    const bool feeds_w = sonar ? bootstrapper_ && bootstrapper_->FromSonar()
                               : !bootstrapper_ || !bootstrapper_->FromSonar();
    if (!mature && !h.bootstrapped && !feeds_w) {
      if (!bootstrapper_ && h.steps >= options_.lifecycle.bootstrap_scans) h.bootstrapped = true;
    } else if (!mature && !h.bootstrapped) {
      h.z.push_back(JuvenileScan{delta, scan ? *scan : LaserScan{}, h.last_update,
                                 sonar ? *sonar : SonarReading{}});
      if (static_cast<int>(h.z.size()) >= options_.lifecycle.bootstrap_scans) {
        bool accumulate = false;
        if (bootstrapper_) {
          ++stats_.bootstraps;
          PoseBootstrap r = bootstrapper_->Solve(map, *graph_.Frame(h.frame).map, h.z, h.seed);
          if (r.outcome == BootstrapOutcome::kSolved) {
            if (r.map)
              h.trial_map = std::move(r.map);  // M_i^new of eq. 12
            else
              map.ResetRobotPose(r.pose);
            h.bootstrapped = true;
          } else if (r.outcome == BootstrapOutcome::kUndetermined &&
                     h.steps < options_.lifecycle.probation_scans) {
            accumulate = true;
          } else {
            bootstrap_failed_[i] = 1;
          }
        } else {
          h.bootstrapped = true;
        }
        if (!accumulate) {
          h.z.clear();
          h.z.shrink_to_fit();
        }
      }
    }
    h.q = HypothesisQuality(MapOf(h).RobotPose().cov,
                            h.window.Explanation(options_.quality.empty_explanation),
                            options_.quality);
  }
}

void Atlas::JudgeJuveniles() {
  double best_mature = -1.0;
  for (const Hypothesis& h : hypotheses_)
    if (h.state == HypothesisState::kMature) best_mature = std::max(best_mature, h.q);
  for (size_t i = 0; i < hypotheses_.size();) {
    Hypothesis& h = hypotheses_[i];
    const JuvenileVerdict v =
        JudgeJuvenile(h, best_mature, bootstrap_failed_[i] != 0, options_.lifecycle);
    if (v == JuvenileVerdict::kMature) {
      MapFrame& f = graph_.MutableFrame(h.frame);
      if (bootstrapper_ || !options_.keep_frame_map_without_w) {
        f.map = std::move(h.trial_map);
      } else {
        f.map->ResetRobotPose(h.trial_map->RobotPose());
        h.trial_map.reset();
      }
      h.state = HypothesisState::kMature;
      h.failing_steps = 0;
      h.z.clear();
      ++stats_.matured;
    } else if (v == JuvenileVerdict::kDelete) {
      graph_.MutableFrame(h.frame).seed_cooldown_until = step_ + options_.seed_cooldown_steps;
      if (bootstrap_failed_[i]) ++stats_.killed_by_w;
      ++stats_.deleted;
      hypotheses_.erase(hypotheses_.begin() + i);
      bootstrap_failed_.erase(bootstrap_failed_.begin() + i);
      continue;
    }
    ++i;
  }
}

void Atlas::HandleFailures() {
  int failing = 0, healthy = 0, juveniles = 0;
  const int dominant = DominantIndex(hypotheses_);
  const double dominant_q = dominant >= 0 ? hypotheses_[dominant].q : 0.0;
  for (int i = 0; i < static_cast<int>(hypotheses_.size()); ++i) {
    Hypothesis& h = hypotheses_[i];
    if (h.state == HypothesisState::kJuvenile) {
      ++juveniles;
      continue;
    }
    const bool below = UpdateFailing(&h, options_.lifecycle);
    bool lagging = UpdateLagging(&h, i == dominant, dominant_q, options_.lifecycle);
    if (i != dominant && dominant >= 0 && ContradictsDominant(hypotheses_[dominant], h)) {
      h.lagging_steps = options_.lifecycle.lag_steps;
      lagging = true;
      ++stats_.contradicting;
    }
    if (below || lagging)
      ++failing;
    else
      ++healthy;
  }
  if (failing == 0) return;
  if (healthy == 0) {
    // The only mature hypotheses fail. Juveniles on probation are given their chance first.
    if (juveniles > 0) return;
    const int from = DominantIndex(hypotheses_);
    if (!Genesis(from)) return;  // degree full: keep going with the failing map
  }
  for (size_t i = 0; i < hypotheses_.size();) {
    Hypothesis& h = hypotheses_[i];
    if (h.state == HypothesisState::kMature && (h.failing_steps >= options_.lifecycle.fail_steps ||
                                                h.lagging_steps >= options_.lifecycle.lag_steps)) {
      MapFrame& f = graph_.MutableFrame(h.frame);
      ++f.retirements;
      f.seed_cooldown_until = step_ + options_.seed_cooldown_steps;
      ++stats_.retired;
      hypotheses_.erase(hypotheses_.begin() + i);
      continue;
    }
    ++i;
  }
}

bool Atlas::ContradictsDominant(const Hypothesis& dominant, const Hypothesis& h) const {
  const int edge = graph_.FindEdge(dominant.frame, h.frame);
  if (edge < 0) return false;
  const UncertainPose obs = EdgeObservation(PoseOf(dominant), PoseOf(h));
  return RefineEdge(obs, graph_.Transform(edge, dominant.frame), options_.refine_gate_chi2)
             .result == RefineResult::kRejected;
}

void Atlas::GenesisAtCapacity() {
  if (step_ - last_genesis_step_ < options_.genesis_min_interval_steps) return;
  const int d = DominantIndex(hypotheses_);
  if (d < 0) return;
  const Hypothesis& h = hypotheses_[d];
  const LocalMap& map = *graph_.Frame(h.frame).map;
  if (map.Complexity() < map.Capacity()) return;
  if (h.q >= options_.q_traverse) return;  // traversal gets the first chance
  if (h.window.Explanation(1.0) >= options_.capacity_explanation) return;
  for (const Hypothesis& o : hypotheses_) {
    if (o.state == HypothesisState::kJuvenile) return;  // a known place gets its chance first
    if (&o == &h) continue;
    const LocalMap& m = *graph_.Frame(o.frame).map;
    if (m.Complexity() < m.Capacity()) return;
  }
  Genesis(d);
}

bool Atlas::MakeRoomForHypothesis(int keep_index) {
  if (static_cast<int>(hypotheses_.size()) < options_.max_hypotheses) return true;
  // Drop the weakest juvenile, else the weakest mature hypothesis other than `keep_index`.
  int victim = -1;
  for (int pass = 0; pass < 2 && victim < 0; ++pass) {
    const HypothesisState s = pass == 0 ? HypothesisState::kJuvenile : HypothesisState::kMature;
    for (int i = 0; i < static_cast<int>(hypotheses_.size()); ++i) {
      if (i == keep_index || hypotheses_[i].state != s) continue;
      if (victim < 0 || hypotheses_[i].q < hypotheses_[victim].q) victim = i;
    }
  }
  if (victim < 0) return false;
  if (hypotheses_[victim].state == HypothesisState::kMature) {
    ++graph_.MutableFrame(hypotheses_[victim].frame).retirements;
    ++stats_.retired;
  } else {
    ++stats_.deleted;
  }
  hypotheses_.erase(hypotheses_.begin() + victim);
  return true;
}

bool Atlas::Genesis(int from_index) {
  if (from_index < 0) return false;
  const FrameId from = hypotheses_[from_index].frame;
  if (static_cast<int>(graph_.Frame(from).edges.size()) >= graph_.max_degree()) {
    ++stats_.genesis_refused;
    return false;
  }
  // III-C: the robot pose (with its covariance, times genesis_cov_scale) in the old frame becomes
  // the edge; the robot is at exactly zero, with zero covariance, in the new frame.
  UncertainPose robot = graph_.Frame(from).map->RobotPose();
  robot.cov *= options_.genesis_cov_scale;
  const int64_t from_id = hypotheses_[from_index].id;
  if (!MakeRoomForHypothesis(from_index)) return false;
  std::unique_ptr<LocalMap> map = factory_();
  map->ResetRobotPose(UncertainPose{});
  const FrameId id = AddFrame(std::move(map));
  const AddEdgeResult added = AddEdge(from, id, robot, EdgeKind::kGenesis);
  assert(added == AddEdgeResult::kAdded);
  (void)added;
  (void)from_id;
  Hypothesis h;
  h.id = next_hypothesis_id_++;
  h.frame = id;
  h.state = HypothesisState::kMature;
  h.born_step = step_;
  h.window = QualityWindow(options_.quality.window);
  h.q = HypothesisQuality(Mat3::Zero(), options_.quality.empty_explanation, options_.quality);
  hypotheses_.push_back(std::move(h));
  last_genesis_step_ = step_;
  ++stats_.genesis;
  return true;
}

int Atlas::FindDominant() {
  const int d = DominantIndex(hypotheses_);
  for (int i = 0; i < static_cast<int>(hypotheses_.size()); ++i) hypotheses_[i].dominant = i == d;
  stats_.dominant_frame = d >= 0 ? hypotheses_[d].frame : kNoFrame;
  return d;
}

const Projection& Atlas::ProjectionFromDominant(FrameId dominant) {
  if (projection_step_ != step_ || projection_source_ != dominant) {
    ProjectionLimits limits;
    limits.max_frames = options_.projection_max_frames;
    limits.max_rho = options_.projection_max_rho;
    workspace_.Project(graph_, dominant, limits, &projection_);
    projection_step_ = step_;
    projection_source_ = dominant;
    stats_.frames_examined += static_cast<int>(projection_.entries.size());
  }
  return projection_;
}

void Atlas::Traverse(int d) {
  const double q = hypotheses_[d].q;
  const bool returning = q >= options_.q_traverse;
  if (q >= std::max(options_.q_traverse, options_.return_q) || options_.max_seeds_per_step == 0)
    return;
  const FrameId dom_frame = hypotheses_[d].frame;
  const UncertainPose x_d = PoseOf(hypotheses_[d]);
  const Projection& p = ProjectionFromDominant(dom_frame);
  int seeded = 0;
  for (size_t k = 1; k < p.entries.size() && seeded < options_.max_seeds_per_step; ++k) {
    const ProjectedFrame& e = p.entries[k];
    const bool far = e.hops > options_.traversal_max_hops;
    if (far && !(returning && options_.return_far_radius > 0)) continue;
    if (static_cast<int>(hypotheses_.size()) >= options_.max_hypotheses) break;
    const MapFrame& f = graph_.Frame(e.frame);
    if (f.seed_cooldown_until > step_ || HasHypothesis(e.frame)) continue;
    // eq. 10-11: x_i* = T_i^d (+) x_d, T_i^d the pose of the dominant frame in frame i.
    UncertainPose seed = Compose(Inverse(e.pose), x_d);
    if (!bootstrapper_) seed.cov *= options_.seed_cov_scale_without_w;
    if (returning && std::hypot(seed.mean.x, seed.mean.y) >
                         (far ? options_.return_far_radius : options_.return_radius))
      continue;
    if (!WithinReach(*f.map, seed)) {
      ++stats_.seeds_out_of_reach;
      continue;
    }
    Hypothesis h;
    h.id = next_hypothesis_id_++;
    h.frame = e.frame;
    h.state = HypothesisState::kJuvenile;
    h.born_step = step_;
    h.window = QualityWindow(options_.quality.window);
    h.trial_map = f.map->Clone();
    h.trial_map->ResetRobotPose(seed);
    h.seed = seed;
    h.q = HypothesisQuality(seed.cov, options_.quality.empty_explanation, options_.quality);
    h.z.reserve(options_.lifecycle.bootstrap_scans);
    hypotheses_.push_back(std::move(h));
    ++seeded;
  }
  stats_.seeded += seeded;
}

const SelfMatch* Atlas::CachedSelfMatchOf(FrameId f) const {
  const int complexity = graph_.Frame(f).map->Complexity();
  for (const CachedSelfMatch& c : self_cache_)
    if (c.frame == f && c.complexity == complexity) return &c.self;
  return nullptr;
}

bool Atlas::TriedUnchanged(FrameId a, FrameId b) const {
  const int ca = graph_.Frame(a).map->Complexity(), cb = graph_.Frame(b).map->Complexity();
  for (const TriedPair& t : tried_)
    if (t.a == a && t.b == b && t.complexity_a == ca && t.complexity_b == cb) return true;
  return false;
}

void Atlas::RememberTried(FrameId a, FrameId b) {
  tried_[tried_next_] =
      TriedPair{a, b, graph_.Frame(a).map->Complexity(), graph_.Frame(b).map->Complexity()};
  tried_next_ = (tried_next_ + 1) % static_cast<int>(tried_.size());
}

bool Atlas::SpendSearchOnSelfMatch(FrameId a, FrameId b) {
  for (FrameId f : {a, b}) {
    if (CachedSelfMatchOf(f) != nullptr) continue;
    SelfMatchOf(f);
    ++stats_.self_matches;
    return true;
  }
  return false;
}

bool Atlas::WithinReach(const LocalMap& map, const UncertainPose& seed) const {
  const Vec2 p(seed.mean.x, seed.mean.y);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(seed.cov.topLeftCorner<2, 2>());
  const double reach =
      options_.traversal_reach + 3.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
  for (const MapLine& l : map.Lines()) {
    const Vec2 d = l.endpoint_b - l.endpoint_a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - l.endpoint_a).dot(d) / len2, 0.0, 1.0) : 0.0;
    if ((l.endpoint_a + t * d - p).norm() <= reach) return true;
  }
  return false;
}

const SelfMatch& Atlas::SelfMatchOf(FrameId f) {
  if (const SelfMatch* cached = CachedSelfMatchOf(f)) return *cached;
  const int complexity = graph_.Frame(f).map->Complexity();
  CachedSelfMatch& slot = self_cache_[self_cache_next_];
  self_cache_next_ = (self_cache_next_ + 1) % static_cast<int>(self_cache_.size());
  slot.frame = f;
  slot.complexity = complexity;
  slot.self = SelfMatchMap(graph_.Frame(f).map->Lines(), options_.match);
  return slot.self;
}

void Atlas::MatchMaps(int d) {
  if (d < 0 || options_.match_candidates_per_step == 0) return;
  const FrameId dom_frame = hypotheses_[d].frame;
  const LocalMap& dom_map = *graph_.Frame(dom_frame).map;
  if (dom_map.Complexity() < options_.min_match_lines) return;
  const Pose2 robot = dom_map.RobotPose().mean;
  const Projection& p = ProjectionFromDominant(dom_frame);
  candidates_.clear();
  for (size_t k = 1; k < p.entries.size(); ++k) {
    const ProjectedFrame& e = p.entries[k];
    if (graph_.FindEdge(dom_frame, e.frame) >= 0) continue;
    const LocalMap& m = *graph_.Frame(e.frame).map;
    if (m.Complexity() < options_.min_match_lines) continue;
    const double dist = std::hypot(e.pose.mean.x - robot.x, e.pose.mean.y - robot.y);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(e.pose.cov.topLeftCorner<2, 2>());
    const double sigma = std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
    if (dist - 3.0 * sigma > options_.match_radius) continue;
    candidates_.push_back(static_cast<FrameId>(k));  // index into the projection
  }
  if (candidates_.empty()) return;
  const int n = static_cast<int>(candidates_.size());
  const int budget = std::min(n, options_.match_candidates_per_step);
  const int start = static_cast<int>(match_cursor_ % n);
  int advance = 0;
  for (int tried = 0; tried < n && Searches() < budget; ++tried) {
    const ProjectedFrame& e = p.entries[candidates_[(start + tried) % n]];
    advance = tried + 1;
    if (TriedUnchanged(dom_frame, e.frame)) continue;
    // A self-match not cached yet is this search; the pair is matched at a later step.
    if (SpendSearchOnSelfMatch(dom_frame, e.frame)) {
      advance = tried;
      continue;
    }
    RememberTried(dom_frame, e.frame);
    ++stats_.candidates_matched;
    MatchPair(dom_frame, e.frame, &e.pose);
  }
  match_cursor_ += static_cast<uint64_t>(advance);
}

void Atlas::MatchPair(FrameId dom_frame, FrameId other, const UncertainPose* prior) {
  const SelfMatch& self_a = SelfMatchOf(dom_frame);
  const SelfMatch self_a_copy = self_a;  // the cache may evict it while matching b
  const SelfMatch& self_b = SelfMatchOf(other);
  const MapMatch m = atlas::MatchMaps(
      graph_.Frame(dom_frame).map->Lines(), self_a_copy, graph_.Frame(other).map->Lines(), self_b,
      prior, options_.match, options_.points.enabled ? &graph_.Frame(dom_frame).points : nullptr,
      options_.points.enabled ? &graph_.Frame(other).points : nullptr);
  stats_.match_hypotheses += m.hypotheses;
  stats_.match_by_points += m.by_points ? 1 : 0;
  ++stats_.match_reasons[static_cast<int>(m.reason)];
  switch (m.result) {
    case MapMatchResult::kAccepted:
      if (AddEdge(dom_frame, other, m.b_in_a, EdgeKind::kMapMatch) == AddEdgeResult::kAdded)
        ++stats_.match_accepted;
      else
        ++stats_.match_rejected;
      break;
    case MapMatchResult::kRejected:
      ++stats_.match_rejected;
      break;
    case MapMatchResult::kAmbiguous:
      ++stats_.match_ambiguous;
      break;
  }
}

void Atlas::MatchUnconnected(int d) {
  const int n = graph_.FrameCount();
  if (d < 0 || options_.resume_candidates_per_step == 0) return;
  const FrameId dom_frame = hypotheses_[d].frame;
  if (components_.Size(dom_frame) == n) return;  // connected: the projection reaches every frame
  if (graph_.Frame(dom_frame).map->Complexity() < options_.min_match_lines) return;
  int matched = 0;
  for (int looked = 0;
       looked < options_.resume_scan_per_step && matched < options_.resume_candidates_per_step;
       ++looked) {
    const FrameId f = static_cast<FrameId>(resume_cursor_++ % static_cast<uint64_t>(n));
    if (components_.Connected(f, dom_frame)) continue;
    if (graph_.Frame(f).map->Complexity() < options_.min_match_lines) continue;
    if (TriedUnchanged(dom_frame, f)) continue;
    if (SpendSearchOnSelfMatch(dom_frame, f)) {
      --resume_cursor_;  // this frame again at the next step
      break;
    }
    RememberTried(dom_frame, f);
    ++matched;
    ++stats_.match_unconnected;
    MatchPair(dom_frame, f, nullptr);
    if (components_.Connected(f, dom_frame)) break;
  }
}

void Atlas::RefineEdges() {
  int budget = options_.max_refinements_per_step;
  const int n = static_cast<int>(hypotheses_.size());
  for (int i = 0; i < n && budget > 0; ++i) {
    if (hypotheses_[i].state != HypothesisState::kMature) continue;
    for (int j = i + 1; j < n && budget > 0; ++j) {
      if (hypotheses_[j].state != HypothesisState::kMature) continue;
      const FrameId fi = hypotheses_[i].frame, fj = hypotheses_[j].frame;
      const int edge = graph_.FindEdge(fi, fj);
      if (edge < 0) continue;
      const AtlasEdge& e = graph_.Edge(edge);
      if (e.origin == EdgeKind::kMapMatch && !options_.refine_map_match_edges) continue;
      const int64_t last = std::max(e.made_step, e.refined_step);
      if (step_ - last < options_.refine_interval_steps) continue;
      const UncertainPose obs = EdgeObservation(PoseOf(hypotheses_[i]), PoseOf(hypotheses_[j]));
      const EdgeRefinement r =
          RefineEdge(obs, graph_.Transform(edge, fi), options_.refine_gate_chi2);
      --budget;
      if (r.result == RefineResult::kRejected) {
        ++stats_.refine_rejected;
        continue;
      }
      graph_.SetTransform(edge, fi, r.ci.fused, EdgeKind::kRefined, step_);
      ++stats_.refined;
    }
  }
}

// ---- byte image -------------------------------------------------------------------------

namespace {

constexpr uint32_t kMagic = 0x534c5441;  // "ATLS"
constexpr uint64_t kMaxBlob = uint64_t{1} << 30;
// Step counters and hypothesis ids of a loaded image lie in [0, kMaxStep]: far beyond any run,
// and far enough from INT64_MAX that step arithmetic (++step_, step_ - x, step_ + cooldown)
// cannot overflow.
constexpr int64_t kMaxStep = int64_t{1} << 62;
// The initial last_genesis_step_ (atlas.h) of an atlas that has not stepped yet.
constexpr int64_t kNoGenesisStep = -1000000;
// Observations, matches or additions of one scan: a window of 1000 of them sums without
// overflow.
constexpr int32_t kMaxScanCount = 1 << 20;

// Finite, symmetric and positive semi-definite (eigenvalues >= -tiny relative to its scale).
bool ValidCovariance(const Mat3& c) {
  if (!c.allFinite()) return false;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < r; ++k)
      if (std::abs(c(r, k) - c(k, r)) > 1e-9 * (1.0 + std::abs(c(r, k)))) return false;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(c, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return false;
  const double scale = c.cwiseAbs().maxCoeff();
  return eig.eigenvalues().minCoeff() >= -1e-9 * (1.0 + scale);
}

bool ValidCount(int32_t n) { return n >= 0 && n <= kMaxScanCount; }

void PutScan(ByteWriter* w, const LaserScan& s) {
  w->Put<int64_t>(s.stamp.time_since_epoch().count());
  w->Put(s.angle_min);
  w->Put(s.angle_increment);
  w->Put(s.max_range);
  w->PutPose(s.sensor_pose);
  w->Put<uint64_t>(s.ranges.size());
  for (float r : s.ranges) w->Put(r);
}

bool GetScan(ByteReader* r, LaserScan* s) {
  int64_t ns = 0;
  uint64_t n = 0;
  if (!r->Get(&ns) || !r->Get(&s->angle_min) || !r->Get(&s->angle_increment) ||
      !r->Get(&s->max_range) || !r->GetPose(&s->sensor_pose) || !r->Get(&n) || n > 100000)
    return false;
  s->stamp = Time(Duration(ns));
  s->ranges.resize(n);
  for (float& v : s->ranges)
    if (!r->Get(&v)) return false;
  return true;
}

void PutUpdate(ByteWriter* w, const ScanUpdate& u) {
  w->Put<int32_t>(u.observations);
  w->Put<int32_t>(u.matched);
  w->Put<int32_t>(u.added);
  w->Put<uint8_t>(u.ambiguous);
}

void PutSonar(ByteWriter* w, const SonarReading& s) {
  w->Put<int64_t>(s.stamp.time_since_epoch().count());
  w->Put<uint64_t>(s.returns.size());
  for (const SonarReturn& ret : s.returns) {
    w->Put<int32_t>(ret.transducer);
    w->Put(ret.range);
  }
}

bool GetSonar(ByteReader* r, SonarReading* s) {
  int64_t ns = 0;
  uint64_t n = 0;
  if (!r->Get(&ns) || !r->Get(&n) || n > 100000) return false;
  s->stamp = Time(Duration(ns));
  s->returns.resize(n);
  for (SonarReturn& ret : s->returns) {
    int32_t transducer = 0;
    if (!r->Get(&transducer) || !r->Get(&ret.range)) return false;
    ret.transducer = transducer;
  }
  return true;
}

bool GetUpdate(ByteReader* r, ScanUpdate* u) {
  int32_t o, m, a;
  uint8_t amb;
  if (!r->Get(&o) || !r->Get(&m) || !r->Get(&a) || !r->Get(&amb)) return false;
  if (!ValidCount(o) || !ValidCount(m) || !ValidCount(a)) return false;
  *u = ScanUpdate{o, m, a, amb != 0};
  return true;
}

}  // namespace

std::string Atlas::Serialize() const {
  ByteWriter w;
  w.Put(kMagic);
  w.Put(kImageVersion);
  w.Put(step_);
  w.Put(next_hypothesis_id_);
  w.Put(last_genesis_step_);
  w.Put(match_cursor_);
  w.Put<uint32_t>(graph_.FrameCount());
  for (FrameId f = 0; f < graph_.FrameCount(); ++f) {
    const MapFrame& frame = graph_.Frame(f);
    w.Put(frame.created_step);
    w.Put(frame.seed_cooldown_until);
    w.Put<int32_t>(frame.retirements);
    w.PutString(frame.map->Serialize());
    w.PutString(frame.points.Serialize());
  }
  w.Put<uint32_t>(graph_.EdgeCount());
  for (const AtlasEdge& e : graph_.Edges()) {
    w.Put(e.a);
    w.Put(e.b);
    w.PutUncertain(e.b_in_a);
    w.Put(e.kind);
    w.Put(e.origin);
    w.Put(e.made_step);
    w.Put(e.refined_step);
    w.Put<int32_t>(e.refinements);
  }
  w.Put<uint32_t>(hypotheses_.size());
  for (const Hypothesis& h : hypotheses_) {
    w.Put(h.id);
    w.Put(h.frame);
    w.Put(h.state);
    w.Put<uint8_t>(h.dominant);
    w.Put(h.born_step);
    w.Put<int32_t>(h.steps);
    w.Put(h.q);
    w.Put<int32_t>(h.failing_steps);
    w.Put<int32_t>(h.lagging_steps);
    // The ring is allocated at the first Add(): a hypothesis that has not seen an observation
    // yet (just made by Genesis, or only sonar steps without echoes) writes an empty ring of
    // its capacity, so that every image can be read back.
    const std::vector<QualityWindow::Entry>& ring = h.window.Ring();
    w.Put<int32_t>(h.window.Capacity());
    w.Put<int32_t>(h.window.Head());
    w.Put<int32_t>(h.window.Size());
    for (int k = 0; k < h.window.Capacity(); ++k) {
      const QualityWindow::Entry e =
          k < static_cast<int>(ring.size()) ? ring[k] : QualityWindow::Entry{};
      w.Put<int32_t>(e.observations);
      w.Put<int32_t>(e.matched);
    }
    PutUpdate(&w, h.last_update);
    w.Put<uint8_t>(h.bootstrapped);
    w.Put<uint8_t>(h.trial_map != nullptr);
    if (h.trial_map) {
      w.PutString(h.trial_map->Serialize());
      w.PutPose(h.seed.mean);
      for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c) w.Put(h.seed.cov(r, c));
    }
    w.Put<uint32_t>(h.z.size());
    for (const JuvenileScan& z : h.z) {
      w.PutPose(z.odometry_delta);
      PutScan(&w, z.scan);
      PutUpdate(&w, z.update);
      PutSonar(&w, z.sonar);
    }
  }
  return std::move(w.bytes());
}

bool Atlas::Deserialize(const std::string& bytes) {
  ByteReader r(bytes);
  uint32_t magic = 0, version = 0, frames = 0, edges = 0, hyps = 0;
  int64_t step = 0, next_id = 0, last_genesis = 0;
  uint64_t cursor = 0;
  if (!r.Get(&magic) || magic != kMagic || !r.Get(&version) || version < 1 ||
      version > kImageVersion || !r.Get(&step) || !r.Get(&next_id) || !r.Get(&last_genesis) ||
      !r.Get(&cursor) || !r.Get(&frames) || frames > (1u << 24))
    return false;
  if (step < 0 || step > kMaxStep || next_id < 0 || next_id > kMaxStep ||
      last_genesis < kNoGenesisStep || last_genesis > step)
    return false;
  AtlasGraph graph(options_.max_degree);
  for (uint32_t i = 0; i < frames; ++i) {
    int64_t created = 0, cooldown = 0;
    int32_t retirements = 0;
    std::string blob;
    if (!r.Get(&created) || !r.Get(&cooldown) || !r.Get(&retirements) ||
        !r.GetString(&blob, kMaxBlob))
      return false;
    // The cooldown was set with the seed_cooldown_steps of its time: bounded, not tied to ours.
    if (created < 0 || created > step || cooldown < -1 || cooldown > kMaxStep || retirements < 0 ||
        retirements == INT32_MAX)
      return false;
    std::unique_ptr<LocalMap> map = factory_();
    if (!map->Deserialize(blob)) return false;
    FramePoints points(options_.points);
    if (version >= 5 && (!r.GetString(&blob, kMaxBlob) || !points.Deserialize(blob))) return false;
    const FrameId id = graph.AddFrame(std::move(map), created);
    graph.MutableFrame(id).points = std::move(points);
    graph.MutableFrame(id).seed_cooldown_until = cooldown;
    graph.MutableFrame(id).retirements = retirements;
  }
  if (!r.Get(&edges) || edges > (1u << 28)) return false;
  for (uint32_t i = 0; i < edges; ++i) {
    AtlasEdge e;
    int32_t refinements = 0;
    if (!r.Get(&e.a) || !r.Get(&e.b) || !r.GetUncertain(&e.b_in_a) || !r.Get(&e.kind) ||
        !r.Get(&e.origin) || !r.Get(&e.made_step) || !r.Get(&e.refined_step) ||
        !r.Get(&refinements))
      return false;
    // An edge is made by Genesis or map-matching; only covariance intersection (RefineEdges,
    // at most once per step and edge, after the step that made it) changes its kind.
    if (static_cast<uint8_t>(e.kind) > 2 || e.origin == EdgeKind::kRefined ||
        static_cast<uint8_t>(e.origin) > 2 || (e.kind != e.origin && e.kind != EdgeKind::kRefined))
      return false;
    if (!e.b_in_a.mean.IsFinite() || !ValidCovariance(e.b_in_a.cov) || e.made_step < 0 ||
        e.made_step > step)
      return false;
    const bool refined = e.kind == EdgeKind::kRefined;
    if (refined ? refinements < 1 || refinements > e.refined_step - e.made_step ||
                      e.refined_step <= e.made_step || e.refined_step > step
                : refinements != 0 || e.refined_step != -1)
      return false;
    if (graph.AddEdge(e.a, e.b, e.b_in_a, e.origin, e.made_step) != AddEdgeResult::kAdded)
      return false;
    if (refined) graph.RestoreRefinements(graph.EdgeCount() - 1, refinements, e.refined_step);
  }
  if (!r.Get(&hyps) || hyps > static_cast<uint32_t>(options_.max_hypotheses)) return false;
  std::vector<Hypothesis> hypotheses;
  for (uint32_t i = 0; i < hyps; ++i) {
    Hypothesis h;
    uint8_t dominant = 0, bootstrapped = 0, has_trial = 0;
    int32_t steps = 0, failing = 0, lagging = 0, cap = 0, head = 0, size = 0;
    uint32_t nz = 0;
    if (!r.Get(&h.id) || !r.Get(&h.frame) || !graph.HasFrame(h.frame) || !r.Get(&h.state) ||
        static_cast<uint8_t>(h.state) > 1 || !r.Get(&dominant) || !r.Get(&h.born_step) ||
        !r.Get(&steps) || !r.Get(&h.q) || !r.Get(&failing) || (version >= 2 && !r.Get(&lagging)) ||
        !r.Get(&cap) || !r.Get(&head) || !r.Get(&size) || cap < 1 || cap > 1000 || head < 0 ||
        head >= cap || size < 0 || size > cap)
      return false;
    // Ids are handed out from next_id; a hypothesis is born at a step and counts the steps
    // since (the first frame's also the step it was made in); q is eq. 5, in [0, 1].
    if (h.id < 0 || h.id >= next_id || h.born_step < 0 || h.born_step > step || steps < 0 ||
        steps > step - h.born_step + 1 || steps == INT32_MAX || !std::isfinite(h.q) || h.q < 0.0 ||
        h.q > 1.0 || failing < 0 || failing > steps || lagging < 0 || lagging == INT32_MAX)
      return false;
    std::vector<QualityWindow::Entry> ring(cap);
    for (QualityWindow::Entry& e : ring)
      if (!r.Get(&e.observations) || !r.Get(&e.matched) || !ValidCount(e.observations) ||
          e.matched < 0 || e.matched > e.observations)
        return false;
    h.window.Restore(cap, std::move(ring), head, size);
    if (!GetUpdate(&r, &h.last_update) || !r.Get(&bootstrapped) || !r.Get(&has_trial)) return false;
    h.dominant = dominant != 0;
    h.steps = steps;
    h.failing_steps = failing;
    h.lagging_steps = lagging;
    h.bootstrapped = bootstrapped != 0;
    if ((h.state == HypothesisState::kJuvenile) != (has_trial != 0)) return false;
    for (const Hypothesis& o : hypotheses)
      if (o.id == h.id) return false;
    if (has_trial) {
      std::string blob;
      if (!r.GetString(&blob, kMaxBlob)) return false;
      h.trial_map = factory_();
      if (!h.trial_map->Deserialize(blob)) return false;
      if (version >= 4) {
        if (!r.GetPose(&h.seed.mean)) return false;
        for (int row = 0; row < 3; ++row)
          for (int col = row; col < 3; ++col) {
            if (!r.Get(&h.seed.cov(row, col))) return false;
            h.seed.cov(col, row) = h.seed.cov(row, col);
          }
        if (!h.seed.mean.IsFinite() || !ValidCovariance(h.seed.cov)) return false;
      }
    }
    // Z grows by at most one scan a step, only while the juvenile is not bootstrapped, and is
    // kept past bootstrap_scans only while an undetermined w accumulates, i.e. while steps <
    // probation_scans: it holds fewer than probation_scans scans, and no more than steps.
    if (!r.Get(&nz) || nz >= static_cast<uint32_t>(options_.lifecycle.probation_scans) ||
        nz > static_cast<uint32_t>(steps) ||
        (nz > 0 && (h.state != HypothesisState::kJuvenile || h.bootstrapped)))
      return false;
    h.z.resize(nz);
    for (JuvenileScan& z : h.z)
      if (!r.GetPose(&z.odometry_delta) || !GetScan(&r, &z.scan) || !GetUpdate(&r, &z.update) ||
          (version >= 3 && !GetSonar(&r, &z.sonar)))
        return false;
    if (has_trial && version < 4) {
      // No seed saved: w's Z starts again from the juvenile's current pose.
      h.seed = h.trial_map->RobotPose();
      h.z.clear();
    }
    for (const Hypothesis& o : hypotheses)
      if (o.frame == h.frame) return false;  // at most one hypothesis per frame
    hypotheses.push_back(std::move(h));
  }
  if (!r.AtEnd()) return false;
  // After any step the atlas has a mature hypothesis (a mature one is retired only when
  // another stays or Genesis makes one); without one, it would output nothing from now on.
  if (graph.FrameCount() > 0 &&
      std::none_of(hypotheses.begin(), hypotheses.end(),
                   [](const Hypothesis& h) { return h.state == HypothesisState::kMature; }))
    return false;
  graph_ = std::move(graph);
  components_.Rebuild(graph_);
  hypotheses_ = std::move(hypotheses);
  step_ = step;
  graph_pending_ = false;
  next_hypothesis_id_ = next_id;
  last_genesis_step_ = last_genesis;
  match_cursor_ = cursor;
  projection_step_ = -1;
  projection_source_ = kNoFrame;
  for (CachedSelfMatch& c : self_cache_) c = CachedSelfMatch{};
  for (TriedPair& t : tried_) t = TriedPair{};
  stats_ = StepStats{};
  return true;
}

}  // namespace atlas
