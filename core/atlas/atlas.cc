#include "core/atlas/atlas.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>

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
  if (max_bootstraps_per_step < 1) return "max_bootstraps_per_step must be at least 1";
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
  if (!(capacity_explanation >= 0 && capacity_explanation <= 1))
    return "capacity_explanation must lie in [0, 1]";
  if (genesis_min_interval_steps < 0) return "genesis_min_interval_steps must be non-negative";
  if (resume_candidates_per_step < 0) return "resume_candidates_per_step must be non-negative";
  if (resume_scan_per_step < 1) return "resume_scan_per_step must be at least 1";
  return "";
}

AtlasOptions SonarAtlasOptions(AtlasOptions o) {
  o.match = SonarMapMatchOptions();
  o.points.enabled = false;
  o.genesis_cov_scale = 1.0;
  o.return_q = 0.0;
  o.return_far_radius = 0.0;
  return o;
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
  return h.state == HypothesisState::kJuvenile ? *h.trial_map : graph_.MutableMap(h.frame);
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
  const int d = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
  if (d < 0) return out;
  const Hypothesis& h = hypotheses_[d];
  out.valid = true;
  out.hypothesis = h.id;
  out.frame = h.frame;
  out.pose = PoseOf(h);
  out.q = h.q;
  out.switched = previous_dominant_ >= 0 && h.id != previous_dominant_;
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
  previous_dominant_ = -1;
  for (const Hypothesis& h : hypotheses_)
    if (h.dominant) previous_dominant_ = h.id;
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
  const int d = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
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
  w_searches_ = 0;
  // While a map-matching search is pending over steps, it and w take turns: w yields at odd
  // steps, map-matching whenever w searched.
  const bool w_yields = pending_match_ && step_ % 2 == 1;
  // One observation for every hypothesis: the maps share its lines.
  const ScanObservation observation = scan ? ScanObservation(*scan) : ScanObservation();
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
      h.last_update = map.Update(observation, mature);
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
      h.z.push_back(
          JuvenileScan{delta, observation, h.last_update, sonar ? *sonar : SonarReading{}});
      if (static_cast<int>(h.z.size()) >= options_.lifecycle.bootstrap_scans &&
          !(bootstrapper_ && w_yields) &&
          (h.w_search || w_searches_ < options_.max_bootstraps_per_step)) {
        bool accumulate = false;
        if (bootstrapper_) {
          ++w_searches_;
          const LocalMap& frame_map = *graph_.Frame(h.frame).map;
          if (!h.w_search) {
            ++stats_.bootstraps;
            h.w_search = bootstrapper_->Begin(map, frame_map, h.z, h.seed);
            h.w_begun_at = h.z.size();
          }
          if (!h.w_search->Continue(map, frame_map, h.z)) {
            accumulate = true;  // w goes on at the next step; Z keeps growing meanwhile
          } else {
            accumulate = UseBootstrap(static_cast<int>(i), map, h.w_search->TakeResult());
            h.w_search.reset();
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
    h.q = HypothesisQuality(PoseOf(h).cov, h.window.Explanation(options_.quality.empty_explanation),
                            options_.quality);
  }
}

bool Atlas::UseBootstrap(int i, LocalMap& map, PoseBootstrap r) {
  Hypothesis& h = hypotheses_[i];
  if (r.outcome == BootstrapOutcome::kSolved) {
    if (r.map) {
      h.trial_map = std::move(r.map);  // M_i^new of eq. 12
    } else {
      // The pose at Z's last step as it was at Begin, carried to now by the odometry.
      map.ResetRobotPose(r.pose);
      for (size_t k = h.w_begun_at; k < h.z.size(); ++k) map.Predict(h.z[k].odometry_delta);
    }
    h.bootstrapped = true;
    return false;
  }
  if (r.outcome == BootstrapOutcome::kUndetermined && h.steps < options_.lifecycle.probation_scans)
    return true;
  bootstrap_failed_[i] = 1;
  return false;
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
      graph_.ReplaceMap(h.frame, std::move(h.trial_map));
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
  const int dominant = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
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
    const int from = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
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
  const int d = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
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
  const int d = DominantIndex(hypotheses_, options_.lifecycle.switch_margin);
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
  if (matcher_) return false;  // the matcher has no self-matches to cache
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
  return map.Reaches(p, reach);
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

bool Atlas::ContinuePendingMatch() {
  if (!pending_match_) return false;
  const int n = graph_.FrameCount();
  if (pending_a_ >= n || pending_b_ >= n) {  // the graph was replaced (Deserialize)
    pending_match_.reset();
    return false;
  }
  if (!pending_match_->Continue(*graph_.Frame(pending_a_).map, *graph_.Frame(pending_b_).map))
    return true;
  ApplyMatch(pending_a_, pending_b_, pending_match_->Result());
  pending_match_.reset();
  return true;
}

void Atlas::MatchMaps(int d) {
  if (d < 0 || options_.match_candidates_per_step == 0) return;
  // A matcher's search may span steps: one at a time, its slice is this step's search, unless
  // w searched this step (see UpdateHypotheses). A new search's first slice always runs.
  if (matcher_ && pending_match_) {
    if (w_searches_ == 0) ContinuePendingMatch();
    return;
  }
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
    if (matcher_) {
      pending_match_ =
          matcher_->Begin(*graph_.Frame(dom_frame).map, *graph_.Frame(e.frame).map, &e.pose);
      pending_a_ = dom_frame;
      pending_b_ = e.frame;
      ContinuePendingMatch();
      if (pending_match_) break;  // goes on at the next steps
      continue;
    }
    MatchPair(dom_frame, e.frame, &e.pose);
  }
  match_cursor_ += static_cast<uint64_t>(advance);
}

MapMatch Atlas::MatchWithLines(FrameId dom_frame, FrameId other, const UncertainPose* prior) {
  const SelfMatch& self_a = SelfMatchOf(dom_frame);
  const SelfMatch self_a_copy = self_a;  // the cache may evict it while matching b
  const SelfMatch& self_b = SelfMatchOf(other);
  return atlas::MatchMaps(graph_.Frame(dom_frame).map->Lines(), self_a_copy,
                          graph_.Frame(other).map->Lines(), self_b, prior, options_.match,
                          options_.points.enabled ? &graph_.Frame(dom_frame).points : nullptr,
                          options_.points.enabled ? &graph_.Frame(other).points : nullptr);
}

void Atlas::MatchPair(FrameId dom_frame, FrameId other, const UncertainPose* prior) {
  ApplyMatch(dom_frame, other,
             matcher_
                 ? matcher_->Match(*graph_.Frame(dom_frame).map, *graph_.Frame(other).map, prior)
                 : MatchWithLines(dom_frame, other, prior));
}

void Atlas::ApplyMatch(FrameId dom_frame, FrameId other, const MapMatch& m) {
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

}  // namespace atlas
