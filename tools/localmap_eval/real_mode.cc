#include "tools/localmap_eval/real_mode.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "atlas_paths.h"
#include "core/eval/error_stats.h"
#include "core/eval/relations_metric.h"
#include "core/localmap/line_ekf_map.h"
#include "core/mapper/odometry_track.h"
#include "core/scanmatch/scan_matcher.h"
#include "formats/text_rows.h"
#include "logs/carmen/carmen_log.h"
#include "tools/cli/command_line.h"
#include "tools/eval/trajectory_files.h"
#include "tools/localmap_eval/filter_overrides.h"
#include "tools/render/canvas.h"

namespace atlas::localmap_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

LocalMapOptions RealFilterOptions(int capacity) {
  LocalMapOptions o;
  o.capacity = capacity;
  o.extraction.range_sigma = 0.01;
  // Walls that are not straight to the centimetre plus the log's 1 cm range quantisation: at
  // 0.015 the chi-square fit test (extraction.fit_gate) rejected 6 % of the lines.
  o.extraction.model_sigma = 0.03;
  o.extraction.split_distance = 0.06;
  o.extraction.min_points = 10;
  o.extraction.min_length = 0.6;
  o.odometry.track_width = 0.5;
  o.odometry.wheel_var_per_m = 1e-4;
  o.odometry.xy_var_per_m = 1e-3;
  o.odometry.xy_var_per_rad = 1e-4;
  o.odometry.theta_var_per_m = 5e-3;
  o.odometry.theta_var_per_rad = 3e-2;
  o.extraction.min_rho_sigma = 0.03;
  o.extraction.min_alpha_sigma = 0.02;
  o.association.new_feature_min_length = 1.0;
  return o;
}

struct ScanRecord {
  Time stamp{};
  int stretch = 0;
  Pose2 estimate;        // in the stretch's map-frame
  Pose2 odometry;        // the log's, at the stamp
  Pose2 odometry_taken;  // at the stamp + laser time offset (the filter's)
  const LaserScan* scan = nullptr;
};

// The options' defaults.
struct RealDefaults {
  std::string log = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
  std::string relations = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.relations";
  double stretch_m = 30;
  double draw_stretch = 3;
  double laser_x = 0.0;
  double time_offset_s = 0.0;
  int capacity = 100;
  int scan_match = 1;
};

