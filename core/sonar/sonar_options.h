#pragma once
// Options of the sonar line mapping (module atlas_sonar): the wide-beam measurement model,
// the gated EKF update, and RANSAC grouping with delayed decision making for new features
// (paper, Section IV, Fig. 9). One struct with defaults, validated once by Validate().

#include <cstdint>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

// Which sensors a SonarLocalMap uses (laser alone, sonar alone, or both).
enum class RangeSensors { kLaser, kSonar, kBoth };

struct SonarModelOptions {
  // Range noise of one return: sigma = range_sigma + range_sigma_per_m * range (metres), plus
  // model_sigma for walls that are not quite where the tangent model puts them.
  double range_sigma = 0.01;
  double range_sigma_per_m = 0.01;
  double model_sigma = 0.02;
  // The cone used for interpretation is the transducer's beam_width times this (>= 1 widens it).
  double cone_scale = 1.0;
  // Critical incidence of a specular wall (radians): a wall whose normal lies up to this much
  // outside the cone still echoes along the cone's edge ray, range d / cos(psi)
  // (PredictSonarRange). 0 = pure tangent model (edge echoes are then outliers).
  double edge_incidence = 0.3;
  // Returns at or beyond this fraction of the transducer's max_range are not used.
  double max_range_fraction = 0.95;
  double min_range = 0.1;  // metres

  std::string Validate() const;
};

struct SonarUpdateOptions {
  double gate = 0.99;  // chi-square probability (1 dof) for pairing a return with a feature
  // A return compatible with a feature at this looser probability is never kept for
  // initialising new features (it belongs to a mapped wall, or to none).
  double loose_gate = 0.9999;
  // The tangent point must lie within the feature's extent, or at most this far beyond it. It
  // must bridge a doorway or an alcove's opening, so that the wall on its far side (the same
  // line) updates the feature instead of being buffered for the initialiser as a new wall.
  // 1.5 m (was 1.0) bridges the simulator's alcove openings (1.5 m): over 100 runs of each
  // world (atlas-sonar-eval atlas, seeds 1-91, w off), the alcove loop's robot NEES was inside
  // the band at 83.8 % of steps instead of 44.9 % (gross false closures 3 -> 0) and the building
  // at 48.4 % (49.4 %); 0.5 or 0.3 make both worse (building 41 / 23 %), 2.0 and 3.0 are
  // between (docs/design.md, "Sonar local maps").
  double max_extent_gap = 1.5;
  // An edge-of-cone echo grows a feature's extent only to the point of its cone's footprint on
  // the line nearest to the extent (none when they overlap), not to where its edge ray meets the
  // line (the jambs of alcoves grew across the corridor). In-cone echoes grow it to their
  // tangent point either way. Off: the earlier rule, kept for comparison.
  bool edge_extent_footprint = true;
  // Two features within the gate: the return is ambiguous unless the best one's squared
  // distance is smaller than the other's minus this margin.
  double ambiguity_margin = 4.0;
  // A return longer than the range predicted for a mapped feature that echoes in this cone
  // (within its extent) by more than behind_sigmas standard deviations of the innovation came
  // back after a second bounce (multipath, Fig. 9's specular misses): neither used nor buffered.
  double behind_sigmas = 4.0;
  // A line from the initialiser closer than this to a feature (|d alpha| radians and
  // |d rho| metres, map frame) is a duplicate of it and is not added.
  double duplicate_alpha = 0.25;
  double duplicate_rho = 0.3;

  std::string Validate() const;
};

