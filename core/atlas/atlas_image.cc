// The atlas's byte image: Atlas::Serialize, SerializeWithoutFrameMaps, Deserialize and
// DeserializeWithFrameMaps (format in byte_image.h).
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/atlas/byte_image.h"

namespace atlas {

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

std::string Atlas::Serialize() const { return SerializeImage(true); }

std::string Atlas::SerializeWithoutFrameMaps() const { return SerializeImage(false); }

bool Atlas::Deserialize(const std::string& bytes) {
  return DeserializeWithFrameMaps(bytes, FrameMapImages()).ok();
}

std::string Atlas::SerializeImage(bool frame_maps) const {
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
    // Kept apart: an empty map image, which no map writes (every one begins with its magic).
    w.PutString(frame_maps ? frame.map->Serialize() : std::string());
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
      PutScan(&w, z.observation.scan());
      PutUpdate(&w, z.update);
      PutSonar(&w, z.sonar);
    }
  }
  return std::move(w.bytes());
}

ImageLoadResult Atlas::DeserializeWithFrameMaps(const std::string& bytes,
                                                const FrameMapImages& frame_maps) {
  const ImageLoadResult malformed;
  ByteReader r(bytes);
  uint32_t magic = 0, version = 0, frames = 0, edges = 0, hyps = 0;
  int64_t step = 0, next_id = 0, last_genesis = 0;
  uint64_t cursor = 0;
  if (!r.Get(&magic) || magic != kMagic || !r.Get(&version) || version < 1 ||
      version > kImageVersion || !r.Get(&step) || !r.Get(&next_id) || !r.Get(&last_genesis) ||
      !r.Get(&cursor) || !r.Get(&frames) || frames > (1u << 24))
    return malformed;
  if (step < 0 || step > kMaxStep || next_id < 0 || next_id > kMaxStep ||
      last_genesis < kNoGenesisStep || last_genesis > step)
    return malformed;
  AtlasGraph graph(options_.max_degree);
  for (uint32_t i = 0; i < frames; ++i) {
    int64_t created = 0, cooldown = 0;
    int32_t retirements = 0;
    std::string blob;
    if (!r.Get(&created) || !r.Get(&cooldown) || !r.Get(&retirements) ||
        !r.GetString(&blob, kMaxBlob))
      return malformed;
    // The cooldown was set with the seed_cooldown_steps of its time: bounded, not tied to ours.
    if (created < 0 || created > step || cooldown < -1 || cooldown > kMaxStep || retirements < 0 ||
        retirements == INT32_MAX)
      return malformed;
    const FrameId id = graph.FrameCount();
    std::unique_ptr<LocalMap> map = factory_();
    if (version >= 6 && blob.empty()) {
      const std::string* kept = frame_maps ? frame_maps(id) : nullptr;
      if (kept == nullptr) return ImageLoadResult{ImageLoadStatus::kFrameMapMissing, id};
      if (!map->Deserialize(*kept)) return ImageLoadResult{ImageLoadStatus::kFrameMapMalformed, id};
    } else if (!map->Deserialize(blob)) {
      return malformed;
    }
    FramePoints points(options_.points);
    if (version >= 5 && (!r.GetString(&blob, kMaxBlob) || !points.Deserialize(blob)))
      return malformed;
    graph.AddFrame(std::move(map), created);
    graph.MutableFrame(id).points = std::move(points);
    graph.MutableFrame(id).seed_cooldown_until = cooldown;
    graph.MutableFrame(id).retirements = retirements;
  }
  if (!r.Get(&edges) || edges > (1u << 28)) return malformed;
  for (uint32_t i = 0; i < edges; ++i) {
    AtlasEdge e;
    int32_t refinements = 0;
    if (!r.Get(&e.a) || !r.Get(&e.b) || !r.GetUncertain(&e.b_in_a) || !r.Get(&e.kind) ||
        !r.Get(&e.origin) || !r.Get(&e.made_step) || !r.Get(&e.refined_step) ||
        !r.Get(&refinements))
      return malformed;
    // An edge is made by Genesis or map-matching; only covariance intersection (RefineEdges,
    // at most once per step and edge, after the step that made it) changes its kind.
    if (static_cast<uint8_t>(e.kind) > 2 || e.origin == EdgeKind::kRefined ||
        static_cast<uint8_t>(e.origin) > 2 || (e.kind != e.origin && e.kind != EdgeKind::kRefined))
      return malformed;
    if (!e.b_in_a.mean.IsFinite() || !ValidCovariance(e.b_in_a.cov) || e.made_step < 0 ||
        e.made_step > step)
      return malformed;
    const bool refined = e.kind == EdgeKind::kRefined;
    if (refined ? refinements < 1 || refinements > e.refined_step - e.made_step ||
                      e.refined_step <= e.made_step || e.refined_step > step
                : refinements != 0 || e.refined_step != -1)
      return malformed;
    if (graph.AddEdge(e.a, e.b, e.b_in_a, e.origin, e.made_step) != AddEdgeResult::kAdded)
      return malformed;
    if (refined) graph.RestoreRefinements(graph.EdgeCount() - 1, refinements, e.refined_step);
  }
  if (!r.Get(&hyps) || hyps > static_cast<uint32_t>(options_.max_hypotheses)) return malformed;
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
      return malformed;
    // Ids are handed out from next_id; a hypothesis is born at a step and counts the steps
    // since (the first frame's also the step it was made in); q is eq. 5, in [0, 1].
    if (h.id < 0 || h.id >= next_id || h.born_step < 0 || h.born_step > step || steps < 0 ||
        steps > step - h.born_step + 1 || steps == INT32_MAX || !std::isfinite(h.q) || h.q < 0.0 ||
        h.q > 1.0 || failing < 0 || failing > steps || lagging < 0 || lagging == INT32_MAX)
      return malformed;
    std::vector<QualityWindow::Entry> ring(cap);
    for (QualityWindow::Entry& e : ring)
      if (!r.Get(&e.observations) || !r.Get(&e.matched) || !ValidCount(e.observations) ||
          e.matched < 0 || e.matched > e.observations)
        return malformed;
    h.window.Restore(cap, std::move(ring), head, size);
    if (!GetUpdate(&r, &h.last_update) || !r.Get(&bootstrapped) || !r.Get(&has_trial))
      return malformed;
    h.dominant = dominant != 0;
    h.steps = steps;
    h.failing_steps = failing;
    h.lagging_steps = lagging;
    h.bootstrapped = bootstrapped != 0;
    if ((h.state == HypothesisState::kJuvenile) != (has_trial != 0)) return malformed;
    for (const Hypothesis& o : hypotheses)
      if (o.id == h.id) return malformed;
    if (has_trial) {
      std::string blob;
      if (!r.GetString(&blob, kMaxBlob)) return malformed;
      h.trial_map = factory_();
      if (!h.trial_map->Deserialize(blob)) return malformed;
      if (version >= 4) {
        if (!r.GetPose(&h.seed.mean)) return malformed;
        for (int row = 0; row < 3; ++row)
          for (int col = row; col < 3; ++col) {
            if (!r.Get(&h.seed.cov(row, col))) return malformed;
            h.seed.cov(col, row) = h.seed.cov(row, col);
          }
        if (!h.seed.mean.IsFinite() || !ValidCovariance(h.seed.cov)) return malformed;
      }
    }
    // Z grows by at most one scan a step, only while the juvenile is not bootstrapped, and is
    // kept past bootstrap_scans only while an undetermined w accumulates, i.e. while steps <
    // probation_scans: it holds fewer than probation_scans scans, and no more than steps.
    if (!r.Get(&nz) || nz >= static_cast<uint32_t>(options_.lifecycle.probation_scans) ||
        nz > static_cast<uint32_t>(steps) ||
        (nz > 0 && (h.state != HypothesisState::kJuvenile || h.bootstrapped)))
      return malformed;
    h.z.resize(nz);
    for (JuvenileScan& z : h.z) {
      LaserScan scan;
      if (!r.GetPose(&z.odometry_delta) || !GetScan(&r, &scan) || !GetUpdate(&r, &z.update) ||
          (version >= 3 && !GetSonar(&r, &z.sonar)))
        return malformed;
      z.observation = ScanObservation(std::move(scan));  // its lines are extracted on demand
    }
    if (has_trial && version < 4) {
      // No seed saved: w's Z starts again from the juvenile's current pose.
      h.seed = h.trial_map->RobotPose();
      h.z.clear();
    }
    for (const Hypothesis& o : hypotheses)
      if (o.frame == h.frame) return malformed;  // at most one hypothesis per frame
    hypotheses.push_back(std::move(h));
  }
  if (!r.AtEnd()) return malformed;
  // After any step the atlas has a mature hypothesis (a mature one is retired only when
  // another stays or Genesis makes one); without one, it would output nothing from now on.
  if (graph.FrameCount() > 0 &&
      std::none_of(hypotheses.begin(), hypotheses.end(),
                   [](const Hypothesis& h) { return h.state == HypothesisState::kMature; }))
    return malformed;
  graph_ = std::move(graph);
  pending_match_.reset();
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
  return ImageLoadResult{ImageLoadStatus::kLoaded, kNoFrame};
}

}  // namespace atlas
