#include "kestrel/slam/compact_slam.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::slam {

Status CompactSlam::configure(const SlamParams& p) {
  if (validate(p) != Status::kOk) return Status::kInvalidArgument;
  params_ = p;
  counters_ = {};
  started_ = false;
  prng_.reseed(1);
  return Status::kOk;
}

bool CompactSlam::due_to_draw(const Pose2& pose) const {
  return std::hypot(pose.x - last_drawn_.x, pose.y - last_drawn_.y) >= params_.draw_every_m ||
         std::fabs(wrap_angle(pose.theta - last_drawn_.theta)) >= params_.draw_every_rad;
}

void CompactSlam::draw(const Pose2& pose) {
  last_drawn_ = pose;
  ++counters_.drawn;
  const ScanPlacement at(map_, pose);
  const float to_sub = kSub / map_.cell_m();
  const auto hole_half = static_cast<int32_t>(0.5f * params_.hole_width_m * to_sub);
  const auto clear = static_cast<int32_t>(params_.clear_reach_m * to_sub);
  const auto weight = static_cast<uint8_t>(params_.weight);
  for (uint16_t i = 0; i < scan_.count; ++i) {
    map_.draw_return(at.sensor(), at.place(scan_.point[i]), hole_half, clear, weight);
  }
}

bool CompactSlam::within_limits(const Pose2& prior, const Pose2& pose) const {
  return std::hypot(pose.x - prior.x, pose.y - prior.y) <= params_.max_correction_m &&
         std::fabs(wrap_angle(pose.theta - prior.theta)) <= params_.max_correction_rad;
}

SlamResult CompactSlam::process(const scan_matching::ScanPoints& points, const Pose2& prior) {
  using namespace slam_flag;
  SlamResult r;
  r.pose = prior;
  r.fit = prior;
  if (!prior.finite()) {
    r.flags = kNotFinite;
    return r;
  }
  thin_to_map_scan(points, started_ ? map_.cell_m() : params_.cell_m, static_cast<uint16_t>(params_.max_points),
                   scan_);
  r.points = scan_.count;
  if (scan_.count < static_cast<uint16_t>(params_.min_points)) {
    ++counters_.too_few_points;
    r.flags = kTooFewPoints;
    return r;
  }
  ++counters_.scans;
  if (!started_) {
    if (map_.reset(params_.cell_m, prior.x, prior.y) != Status::kOk) {
      r.flags = kNotFinite;
      return r;
    }
    started_ = true;
    draw(prior);
    r.flags = kStarted | kDrawn;
    return r;
  }
  if (counters_.scans <= static_cast<uint32_t>(params_.warmup_scans)) {
    draw(prior);
    r.flags = kWarmingUp | kDrawn;
    return r;
  }
  FitResult fit = monte_carlo_search(map_, scan_, prior, {params_.sigma_xy_m, params_.sigma_theta_rad},
                                           {params_.anchor_per_m2, params_.anchor_per_rad2},
                                           static_cast<uint32_t>(params_.iterations), prng_);
  // Only the part of the move the map supports; the gain is judged on what is left of it.
  const FitCurvature curvature = fit_curvature(map_, scan_, fit.pose, map_.cell_m());
  fit.pose = supported_move(curvature, prior, fit.pose, params_.min_curvature);
  fit.level = mean_level(map_, scan_, fit.pose);
  r.flags = kMatched;
  r.fit = fit.pose;
  r.level = static_cast<float>(fit.level) / kSub;
  r.prior_level = static_cast<float>(fit.prior_level) / kSub;
  if (r.level > params_.max_fit_level) {
    r.flags |= kNoFit;
    ++counters_.no_fit;
  } else if (r.prior_level - r.level < params_.min_gain_level) {
    r.flags |= kNoGain;
    ++counters_.no_gain;
  } else if (!within_limits(prior, fit.pose)) {
    r.flags |= kTooFar;
    ++counters_.too_far;
  } else {
    r.flags |= kCorrected;
    r.pose = fit.pose;
    ++counters_.corrections;
  }
  // Drawn where it fits best (the anchor and supported_move keep that at the filter's pose
  // where the map cannot tell), unless the search jumped beyond the correction's limits.
  const Pose2 at = (r.flags & kTooFar) != 0 ? prior : fit.pose;
  if (due_to_draw(at)) {
    // The curvature of the mean over every return, unknown ones flat at kUnknown, scaled to
    // the returns the map knows: a scan half on new ground is pinned by the half it knows. Both
    // are taken near where the scan would be drawn: the curvature where the search ended (it
    // is measured there for supported_move), the share at the supported fit. The share counts
    // at least a tenth, so that a scan almost wholly on new ground is not judged pinned on
    // the curvature of a handful of returns.
    if (params_.draw_min_curvature > 0 &&
        curvature.least() < params_.draw_min_curvature * std::max(0.1f, known_share(map_, scan_, fit.pose))) {
      r.flags |= kUnpinned;
      ++counters_.unpinned;
    } else {
      draw(at);
      r.flags |= kDrawn;
    }
  }
  return r;
}

}  // namespace kestrel::slam
