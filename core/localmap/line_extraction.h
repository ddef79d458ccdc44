#pragma once
// Line extraction from one laser scan: split-and-merge segmentation followed by a weighted
// least-squares line fit per segment, after Nguyen, Martinelli, Tomatis and Siegwart, "A
// comparison of line extraction algorithms using 2D laser rangefinder for indoor mobile
// robotics" (IROS 2005), and Pfister, Roumeliotis and Burdick, "Weighted line fitting
// algorithms for mobile robot map building and efficient data representation" (ICRA 2003).
//
// 1. Beams become points in the sensor frame; no-return beams and ranges outside
//    [min_range, max_range) are never points. Consecutive points farther apart than max_gap
//    start a new cluster.
// 2. Split: each cluster is split recursively at the point farthest from the chord between its
//    first and last point while that distance exceeds split_distance (iterative end-point fit).
// 3. Merge: adjacent segments of one cluster whose joint fit stays within split_distance merge.
//    A segment that meets another segment of its cluster (a corner) loses corner_points points
//    at that end: they fit both walls within their noise and bias whichever fit keeps them.
// 4. Fit: each segment of at least min_points points is fitted in range space: the range of
//    beam i is r_i = rho / cos(phi_i - alpha) + noise, with the exact bearing phi_i and
//    variance v_i = sigma_r(r_i)^2 + model_sigma^2 / cos^2(phi_i - alpha) (the model noise is
//    normal to the line). From the unweighted total-least-squares line, one Gauss-Newton step
//    on sum_i (r_i - rho / cos(phi_i - alpha))^2 / v_i; the (rho, alpha) covariance is the
//    inverse of its information sum_i J_i^T J_i / v_i. A point-space (total least squares)
//    fit would be biased, because its noise is along the beams (errors in variables).
//    End points whose beam spacing along the fitted line, rho dphi / cos^2(phi - alpha),
//    comes within 4 sigma of its noise (sqrt(2) sigma_r |sin(phi - alpha)|) of max_gap are
//    trimmed (there the gap test's cut depends on the range noise and would keep a biased
//    selection of points), as are end points farther than 3 sigma from the fit; the segment
//    is then refitted. The fit must then pass a chi-square test, sum_i (normal residual_i)^2 / (v_i
//    cos^2) < chi2_inv(fit_gate, n - 2) (the covariance above is only right for points of one
//    straight wall); a segment that fails is not a line. The floors min_rho_sigma^2,
//    min_alpha_sigma^2 are then added to the variances.
// 5. Endpoints are the first and last point projected on the line; lines shorter than
//    min_length are dropped. At most max_lines lines are returned (longest kept).
//
// Pure function of the scan and options; fixed work bound per scan (O(beams * log) splits).

#include <span>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/localmap/line_model.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

// Lines in the SENSOR frame, canonical (rho >= 0), in beam order. `options` must be valid.
std::vector<ObservedLine> ExtractLines(const LaserScan& scan, const LineExtractionOptions& options);

// Lines in the ROBOT frame: ExtractLines moved through scan.sensor_pose (exact).
std::vector<ObservedLine> ExtractRobotFrameLines(const LaserScan& scan,
                                                 const LineExtractionOptions& options);

// The range-space fit of step 4 on given points (sensor frame, the sensor at the origin), with
// range variance range_var_i per point and model_var normal to the line. Needs >= 2 points;
// returns false if degenerate (or a beam runs parallel to the line). Exposed for tests.
bool FitLine(const std::vector<Vec2>& points, const std::vector<double>& range_var,
             double model_var, ObservedLine& line);
bool FitLine(std::span<const Vec2> points, std::span<const double> range_var, double model_var,
             ObservedLine& line);

}  // namespace atlas