int RunRealMode(const cli::ToolOptions& args) {
  const RealDefaults d;
  std::string log_path = d.log;
  std::string rel_path = d.relations;
  if (args.values.count("--log")) log_path = args.values.at("--log");
  if (args.values.count("--relations")) rel_path = args.values.at("--relations");
  double stretch_m = d.stretch_m, draw_stretch = d.draw_stretch, laser_x = d.laser_x,
         time_offset_s = d.time_offset_s;
  int capacity = d.capacity, scan_match = d.scan_match;
  std::string error;
  if (!GetNumberOption(args, "--stretch", 1, 1e6, stretch_m, error) ||
      !GetNumberOption(args, "--laser-x", -2, 2, laser_x, error) ||
      !GetNumberOption(args, "--laser-time-offset", -1, 1, time_offset_s, error) ||
      !GetIntegerOption(args, "--scan-match", 0, 1, scan_match, error) ||
      !GetIntegerOption(args, "--capacity", 1, 10000, capacity, error) ||
      !GetNumberOption(args, "--draw-stretch", 0, 1e6, draw_stretch, error)) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s\n", error.c_str());
    return 2;
  }
  std::fprintf(stderr, "reading %s ...\n", log_path.c_str());
  const carmen::CarmenReadResult read = carmen::ReadCarmenLog(log_path, carmen::CarmenLogOptions());
  if (!read.ok()) {
    std::fprintf(stderr, "atlas-localmap-eval real: cannot read the log: %s (give --log FILE)\n",
                 read.error.c_str());
    return 1;
  }
  const formats::TextFile rel_text = formats::ReadTextFile(rel_path);
  if (!rel_text.error.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s (give --relations FILE)\n",
                 rel_text.error.c_str());
    return 1;
  }
  const eval::RelationsParse rels = eval::ParseRelations(rel_text.text, rel_path);
  if (!rels.error.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s\n", rels.error.c_str());
    return 1;
  }
  LocalMapOptions options = RealFilterOptions(static_cast<int>(capacity));
  const std::string invalid =
      ApplyOverrides(args.values.count("--set") ? args.values.at("--set") : "", options);
  if (!invalid.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: bad filter options: %s\n", invalid.c_str());
    return 1;
  }
  // The odometry of the laser lines, to look it up at stamp + offset (as atlasd's loop does).
  std::vector<OdometrySample> samples;
  for (const carmen::CarmenEvent& ev : read.log.events) {
    const LaserScan* scan = std::get_if<LaserScan>(&ev.event);
    if (scan != nullptr && ev.odometry_pose) samples.push_back({scan->stamp, *ev.odometry_pose});
  }
  OdometryTrack track(samples.size(), Duration::zero());
  for (const OdometrySample& o : samples) track.Add(o);
  const Duration time_offset = FromSeconds(time_offset_s).time_since_epoch();
  std::vector<ScanRecord> records;
  std::unique_ptr<LineEkfMap> map;
  std::unique_ptr<LineEkfMap> drawn;
  std::vector<size_t> drawn_records;
  int stretch = -1;
  double travelled = 0.0;
  Pose2 last_odo;
  bool have_odo = false;
  int updates = 0, matched = 0, observed = 0, ambiguous = 0, recovered = 0;
  ScanMatchOptions match_options;
  match_options.enabled = scan_match != 0;
  ScanMatcher matcher(match_options);
  int64_t increments_matched = 0, match_fallbacks = 0;
  for (const carmen::CarmenEvent& ev : read.log.events) {
    const LaserScan* scan = std::get_if<LaserScan>(&ev.event);
    if (scan == nullptr || !ev.odometry_pose) continue;
    Pose2 odo = *ev.odometry_pose;
    if (time_offset != Duration::zero()) track.PoseAt(scan->stamp + time_offset, &odo);
    Pose2 delta;
    if (have_odo) {
      delta = Between(last_odo, odo);
      travelled += std::hypot(delta.x, delta.y);
    }
    LaserScan mounted = *scan;
    mounted.sensor_pose = Compose(Pose2{laser_x, 0.0, 0.0}, scan->sensor_pose);
    if (!map || travelled >= stretch_m) {
      if (map && stretch == static_cast<int>(draw_stretch)) drawn = std::move(map);
      map = std::make_unique<LineEkfMap>(options);
      ++stretch;
      travelled = 0.0;
    } else if (match_options.enabled && matcher.HasReference()) {
      const ScanMatchResult m =
          matcher.Match(mounted, {delta, LineEkfMap::OdometryNoise(delta, options.odometry)});
      if (m.outcome == ScanMatchOutcome::kMatched) {
        ++increments_matched;
        map->Predict(m.increment.mean, m.increment.cov);
      } else {
        ++match_fallbacks;
        map->Predict(delta);
      }
    } else {
      map->Predict(delta);
    }
    if (match_options.enabled) matcher.SetReference(mounted);
    last_odo = odo;
    have_odo = true;
    const UncertainPose prior = map->RobotPose();
    const ScanUpdate up = map->Update(mounted, true);
    if (std::getenv("LOCALMAP_DEBUG") && up.added > 0) {
      const UncertainPose rp = map->RobotPose();
      for (const MapLine& l : map->Lines()) {
        if (l.id < map->Lines().back().id - up.added + 1) continue;
        std::fprintf(stderr,
                     "scan t %.2f stretch %d: new feature %d (%.3f m, %.2f deg) length %.2f m, "
                     "robot sd %.3f m %.1f deg, %d features\n",
                     ToSeconds(scan->stamp.time_since_epoch()), stretch, l.id, l.rho,
                     l.alpha * 180 / M_PI, (l.endpoint_b - l.endpoint_a).norm(),
                     std::sqrt(rp.cov(0, 0) + rp.cov(1, 1)), std::sqrt(rp.cov(2, 2)) * 180 / M_PI,
                     map->Complexity());
      }
    }
    if (std::getenv("LOCALMAP_DEBUG")) {
      const double turn = WrapAngle(map->RobotPose().mean.theta - prior.mean.theta);
      if (std::abs(turn) > 0.05) {
        std::fprintf(
            stderr,
            "scan t %.2f stretch %d: heading corrected %.1f deg (prior sd %.1f deg, odometry "
            "step %.1f deg), %d lines, %d matched%s, %d features\n",
            ToSeconds(scan->stamp.time_since_epoch()), stretch, turn * 180 / M_PI,
            std::sqrt(prior.cov(2, 2)) * 180 / M_PI, delta.theta * 180 / M_PI, up.observations,
            up.matched, map->LastUpdateRecovered() ? " (recovery)" : "", map->Complexity());
      }
    }
    ++updates;
    recovered += map->LastUpdateRecovered() ? 1 : 0;
    matched += up.matched;
    observed += up.observations;
    ambiguous += up.ambiguous ? 1 : 0;
    records.push_back(
        ScanRecord{scan->stamp, stretch, map->RobotPose().mean, *ev.odometry_pose, odo, scan});
    if (stretch == static_cast<int>(draw_stretch)) drawn_records.push_back(records.size() - 1);
  }
  if (map && stretch == static_cast<int>(draw_stretch)) drawn = std::move(map);
  std::fprintf(stderr,
               "%d scans, %d stretches of %.0f m; %d lines observed, %d matched (%.1f%%), "
               "%d scans with an ambiguous association, %d paired only by the recovery pass\n",
               updates, stretch + 1, stretch_m, observed, matched,
               100.0 * matched / std::max(1, observed), ambiguous, recovered);
  if (match_options.enabled) {
    std::fprintf(stderr, "scan matching: %lld increments matched, %lld fell back to the odometry\n",
                 static_cast<long long>(increments_matched),
                 static_cast<long long>(match_fallbacks));
  }

  // Relations with both poses in one stretch.
  auto find = [&](Time t) -> const ScanRecord* {
    auto it = std::lower_bound(records.begin(), records.end(), t,
                               [](const ScanRecord& r, Time x) { return r.stamp < x; });
    const ScanRecord* best = nullptr;
    Duration best_d = eval::kDefaultMatchTolerance + Duration(1);
    for (auto c : {it, it == records.begin() ? it : it - 1}) {
      if (c == records.end()) continue;
      const Duration d = c->stamp > t ? c->stamp - t : t - c->stamp;
      if (d < best_d) {
        best_d = d;
        best = &*c;
      }
    }
    return best_d <= eval::kDefaultMatchTolerance ? best : nullptr;
  };
  std::vector<double> est_t, est_r, dr_t, dr_r, drs_t, drs_r;
  int unmatched = 0, cross_stretch = 0;
  for (const eval::Relation& rel : rels.relations) {
    const ScanRecord* a = find(rel.t1);
    const ScanRecord* b = find(rel.t2);
    if (a == nullptr || b == nullptr) {
      ++unmatched;
      continue;
    }
    if (a->stretch != b->stretch) {
      ++cross_stretch;
      continue;
    }
    const eval::RelationError e = eval::RelationErrorOf(rel, Between(a->estimate, b->estimate));
    const eval::RelationError d = eval::RelationErrorOf(rel, Between(a->odometry, b->odometry));
    if (std::getenv("LOCALMAP_DEBUG")) {
      std::fprintf(stderr,
                   "rel stretch %d t %.2f dt %.2f move %.3f %.3f: ekf %.4f %.3f dr %.4f %.3f "
                   "(odometry turn %.3f, ekf turn %.3f)\n",
                   a->stretch, ToSeconds(rel.t1.time_since_epoch()), ToSeconds(rel.t2 - rel.t1),
                   rel.delta.x, rel.delta.theta, e.translation_m, e.rotation_deg, d.translation_m,
                   d.rotation_deg, Between(a->odometry, b->odometry).theta,
                   Between(a->estimate, b->estimate).theta);
    }
    est_t.push_back(e.translation_m);
    est_r.push_back(e.rotation_deg);
    dr_t.push_back(d.translation_m);
    dr_r.push_back(d.rotation_deg);
    const eval::RelationError ds =
        eval::RelationErrorOf(rel, Between(a->odometry_taken, b->odometry_taken));
    drs_t.push_back(ds.translation_m);
    drs_r.push_back(ds.rotation_deg);
  }
  const eval::ErrorStats et = eval::Summarize(est_t), er = eval::Summarize(est_r);
  const eval::ErrorStats dt = eval::Summarize(dr_t), dr = eval::Summarize(dr_r);
  const eval::ErrorStats dst = eval::Summarize(drs_t), dsr = eval::Summarize(drs_r);
  std::printf(
      "mit-csail: %zu relations; scored %zu (both poses in one %.0f m stretch), %d across "
      "stretches, %d without a scan\n",
      rels.relations.size(), est_t.size(), stretch_m, cross_stretch, unmatched);
  std::printf(
      "  local map EKF  : trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg\n",
      et.mean, et.stddev, et.rmse, et.max, er.mean, er.stddev);
  std::printf(
      "  dead reckoning : trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg\n",
      dt.mean, dt.stddev, dt.rmse, dt.max, dr.mean, dr.stddev);
  if (time_offset != Duration::zero()) {
    std::printf(
        "  dead reckoning at stamp %+.3f s: trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f "
        "+- %.3f deg\n",
        time_offset_s, dst.mean, dst.stddev, dst.rmse, dst.max, dsr.mean, dsr.stddev);
  }
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::printf(
      "  medians: EKF trans %.4f m rot %.3f deg; dead reckoning trans %.4f m rot %.3f deg\n",
      median(est_t), median(est_r), median(dr_t), median(dr_r));
  std::printf("  ratio dead reckoning / EKF: translation %.2f, rotation %.2f (target >= 5)\n",
              dt.mean / std::max(et.mean, 1e-12), dr.mean / std::max(er.mean, 1e-12));
  if (time_offset != Duration::zero()) {
    std::printf("  ratio dead reckoning at stamp %+.3f s / EKF: translation %.2f, rotation %.2f\n",
                time_offset_s, dst.mean / std::max(et.mean, 1e-12),
                dsr.mean / std::max(er.mean, 1e-12));
  }

  if (args.values.count("--png") && drawn && !drawn_records.empty()) {
    const std::string png = args.values.at("--png");
    std::vector<Vec2> points;
    std::vector<Vec2> path;
    Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
    for (size_t i : drawn_records) {
      const ScanRecord& r = records[i];
      const Pose2 sensor =
          Compose(r.estimate, Compose(Pose2{laser_x, 0.0, 0.0}, r.scan->sensor_pose));
      path.push_back(Vec2(r.estimate.x, r.estimate.y));
      for (size_t b = 0; b < r.scan->ranges.size(); ++b) {
        const float range = r.scan->ranges[b];
        if (!IsReturn(range) || range > 15.0f) continue;
        const double phi = r.scan->angle_min + b * static_cast<double>(r.scan->angle_increment);
        const Vec2 p = sensor.TransformPoint(Vec2(range * std::cos(phi), range * std::sin(phi)));
        points.push_back(p);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    std::string err;
    draw::ImageFormat format;
    if (!draw::ImageFormatOf(png, &format)) {
      std::fprintf(stderr, "atlas-localmap-eval: --png must end in .png or .svg\n");
      return 1;
    }
    const draw::ViewTransform view =
        draw::ViewTransform::Fit(lo - Vec2(1, 1), hi + Vec2(1, 1), 10, 40, 1580, 1150);
    auto canvas = draw::Canvas::Create(format, png, 1600, 1200, view, &err);
    if (!canvas) {
      std::fprintf(stderr, "atlas-localmap-eval: %s\n", err.c_str());
      return 1;
    }
    canvas->Points(points, draw::Color{0.55, 0.55, 0.55, 0.35}, 0.7);
    canvas->Polyline(path, draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 2.0, false});
    for (const MapLine& l : drawn->Lines()) {
      canvas->Line(l.endpoint_a, l.endpoint_b,
                   draw::Stroke{draw::Color{0.85, 0.1, 0.1, 1.0}, 3.0, false});
      canvas->CovarianceEllipse(
          0.5 * (l.endpoint_a + l.endpoint_b),
          Eigen::Matrix2d(Eigen::Vector2d(l.cov(0, 0), l.cov(0, 0)).asDiagonal()), 3.0,
          draw::Stroke{draw::Color{0.85, 0.1, 0.1, 0.6}, 1.0, false});
    }
    const UncertainPose rp = drawn->RobotPose();
    canvas->Pose(rp.mean, 0.25, draw::Color{0.1, 0.4, 0.9, 1.0});
    canvas->CovarianceEllipse(Vec2(rp.mean.x, rp.mean.y), rp.cov.topLeftCorner<2, 2>(), 3.0,
                              draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 1.5, false});
    char title[200];
    std::snprintf(title, sizeof(title),
                  "mit-csail stretch %d: %zu scans, %d lines (EKF, map-frame of the stretch)",
                  static_cast<int>(draw_stretch), drawn_records.size(), drawn->Complexity());
    canvas->TextPx(Vec2(12, 28), title, 20, draw::Color{}, true);
    canvas->ScaleBar();
    canvas->Legend(Vec2(12, 1185), {{"scan points (estimated poses)", {0.55, 0.55, 0.55, 1}, true},
                                    {"map lines (extent)", {0.85, 0.1, 0.1, 1}, false},
                                    {"robot path, 3-sigma pose", {0.1, 0.4, 0.9, 1}, false}});
    const std::string fin = canvas->Finish();
    if (!fin.empty()) {
      std::fprintf(stderr, "atlas-localmap-eval: %s\n", fin.c_str());
      return 1;
    }
    std::printf("wrote %s (stretch %d)\n", png.c_str(), static_cast<int>(draw_stretch));
  }
  return 0;
}

}  // namespace

