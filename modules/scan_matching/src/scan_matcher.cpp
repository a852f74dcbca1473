#include "kestrel/scan_matching/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kestrel::scan_matching {
namespace {

float ceil_div(float a, float b) { return std::ceil(a / b - 1e-4f); }
constexpr int kSeedWindow = 8;  // cells and steps of the hypothesis searches

}  // namespace

ScanMatcher::ScanMatcher(const Params& p, LikelihoodMap& a, LikelihoodMap& b, bool synchronous)
    : params_(p), synchronous_(synchronous), local_(p, a, b) {
  (void)configure(p);
}

Status ScanMatcher::configure(const Params& p, const Pose2& initial) {
  if (!(p.angle_step_rad > 0) || !(p.max_range_m > p.min_range_m) || !initial.finite() ||
      !(p.restart_after_lost_s >= 0)) {
    return Status::kInvalidArgument;
  }
  // The search holds points as int16 cells (CorrelativeSearch::setup).
  if (!(p.resolution_m > 0) || !(p.max_range_m / p.resolution_m < 32000.0f)) return Status::kInvalidArgument;
  const Status s = local_.configure(p);
  if (!ok(s)) return s;
  params_ = p;
  initial_ = initial;
  started_ = false;
  accepted_ = 0;
  key_discs_.count = 0;
  return Status::kOk;
}

void ScanMatcher::update_beam_table(const LaserScan& scan) {
  if (scan.beam_count == table_beams_ && scan.first_angle_rad == table_first_rad_ &&
      scan.angle_step_rad == table_step_rad_) {
    return;
  }
  for (uint16_t i = 0; i < scan.beam_count; ++i) {
    const float a = scan.angle_of(i);
    beam_cos_[i] = std::cos(a);
    beam_sin_[i] = std::sin(a);
  }
  table_beams_ = scan.beam_count;
  table_first_rad_ = scan.first_angle_rad;
  table_step_rad_ = scan.angle_step_rad;
}

bool ScanMatcher::to_points(const LaserScan& scan) {
  update_beam_table(scan);
  ScanPoints& pts = key_.points;
  pts.count = 0;
  pts.angle_step_rad = std::fabs(scan.angle_step_rad);
  pts.sweep_dx_m = pts.sweep_dy_m = pts.sweep_dtheta_rad = 0;
  const float lo = params_.min_range_m * 1000.0f;
  float hi = params_.max_range_m * 1000.0f;
  if (scan.max_range_mm > 0) hi = std::min(hi, static_cast<float>(scan.max_range_mm));
  for (uint16_t i = 0; i < scan.beam_count; ++i) {
    const uint16_t r = scan.range_mm[i];
    if (!LaserScan::is_return(r)) continue;
    const float rf = static_cast<float>(r);
    if (rf < lo || rf >= hi) continue;  // at the maximum range: no return, not a surface
    pts.x[pts.count] = rf * 1e-3f * beam_cos_[i];
    pts.y[pts.count] = rf * 1e-3f * beam_sin_[i];
    pts.range_mm[pts.count] = r;
    pts.beam[pts.count] = i;
    ++pts.count;
  }
  return pts.count >= std::max<uint16_t>(params_.min_points, 2);
}

