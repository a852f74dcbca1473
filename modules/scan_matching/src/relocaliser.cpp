#include "kestrel/scan_matching/relocaliser.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

namespace {
int cells(float m, float res) { return static_cast<int>(std::lround(m / res)); }
}  // namespace

Status validate(const RelocaliserParams& p) {
  if (!(p.resolution_m >= 0.01f && p.resolution_m <= 0.2f) || !(p.sigma_m > 0.0f) ||
      !(3.0f * p.sigma_m / p.resolution_m < 64.0f) || !(p.angle_step_rad > 0.0f && p.angle_step_rad <= 0.1f) ||
      !(p.window_m > 0.0f) || !(p.window_rad >= 0.0f && p.window_rad <= 1.0f) || !(p.min_score >= 0.0f && p.min_score <= 1.0f) ||
      p.min_points < 3 || !(p.min_gain >= 0.0f) || !(p.exclusion_m > 0.0f) || !(p.ambiguity_m > p.exclusion_m) ||
      !(p.max_second_ratio > 0.0f && p.max_second_ratio <= 1.0f))
    return Status::kInvalidArgument;
  if (cells(p.window_m, p.resolution_m) > kMaxWindowCells || cells(p.ambiguity_m, p.resolution_m) > kMaxExhaustiveWindow ||
      cells(p.window_rad, p.angle_step_rad) > kMaxThetaSteps)
    return Status::kInvalidArgument;
  return Status::kOk;
}

Status Relocaliser::configure(const RelocaliserParams& p, const Params& matcher) {
  if (validate(p) != Status::kOk || !(matcher.max_range_m > 0.0f)) return Status::kInvalidArgument;
  Params m = matcher;
  m.resolution_m = p.resolution_m;
  m.sigma_m = p.sigma_m;
  m.kernel_sigmas = 3.0f;
  if (map_.configure(m) != Status::kOk) return Status::kInvalidArgument;
  params_ = p;
  matcher_ = m;
  extractor_.set_params(m);
  reference_count_ = 0;
  return Status::kOk;
}

Status Relocaliser::add_reference(const ScanPoints& pts, const Pose2& pose) {
  if (!pose.finite()) return Status::kInvalidArgument;
  if (pts.count < params_.min_points) return Status::kNoData;
  if (reference_count_ >= kMaxReferenceScans) return Status::kCapacityExceeded;
  extractor_.extract(pts, contours_);
  const float res = map_.resolution_m();
  if (reference_count_ == 0) {
    const float half = 0.5f * static_cast<float>(map_.dim()) * res;
    map_.begin(std::floor((pose.x - half) / res) * res, std::floor((pose.y - half) / res) * res);
    reference_pose_ = pose;
  }
  const float inv = static_cast<float>(kSub) / res;
  const float lim = static_cast<float>(map_.dim() * kSub - 1);
  const float c = std::cos(pose.theta), s = std::sin(pose.theta);
  const auto to_map = [&](uint16_t i, int16_t& mx, int16_t& my) {
    if (!std::isfinite(pts.x[i]) || !std::isfinite(pts.y[i])) return false;
    const float fx = (pose.x + c * pts.x[i] - s * pts.y[i] - map_.origin_x_m()) * inv;
    const float fy = (pose.y + s * pts.x[i] + c * pts.y[i] - map_.origin_y_m()) * inv;
    if (!(fx >= 0 && fx <= lim && fy >= 0 && fy <= lim)) return false;  // beyond the map: left out
    mx = static_cast<int16_t>(fx);
    my = static_cast<int16_t>(fy);
    return true;
  };
  // A scan has at most kMaxPoints segments and dots, the list holds kMaxReferenceScans of them:
  // draw cannot fail.
  MapSegment seg;
  for (uint16_t i = 0; i < contours_.segment_count; ++i) {
    if (to_map(contours_.seg_a[i], seg.ax, seg.ay) && to_map(contours_.seg_b[i], seg.bx, seg.by)) (void)map_.draw(seg);
  }
  for (uint16_t i = 0; i < contours_.point_count; ++i) {
    if (contours_.degree[i] != 0 || !to_map(i, seg.ax, seg.ay)) continue;
    seg.bx = seg.ax;
    seg.by = seg.ay;
    (void)map_.draw(seg);
  }
  map_.finish();  // over everything drawn so far: the pyramid is rebuilt, not added to
  ++reference_count_;
  return Status::kOk;
}

// The best score at the best rotation among translations between exclusion_m and ambiguity_m
// of the best, over the best's: how sure the search is of where along the scene it stands.
float Relocaliser::second_peak_ratio(const GridPose& best) {
  const int half = cells(params_.ambiguity_m, params_.resolution_m);
  const int excl = cells(params_.exclusion_m, params_.resolution_m);
  const uint16_t* img = search_.slice(best.k, best.tx, best.ty, half);
  const int w = 2 * half + 1;
  int32_t second = 0;
  for (int y = -half; y <= half; ++y) {
    for (int x = -half; x <= half; ++x) {
      if (x * x + y * y <= excl * excl || x * x + y * y > half * half) continue;
      second = std::max<int32_t>(second, img[static_cast<std::size_t>((y + half) * w + (x + half))]);
    }
  }
  return best.score > 0 ? static_cast<float>(second) / static_cast<float>(best.score) : 1.0f;
}

Relocalisation Relocaliser::locate(const ScanPoints& pts, const Pose2& guess) {
  Relocalisation r;
  r.pose = guess;
  if (reference_count_ == 0) return r;
  r.outcome = RelocaliseOutcome::kBadInput;
  const int half_cells = cells(params_.window_m, params_.resolution_m);
  const int half_steps = cells(params_.window_rad, params_.angle_step_rad);
  const int slice_half = cells(params_.ambiguity_m, params_.resolution_m);
  if (!guess.finite() || std::hypot(guess.x - reference_pose_.x, guess.y - reference_pose_.y) > 0.5f * map_.dim() * map_.resolution_m())
    return r;
  if (search_.setup(pts, guess, map_, half_cells, half_steps, params_.angle_step_rad, slice_half, matcher_.max_range_m) != Status::kOk)
    return r;
  const GridPose best = search_.branch_and_bound();
  const int judged = best.score >= 0 ? search_.scored_points(best.k) : 0;
  const float denom = static_cast<float>(std::max(1, judged)) * kCellMax;
  r.points = static_cast<uint16_t>(judged);
  r.score = static_cast<float>(std::max(0, best.score)) / denom;
  const int guess_judged = search_.scored_points(0);
  r.guess_score = static_cast<float>(search_.score(0, 0, 0)) / (static_cast<float>(std::max(1, guess_judged)) * kCellMax);
  if (best.score < 0 || judged < params_.min_points || r.score < params_.min_score) {
    r.outcome = RelocaliseOutcome::kNoFit;
    return r;
  }
  if (r.score < (1.0f + params_.min_gain) * r.guess_score) {
    r.outcome = RelocaliseOutcome::kNoGain;
    return r;
  }
  r.second_ratio = second_peak_ratio(best);
  if (r.second_ratio >= params_.max_second_ratio) {
    r.outcome = RelocaliseOutcome::kAmbiguous;
    return r;
  }
  r.pose = search_.pose_of(static_cast<float>(best.k), static_cast<float>(best.tx), static_cast<float>(best.ty));
  r.outcome = RelocaliseOutcome::kFixed;
  return r;
}

}  // namespace kestrel::scan_matching