cli::ToolMode RealMode() {
  const RealDefaults d;
  return {
      "real",
      "mit-csail: one local map per stretch, scored on the relations",
      {{"--log", "F", "the CARMEN log (default " + d.log + ")"},
       {"--relations", "F", "its relations (default " + d.relations + ")"},
       {"--stretch", "M",
        "metres of travel per local map (default " + cli::HelpNumber(d.stretch_m) + ")"},
       {"--capacity", "C", "map capacity (default " + std::to_string(d.capacity) + ")"},
       {"--png", "F", "draws stretch K's map over its scans, .png or .svg (default: none)"},
       {"--draw-stretch", "K",
        "the stretch --png draws (default " + cli::HelpNumber(d.draw_stretch) + ")"},
       {"--set", "name=v,...", "filter options overridden (a bad name lists them; default: none)"},
       {"--laser-x", "X",
        "the laser X metres ahead of the robot's centre (default " + cli::HelpNumber(d.laser_x) +
            ")"},
       {"--laser-time-offset", "S",
        "a scan was taken at its stamp + S seconds (default " + cli::HelpNumber(d.time_offset_s) +
            ")"},
       {"--scan-match", "0|1",
        "1: predict with scan matching, as atlasd; 0: odometry (default " +
            std::to_string(d.scan_match) + ")"}},
      RunRealMode};
}

}  // namespace atlas::localmap_eval