// The laser sweeps its beams one after another (the URG-04LX's 682 over 67 ms), and a vehicle
// that moves or turns meanwhile sees each beam from a different pose: turning at 0.75 rad/s,
// the sweep's last beam looks 0.05 rad further round than its first. Uncorrected, the match
// fits the middle of a bent scan, and key scans taken in a turn draw the bend into the local
// map, where it stays: on iarc-arena's waypoint tour with the URG-04LX the heading was 0.09 rad
// off after two turns and the flight ended against a door frame. Each point is moved to where
// the sensor was at the stamp (the first beam), the prior's velocity and yaw rate held over the
// sweep; second order in the turn angle (below a millimetre at 4 m over one sweep).
void ScanMatcher::deskew(const LaserScan& scan, const PosePrior& prior) {
  const float w = prior.yaw_rate_radps;
  if (scan.beam_interval.us <= 0 || !prior.pose.finite() || !std::isfinite(w) || !std::isfinite(prior.vx_mps) ||
      !std::isfinite(prior.vy_mps) || (w == 0.0f && prior.vx_mps == 0.0f && prior.vy_mps == 0.0f)) {
    return;  // nothing to correct with: the scan is taken as instantaneous
  }
  const float c = std::cos(prior.pose.theta), s = std::sin(prior.pose.theta);
  const float vx = c * prior.vx_mps + s * prior.vy_mps, vy = -s * prior.vx_mps + c * prior.vy_mps;  // sensor frame
  const float step_s = static_cast<float>(scan.beam_interval.seconds());
  ScanPoints& pts = key_.points;
  pts.sweep_dx_m = vx * step_s;
  pts.sweep_dy_m = vy * step_s;
  pts.sweep_dtheta_rad = w * step_s;
  for (uint16_t i = 0; i < pts.count; ++i) {
    const float t = step_s * static_cast<float>(pts.beam[i]);
    const float a = w * t, ca = 1.0f - 0.5f * a * a;
    const float x = pts.x[i], y = pts.y[i];
    pts.x[i] = ca * x - a * y + vx * t;
    pts.y[i] = a * x + ca * y + vy * t;
  }
}

float ScanMatcher::laser_reach_m(const LaserScan& scan) const {
  const float sensor = scan.max_range_mm > 0 ? static_cast<float>(scan.max_range_mm) * 1e-3f : params_.max_range_m;
  return std::min(params_.max_range_m, sensor);
}

void ScanMatcher::remember_key(const Pose2& pose, bool restart) {
  SeenDiscs& d = key_discs_;
  if (restart) d.count = 0;
  // The local map keeps the last `keyframes` key scans; so do the discs.
  const std::size_t k = std::clamp<std::size_t>(params_.keyframes, 1, kMaxKeyframes);
  d.count = std::min(d.count + 1, k);
  for (std::size_t i = d.count - 1; i > 0; --i) {
    d.x[i] = d.x[i - 1];
    d.y[i] = d.y[i - 1];
  }
  d.x[0] = pose.x;
  d.y[0] = pose.y;
}

float ScanMatcher::distance_to_nearest_key(const Pose2& p) const {
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < key_discs_.count; ++i) {
    best = std::min(best, std::hypot(p.x - key_discs_.x[i], p.y - key_discs_.y[i]));
  }
  return best;
}