// RANSAC grouping of buffered returns with delayed decision making (Leonard and Rikoski).
struct SonarInitOptions {
  int max_returns = 256;            // buffer capacity (oldest dropped first)
  int max_vantage = 128;            // vantage points kept (oldest dropped first)
  double window_m = 6.0;            // vantage points farther than this from the robot are dropped
  int iterations = 120;             // RANSAC hypotheses per decision (work bound)
  double min_pair_baseline = 0.25;  // metres between the two vantage points of a sample
  double inlier_sigmas = 2.5;       // |r - predicted| within this many sigmas
  int min_support = 6;              // inlier returns
  int min_vantage = 4;              // distinct vantage points among the inliers
  double min_baseline = 1.0;        // metres spanned by the inliers' vantage points
  // Rival: a different line (|d alpha| > rival_alpha or |d rho| > rival_rho) sharing at least
  // rival_overlap of the best line's inliers. It makes the grouping ambiguous when its support
  // is at least rival_ratio of the best's: the decision is delayed.
  double rival_alpha = 0.15;
  double rival_rho = 0.2;
  double rival_overlap = 0.3;
  double rival_ratio = 0.7;
  // Arcs through one point (a corner or edge: a point reflector) are tangent to many lines;
  // their tangent points stay close together while the vantage points move. A line whose
  // tangent points span less than this fraction of its vantage baseline is not accepted.
  double min_extent_ratio = 0.4;
  // Delayed decision between a wall and a point reflector (a corner, a jamb's edge, or the
  // virtual source of a multipath echo: the range is the distance to one point, wherever it
  // lies in the cone). The best line's inliers are also fitted with one point (Gauss-Newton
  // on the ranges); when the point explains at least rival_ratio of them, the returns do not
  // tell a wall from a point and no line is made from them. Off: only min_extent_ratio. In the
  // simulated corridor (atlas-sonar-eval mc, 20 runs, 24 transducers, edge echoes off) it
  // removes 105 of the 123 initialisations farther than 0.25 m or 10 deg from every wall and
  // none of the 40 on a wall (docs/design.md, "Sonar local maps").
  bool point_rival = true;
  // Whether grouping counts edge-of-cone echoes (SonarModelOptions::edge_incidence) as inliers.
  // Off: RANSAC, the refinement and the line's covariance use the tangent model alone (in-cone
  // echoes). With edge echoes admitted, a group of returns fits lines over another
  // 2 x edge_incidence of angles, and the edge terms' strong d range / d alpha make a wrong
  // angle look certain: diagonal phantom lines at corners and end walls approached head-on
  // were initialised some 15 degrees off (line NEES at initialisation 9.8 against 2 expected).
  // Edge echoes of mapped features are still used by the updates. Off, together with point_rival
  // and the sonar atlas's alternative_sigmas (SonarMapMatchOptions): over 100 seeded runs each of
  // the building and of the alcove loop (docs/design.md, "Sonar local maps") the sonar-only atlas
  // makes half the false closures (11, 5 gross, against 25, 9 gross with edge echoes on) and its
  // robot NEES is inside the band on 49 % of the building's steps (37 %); on the alcove loop it
  // closes fewer loops and is inside the band less often (45 %, 51 %).
  bool edge_echoes = false;
  int max_new_per_decision = 2;
  // Delayed decision making with consistent covariance (SonarLocalMap, delayed_vantages.h): the
  // vantage points are delayed states of the EKF and an accepted line is added with its
  // correlation with the past poses. Off: the line's robot-frame covariance (vantage points
  // independent of each other and of the map) goes through the inverse model as if it were one
  // observation from the current pose (the earlier approximation, kept for comparison: on the
  // hand-made Monte Carlo case, DelayedVantages.InitialisedLineCovarianceMatchesMonteCarlo, its
  // rho variance is 3.9 times too small and its correlation with the heading is missed).
  bool delayed_states = true;
  // Floors on the initialised line's standard deviations (rho metres, alpha radians).
  double min_rho_sigma = 0.01;
  double min_alpha_sigma = 0.005;
  uint64_t seed = 1;

  std::string Validate() const;
};

struct SonarLocalMapOptions {
  RangeSensors sensors = RangeSensors::kSonar;
  // The transducers of the robot's ring (drivers/p2os P3dxSonarRing/B21SonarRing), used by
  // UpdateWithSonar; index = SonarReturn::transducer. Empty: UpdateWithSonar uses no return.
  std::vector<SonarTransducer> ring;
  LocalMapOptions line_map;  // the EKF (odometry noise, capacity, laser path)
  SonarModelOptions model;
  SonarUpdateOptions update;
  SonarInitOptions init;

  std::string Validate() const;
};

}  // namespace atlas