ScanMatch ScanMatcher::process(const LaserScan& scan, const PosePrior* prior_in) {
  using namespace match_flag;
  ScanMatch out;
  PoseMeasurement2& m = out.measurement;
  m.stamp = scan.stamp;
  m.pose = last_pose_;
  m.covariance = Eigen::Matrix3f::Identity() * 1e6f;
  if (!scan.fan_well_formed()) {
    m.flags = kRejected | kBadGeometry;
    return out;
  }
  if (started_ && scan.stamp < last_stamp_) {
    m.flags = kRejected | kTimeBackwards;
    return out;
  }
  if (!to_points(scan)) {
    m.flags = kRejected | kTooFewPoints;
    out.points = key_.points.count;
    return out;
  }
  out.points = key_.points.count;
  if (prior_in != nullptr) deskew(scan, *prior_in);

  if (!started_) {
    // The first scan defines the map frame at the initial pose.
    key_.pose = initial_;
    key_.restart = false;
    (void)local_.submit(key_);
    remember_key(initial_, true);
    last_key_stamp_ = scan.stamp;
    last_key_at_corridor_match_ = false;
    if (synchronous_) (void)local_.rebuild();
    started_ = true;
    last_pose_ = prev_pose_ = initial_;
    last_stamp_ = prev_stamp_ = last_fit_stamp_ = scan.stamp;
    accepted_ = 1;
    m.pose = initial_;
    m.covariance = Eigen::Matrix3f::Identity() * 1e-6f;
    m.flags = kFirstScan | kKeyScan;
    out.score = 1;
    out.overlap = 1;
    return out;
  }

  const LikelihoodMap* map = local_.acquire();
  if (map == nullptr) {
    local_.release();
    m.flags = kRejected | kNoMap;
    return out;
  }

  // Constant-velocity prediction; the window covers what max acceleration can add since.
  const float dt = static_cast<float>((scan.stamp - last_stamp_).seconds());
  const float dt_prev = static_cast<float>((last_stamp_ - prev_stamp_).seconds());
  Pose2 pred = last_pose_;
  if (accepted_ >= 2 && (params_.velocity_per_scan || dt_prev > 1e-4f)) {
    const float f = params_.velocity_per_scan ? 1.0f : std::min(dt / dt_prev, 2.0f);
    pred.x += (last_pose_.x - prev_pose_.x) * f;
    pred.y += (last_pose_.y - prev_pose_.y) * f;
    pred.theta = wrap_angle(pred.theta + wrap_angle(last_pose_.theta - prev_pose_.theta) * f);
  }
  const Pose2 cv = pred;  // the constant-velocity prediction, before any prior replaces it
  // The window is the box around the prediction that max acceleration allows, grown to also
  // hold the vehicle stopping (the last pose): on logs sampled seconds apart the velocity
  // can change completely between scans, and on the vehicle the growth is v * dt, a few cm.
  const Pose2* prior = prior_in != nullptr && prior_in->pose.finite() ? &prior_in->pose : nullptr;
  float win_m0 = 0.5f * params_.max_accel_mps2 * dt * dt;
  float win_rad0 = 0.5f * params_.max_ang_accel_radps2 * dt * dt;
  if (prior != nullptr) {
    pred = *prior;
    // NaN and negative sigmas fail these tests and keep the acceleration window.
    if (prior_in->position_std_m >= 0) win_m0 = params_.prior_sigmas * prior_in->position_std_m;
    if (prior_in->heading_std_rad >= 0) win_rad0 = params_.prior_sigmas * prior_in->heading_std_rad;
  }
  win_m0 = std::clamp(win_m0, params_.min_window_m, params_.max_window_m);
  win_rad0 = std::clamp(win_rad0, params_.min_window_rad, params_.max_window_rad);
  // Without a prior, the stopped hypothesis (the last pose) is searched too; a prior already
  // says whether the vehicle stopped.
  const float gx = prior != nullptr ? 0.0f : 0.5f * (last_pose_.x - pred.x);
  const float gy = prior != nullptr ? 0.0f : 0.5f * (last_pose_.y - pred.y);
  const float gt = prior != nullptr ? 0.0f : 0.5f * wrap_angle(last_pose_.theta - pred.theta);
  pred.x += gx;
  pred.y += gy;
  pred.theta = wrap_angle(pred.theta + gt);
  // ...but never beyond the configured maximum: that bounds the worst-case time per scan.
  const float win_m = std::min(win_m0 + std::max(std::fabs(gx), std::fabs(gy)), params_.max_window_m);
  const float win_rad = std::min(win_rad0 + std::fabs(gt), params_.max_window_rad);
  const float res = map->resolution_m();
  // The search grid is the map's grid (and whole angle steps): a vehicle that holds still gets
  // the same answer scan after scan instead of one that wanders inside a cell.
  pred.x = map->origin_x_m() + std::round((pred.x - map->origin_x_m()) / res) * res;
  pred.y = map->origin_y_m() + std::round((pred.y - map->origin_y_m()) / res) * res;
  pred.theta = wrap_angle(std::round(pred.theta / params_.angle_step_rad) * params_.angle_step_rad);
  int half_cells = static_cast<int>(ceil_div(win_m, res));
  int half_steps = static_cast<int>(ceil_div(win_rad, params_.angle_step_rad));
  const int cap_cells = params_.multi_resolution ? kMaxWindowCells : kMaxExhaustiveWindow;
  if (half_cells > cap_cells || half_steps > kMaxThetaSteps) m.flags |= kWindowClamped;
  half_cells = std::clamp(half_cells, 1, cap_cells);
  half_steps = std::clamp(half_steps, 0, kMaxThetaSteps);
  // The covariance's slices reach cov_half_window cells beyond the optimum (and the rotation
  // curve's two): the search scores the points that stay inside the map over all of it.
  const int slice_half = std::clamp<int>(params_.cov_half_window, 2, kMaxExhaustiveWindow);
  const float reach = laser_reach_m(scan);
  key_discs_.radius_m = reach;
  const SeenDiscs* seen_ptr = params_.key_spacing_of_reach > 0 && key_discs_.count > 0 ? &key_discs_ : nullptr;

  // The motion prior's box around the constant-velocity prediction (Params::cv_box_m), in
  // cells and steps of the window's grid.
  const bool use_box = prior == nullptr && accepted_ >= 2 && params_.cv_box_m > 0 && params_.cv_box_rad >= 0;
  const int box_cells = use_box ? std::clamp(static_cast<int>(ceil_div(params_.cv_box_m, res)), 1, cap_cells) : 0;
  const int box_steps =
      use_box ? std::clamp(static_cast<int>(ceil_div(params_.cv_box_rad, params_.angle_step_rad)), 0, kMaxThetaSteps)
              : 0;
  const int cvx = static_cast<int>(std::lround((cv.x - pred.x) / res)),
            cvy = static_cast<int>(std::lround((cv.y - pred.y) / res));
  const int cvk = static_cast<int>(std::lround(wrap_angle(cv.theta - pred.theta) / params_.angle_step_rad));
  const auto search_around = [&](int hx, int hy, int hk, int cells, int steps) {
    const Pose2 c{pred.x + static_cast<float>(hx) * res, pred.y + static_cast<float>(hy) * res,
                  wrap_angle(pred.theta + static_cast<float>(hk) * params_.angle_step_rad)};
    if (!ok(search_.setup(key_.points, c, *map, cells, steps, params_.angle_step_rad, 0, params_.max_range_m,
                          seen_ptr))) {
      return GridPose{};  // score -1: no seed
    }
    const GridPose local = params_.multi_resolution ? search_.branch_and_bound() : search_.exhaustive();
    return GridPose{local.k + hk, local.tx + hx, local.ty + hy, local.score};
  };

  // Wide windows: a small search around each motion hypothesis (constant velocity, stopped)
  // first; its optimum seeds the pruning of the full search, which stays exact.
  std::array<GridPose, 3> seeds{};
  int seed_count = 0;
  if (params_.multi_resolution && half_cells > kSeedWindow && (gx != 0 || gy != 0 || gt != 0)) {
    for (const float sign : {-1.0f, 1.0f}) {
      const int hx = static_cast<int>(std::lround(sign * gx / res)),
                hy = static_cast<int>(std::lround(sign * gy / res));
      const int hk = static_cast<int>(std::lround(sign * gt / params_.angle_step_rad));
      if (use_box && hx == cvx && hy == cvy && hk == cvk) continue;  // the box search below covers it
      seeds[static_cast<std::size_t>(seed_count++)] =
          search_around(hx, hy, hk, kSeedWindow, std::min(half_steps, kSeedWindow));
    }
  }
  GridPose in_box;
  if (use_box) {
    in_box = search_around(cvx, cvy, cvk, box_cells, std::min(half_steps, box_steps));
    if (params_.multi_resolution) seeds[static_cast<std::size_t>(seed_count++)] = in_box;
  }
  if (!ok(search_.setup(key_.points, pred, *map, half_cells, half_steps, params_.angle_step_rad, slice_half,
                        params_.max_range_m, seen_ptr))) {
    // Only a prediction thousands of kilometres from the map gets here (configure() has
    // checked the rest): nothing to match against.
    local_.release();
    m.flags |= kRejected | kBadGeometry;
    return out;
  }
  GridPose best = params_.multi_resolution ? search_.branch_and_bound(seeds.data(), seed_count) : search_.exhaustive();
  // The prior: the box's optimum stands unless the window's is clearly better. Its score is
  // taken again on the window's grid, so the pose and score agree with the covariance below.
  if (use_box && in_box.score > 0 && std::abs(in_box.k) <= half_steps && std::abs(in_box.tx) <= half_cells &&
      std::abs(in_box.ty) <= half_cells) {
    const int32_t s = search_.score(in_box.k, in_box.tx, in_box.ty);
    if (static_cast<float>(s) >= (1.0f - params_.cv_tie_fraction) * static_cast<float>(best.score)) {
      best = {in_box.k, in_box.tx, in_box.ty, s};
    }
  }
  out.grid = best;
  // The mean cell under the points the map can judge; a scan that reaches past the map is
  // not worse for it.
  // A few points on a pillar can fit perfectly: with fewer scored points than a scan needs
  // (min_points), the match is lost whatever its mean.
  const int scored = search_.scored_points(best.k);
  const float denom = static_cast<float>(std::max(1, scored)) * kCellMax;
  out.score = static_cast<float>(std::max(0, best.score)) / denom;

  if (out.score < params_.min_score || scored < std::max<int>(params_.min_points, 2)) {
    local_.release();
    m.pose = pred;
    m.flags |= kLost;
    if (params_.restart_after_lost_s > 0 &&
        (scan.stamp - last_fit_stamp_).seconds() >= static_cast<double>(params_.restart_after_lost_s)) {
      key_.pose = pred;
      key_.restart = true;
      if (local_.submit(key_)) {
        m.flags |= kKeyScan | kMapRestarted;
        remember_key(pred, true);
        last_key_stamp_ = scan.stamp;
        last_key_at_corridor_match_ = false;
        last_fit_stamp_ = scan.stamp;  // the rebuilt map gets as long again to fit
        if (synchronous_) (void)local_.rebuild();
      }
      key_.restart = false;
    }
    prev_pose_ = last_pose_;
    prev_stamp_ = last_stamp_;
    last_pose_ = pred;
    last_stamp_ = scan.stamp;
    accepted_ = 1;  // no velocity until two matched scans again
    return out;
  }

  // Covariance (5.1.3): the best score per rotation near the optimum, and the translation
  // slice at the best rotation. Near the optimum a small rotation moves the best translation
  // by a cell or two, so each rotation's best is taken over a +-2 cell neighbourhood by image
  // addition (cheap, and exact whenever the per-rotation optimum stays in it).
  const auto best_near = [&](int k) {
    if (k == best.k) return best.score;
    const uint16_t* sl = search_.slice(k, best.tx, best.ty, 2);
    int32_t top = 0;
    for (int i = 0; i < 25; ++i) top = std::max<int32_t>(top, sl[i]);
    return top;
  };
  // The curve's width is measured at half height above its floor, the lower of its two ends;
  // so it is scored only at the ends and outward from the peak until it falls below half
  // height (each rotation scored costs a transform of the scan).
  const int r = std::min<int>(params_.cov_theta_steps, 64);
  const int k0 = std::max(-half_steps, best.k - r), k1 = std::min(half_steps, best.k + r);
  const int32_t end0 = best_near(k0), end1 = best_near(k1);
  // Never above the peak (the motion prior's pose, or a neighbourhood reaching past the
  // window, can leave an end higher): the estimator uses the same clamp.
  const int32_t curve_floor =
      std::min(best.score, k0 == best.k ? end1 : (k1 == best.k ? end0 : std::min(end0, end1)));
  const double half_height = curve_floor + 0.5 * (best.score - curve_floor);
  int left = best.k, right = best.k;
  curve_[static_cast<std::size_t>(best.k - k0)] = best.score;
  while (left > k0) {
    const int32_t v = left - 1 == k0 ? end0 : best_near(left - 1);
    curve_[static_cast<std::size_t>(--left - k0)] = v;
    if (v < half_height) break;
  }
  while (right < k1) {
    const int32_t v = right + 1 == k1 ? end1 : best_near(right + 1);
    curve_[static_cast<std::size_t>(++right - k0)] = v;
    if (v < half_height) break;
  }
  const int ch = std::min<int>(params_.cov_half_window, kMaxExhaustiveWindow);
  const uint16_t* slice = search_.slice(best.k, best.tx, best.ty, ch);
  const CovarianceEstimate ce = cov_.estimate(slice, ch, curve_.data() + (left - k0), right - left + 1, best.k - left,
                                              curve_floor, params_.degenerate_ratio);

  // Overlap: how many points land where the map expects a surface.
  int fit = 0, inside = 0;
  search_.overlap(best.k, best.tx, best.ty, kCellMax / 2, inside, fit);
  const float bx = pred.x + static_cast<float>(best.tx) * res, by = pred.y + static_cast<float>(best.ty) * res;
  // The window follows the vehicle: far from the newest key scan, a new one re-centres it.
  const float span = static_cast<float>(map->dim()) * res;
  const float off_x = bx - (map->origin_x_m() + 0.5f * span), off_y = by - (map->origin_y_m() + 0.5f * span);
  const bool off_centre = std::fabs(off_x) > 0.25f * span || std::fabs(off_y) > 0.25f * span;
  const bool far_from_keys = params_.key_spacing_of_reach > 0 &&
                             distance_to_nearest_key(Pose2{bx, by, 0}) > params_.key_spacing_of_reach * reach;
  local_.release();
  out.overlap = inside > 0 ? static_cast<float>(fit) / static_cast<float>(inside) : 0.0f;

  const Pose2 pose =
      params_.subcell_refine
          ? search_.pose_of(static_cast<float>(best.k) + ce.dk, static_cast<float>(best.tx) + ce.dx,
                            static_cast<float>(best.ty) + ce.dy)
          : search_.pose_of(static_cast<float>(best.k), static_cast<float>(best.tx), static_cast<float>(best.ty));
  m.pose = pose;
  m.covariance.setZero();
  m.covariance.topLeftCorner<2, 2>() = ce.translation_cells * (res * res);
  m.covariance(2, 2) = ce.rotation_steps2 * params_.angle_step_rad * params_.angle_step_rad;
  if (ce.degenerate) m.flags |= kDegenerate;
  out.major_axis_rad = ce.major_axis_rad;
  out.axis_ratio = ce.axis_ratio;

  last_fit_stamp_ = scan.stamp;
  // A corridor match asks for a key scan only while the newest key scan was taken at a match
  // that was not a corridor's (e.g. entering a corridor from a room): one taken at a corridor
  // match already holds what the corridor shows, and every further one would take in the
  // estimate's error along it again. (Any corridor's: turning from one corridor straight into
  // another, or through a room the map already holds, the rule stays off.) The
  // time since it is only worked out for a corridor match (soft float on the Verdex).
  const bool corridor_match = ce.degenerate && ce.truncated;
  const bool map_says_too_little =
      corridor_match && params_.degenerate_key_interval_s > 0 && !last_key_at_corridor_match_ &&
      (scan.stamp - last_key_stamp_).seconds() >= static_cast<double>(params_.degenerate_key_interval_s);
  if (out.overlap < params_.min_overlap || off_centre || far_from_keys || map_says_too_little) {
    key_.pose = pose;
    key_.restart = false;
    if (local_.submit(key_)) {
      m.flags |= kKeyScan;
      remember_key(pose, false);
      last_key_stamp_ = scan.stamp;
      last_key_at_corridor_match_ = corridor_match;
    }
    if (synchronous_) (void)local_.rebuild();
  }
  prev_pose_ = last_pose_;
  prev_stamp_ = last_stamp_;
  last_pose_ = pose;
  last_stamp_ = scan.stamp;
  ++accepted_;
  return out;
}

}  // namespace kestrel::scan_matching
