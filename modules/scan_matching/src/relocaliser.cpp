#include "kestrel/scan_matching/relocaliser.hpp"

#include "kestrel/scan_matching/contour_drawing.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

namespace {
int cells(float m, float res) { return static_cast<int>(std::lround(m / res)); }

// Walks the ray from `pose` at `angle` (world frame) cell by cell for reach_m, calling
// visit(cell_x, cell_y) for each cell after the first until it returns true (then true).
// About 100 steps for 4 m, in Q16 cells: the Verdex has no FPU, and in float the walk cost a
// third of a search there.
template <typename Visit>
bool walk_cells(const LikelihoodMap& map, const Pose2& pose, float angle, float reach_m, Visit visit) {
  constexpr float kOne = 65536.0f;
  const float inv = 1.0f / map.resolution_m();
  // int32 range: locate() takes a guess only within half the map of the reference (the map's
  // centre), and the pose walked from is that guess moved within the search window (or a
  // reference pose, within the map), plus under a metre of the sweep's motion
  // (plausible_sweep), so the start lies within a map's width of the map (at most 2047
  // cells); the walk adds at most two widths more. Three widths in Q16 cells are below 2^29.
  const auto steps = static_cast<int32_t>(std::min(reach_m * inv, 2.0f * static_cast<float>(map.dim())));
  auto x = static_cast<int32_t>(std::lround((pose.x - map.origin_x_m()) * inv * kOne));
  auto y = static_cast<int32_t>(std::lround((pose.y - map.origin_y_m()) * inv * kOne));
  const auto dx = static_cast<int32_t>(std::lround(std::cos(angle) * kOne));
  const auto dy = static_cast<int32_t>(std::lround(std::sin(angle) * kOne));
  for (int32_t k = 1; k <= steps; ++k) {
    x += dx;
    y += dy;
    if (visit(x >> 16, y >> 16)) return true;  // arithmetic shift: floor
  }
  return false;
}
}  // namespace

Status validate(const RelocaliserParams& p) {
  if (!(p.resolution_m >= 0.01f && p.resolution_m <= 0.2f) || !(p.sigma_m > 0.0f) ||
      !(3.0f * p.sigma_m / p.resolution_m < 64.0f) || !(p.angle_step_rad > 0.0f && p.angle_step_rad <= 0.1f) ||
      !(p.window_m > 0.0f) || !(p.window_rad >= 0.0f && p.window_rad <= 1.0f) ||
      !(p.min_score >= 0.0f && p.min_score <= 1.0f) || p.min_points < 3 || !(p.min_gain >= 0.0f) ||
      !(p.exclusion_m > 0.0f) || !(p.exclusion_m < p.window_m) ||
      !(p.max_second_ratio > 0.0f && p.max_second_ratio <= 1.0f) ||
      !(p.max_see_through >= 0.0f && p.max_see_through <= 1.0f) ||
      !(p.see_through_margin_m >= 0.0f && p.see_through_margin_m <= 5.0f) ||
      !(p.wall_level > 0.0f && p.wall_level <= 1.0f) ||
      !(p.max_returns_in_free >= 0.0f && p.max_returns_in_free <= 1.0f))
    return Status::kInvalidArgument;
  if (cells(p.window_m, p.resolution_m) > kMaxWindowCells ||
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
  reference_count_ = 0;  // the next reference is a first one: it clears what the others saw free
  return Status::kOk;
}

bool Relocaliser::within_map(const Pose2& pose) const {
  return std::hypot(pose.x - reference_pose_.x, pose.y - reference_pose_.y) <= 0.5f * map_.dim() * map_.resolution_m();
}

Status Relocaliser::add_reference(const ScanPoints& pts, const Pose2& pose, const LaserScan* scan) {
  if (!pose.finite() || (reference_count_ > 0 && !within_map(pose))) return Status::kInvalidArgument;
  for (uint16_t i = 0; i < pts.count; ++i)
    if (!std::isfinite(pts.x[i]) || !std::isfinite(pts.y[i])) return Status::kInvalidArgument;
  if (pts.count < params_.min_points) return Status::kNoData;
  if (reference_count_ >= kMaxReferenceScans) return Status::kCapacityExceeded;
  extractor_.extract(pts, contours_);
  if (reference_count_ == 0) {
    map_.begin_centred(pose.x, pose.y);
    reference_pose_ = pose;
    seen_free_.reset();
  }
  // A scan has at most kMaxPoints segments and dots, the list holds kMaxReferenceScans of them:
  // drawing cannot run out of room.
  (void)draw_contours(map_, pose, pts, contours_);
  map_.finish();  // over everything drawn so far: the pyramid is rebuilt, not added to
  mark_seen_free(pts, scan, pose);
  ++reference_count_;
  return Status::kOk;
}

// The best score at the best rotation over the window's translations farther than
// exclusion_m from the best, over the best's: how sure the search is of where in the scene it
// stands.
float Relocaliser::second_peak_ratio(const GridPose& best) {
  const GridPose second =
      search_.best_outside(best.k, best.tx, best.ty, cells(params_.exclusion_m, params_.resolution_m));
  return best.score > 0 ? static_cast<float>(std::max(0, second.score)) / static_cast<float>(best.score) : 1.0f;
}

// Whether the ray from `ray` (world frame, along its heading) meets a cell the reference drew
// as wall within reach_m.
bool Relocaliser::passes_a_wall(const Pose2& ray, float reach_m) const {
  const auto wall = static_cast<uint8_t>(std::ceil(params_.wall_level * static_cast<float>(kCellMax)));
  return walk_cells(map_, ray, ray.theta, reach_m, [&](int x, int y) { return map_.at(x, y) >= wall; });
}

namespace {
// The sweep's motion the points were deskewed with, when it is one a vehicle can make over a
// sweep (under a metre and a radian): beyond it, or not finite, the scan is walked as taken at
// once rather than from origins the integer walk cannot hold.
bool plausible_sweep(const ScanPoints& pts, uint16_t beams) {
  const float n = static_cast<float>(beams);
  return std::isfinite(pts.sweep_dx_m) && std::isfinite(pts.sweep_dy_m) && std::isfinite(pts.sweep_dtheta_rad) &&
         std::hypot(pts.sweep_dx_m, pts.sweep_dy_m) * n < 1.0f && std::fabs(pts.sweep_dtheta_rad) * n < 1.0f;
}
}  // namespace

template <typename Beam>
void Relocaliser::for_each_beam(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose, Beam beam) const {
  const float margin = params_.see_through_margin_m;
  if (scan != nullptr && !scan->fan_well_formed()) scan = nullptr;
  uint16_t beams = scan != nullptr ? scan->beam_count : 0;  // the sweep's length, in beams
  for (uint16_t i = 0; i < pts.count; ++i) beams = std::max<uint16_t>(beams, pts.beam[i] + 1);
  const bool sweep = plausible_sweep(pts, beams);
  const float c = std::cos(pose.theta), s = std::sin(pose.theta);
  const float step_x = sweep ? c * pts.sweep_dx_m - s * pts.sweep_dy_m : 0.0f;  // world frame, per beam
  const float step_y = sweep ? s * pts.sweep_dx_m + c * pts.sweep_dy_m : 0.0f;
  const float step_theta = sweep ? pts.sweep_dtheta_rad : 0.0f;
  // Beam b as the deskew saw it: from where the sensor was when b was taken, looking b steps of
  // the sweep's turn further round (in the take-off turn, 0.5 rad/s, the URG-04LX's last beam
  // is 0.03 rad round from the stamp's, 12 cm sideways at 4 m: the kernel's 3 sigma, the only
  // guard of a walk that grazes a wall).
  const auto walk = [&](uint16_t b, float sensor_angle, float reach) {
    if (!(reach > map_.resolution_m())) return;
    const auto k = static_cast<float>(b);
    beam(Pose2{pose.x + k * step_x, pose.y + k * step_y, pose.theta + sensor_angle + k * step_theta}, reach);
  };
  if (scan != nullptr) {
    const uint16_t n = std::min<uint16_t>(scan->beam_count, static_cast<uint16_t>(kMaxBeams));
    const float reach = 1e-3f * static_cast<float>(scan->max_range_mm) - margin;
    for (uint16_t i = 0; i < n; ++i) {
      const uint16_t r = scan->range_mm[i];
      if (LaserScan::is_return(r) && r < scan->max_range_mm) {
        walk(i, scan->angle_of(i), 1e-3f * static_cast<float>(r) - margin);
      } else if (r == range_code::kNoReturn) {
        walk(i, scan->angle_of(i), reach);
      }
    }
  } else {
    // The deskewed point less its beam's origin is the beam as taken, turned by the sweep.
    for (uint16_t i = 0; i < pts.count; ++i) {
      const float k = sweep ? static_cast<float>(pts.beam[i]) : 0.0f;
      const float x = pts.x[i] - k * pts.sweep_dx_m, y = pts.y[i] - k * pts.sweep_dy_m;
      walk(pts.beam[i], std::atan2(y, x) - k * step_theta, std::hypot(x, y) - margin);
    }
  }
}

// Of the beams walked (returns longer than the margin and, with the raw scan, beams that found
// nothing), the share that pass a reference wall.
float Relocaliser::see_through_fraction(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose) const {
  int walked = 0, through = 0;
  for_each_beam(pts, scan, pose, [&](const Pose2& ray, float reach) {
    ++walked;
    if (passes_a_wall(ray, reach)) ++through;
  });
  return walked > 0 ? static_cast<float>(through) / static_cast<float>(walked) : 0.0f;
}

bool Relocaliser::on_map(int x, int y) const {
  return static_cast<unsigned>(x) < static_cast<unsigned>(map_.dim()) &&
         static_cast<unsigned>(y) < static_cast<unsigned>(map_.dim());
}

std::size_t Relocaliser::cell_index(int x, int y) const {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(map_.dim()) + static_cast<std::size_t>(x);
}

bool Relocaliser::cell_of(float x_m, float y_m, int& x, int& y) const {
  const float inv = 1.0f / map_.resolution_m();
  const float fx = std::floor((x_m - map_.origin_x_m()) * inv), fy = std::floor((y_m - map_.origin_y_m()) * inv);
  const auto dim = static_cast<float>(map_.dim());
  if (!(fx >= 0.0f && fx < dim && fy >= 0.0f && fy < dim)) return false;  // NaN too
  x = static_cast<int>(fx);
  y = static_cast<int>(fy);
  return true;
}

void Relocaliser::mark_seen_free(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose) {
  for_each_beam(pts, scan, pose, [&](const Pose2& ray, float reach) {
    walk_cells(map_, ray, ray.theta, reach, [&](int x, int y) {
      if (on_map(x, y)) seen_free_[cell_index(x, y)] = true;
      return false;
    });
  });
}

bool Relocaliser::seen_free(float x_m, float y_m) const {
  int x = 0, y = 0;
  return reference_count_ > 0 && cell_of(x_m, y_m, x, y) && seen_free_[cell_index(x, y)];
}

// Of the points the search judged the best pose on, the share in cells a reference beam crossed
// with no reference wall within the kernel's reach (3 sigma): a beam grazing a wall marks cells
// beside it, where the wall's own returns land. The search's own integer cells: no floating
// point per point (the Verdex has no FPU).
float Relocaliser::returns_in_free_fraction(const GridPose& best) {
  const int judged = search_.scored_points(best.k);
  if (judged == 0) return 0.0f;
  int in_free = 0;
  search_.for_each_cell(best.k, best.tx, best.ty, [&](int x, int y) {
    in_free += map_.at(x, y) == 0 && seen_free_[cell_index(x, y)];
  });
  return static_cast<float>(in_free) / static_cast<float>(judged);
}

Relocalisation Relocaliser::locate(const ScanPoints& pts, const Pose2& guess, const LaserScan* scan) {
  Relocalisation r;
  r.pose = guess;
  if (reference_count_ == 0) return r;
  r.outcome = RelocaliseOutcome::kBadInput;
  const int half_cells = cells(params_.window_m, params_.resolution_m);
  const int half_steps = cells(params_.window_rad, params_.angle_step_rad);
  if (!guess.finite() || !within_map(guess)) return r;
  if (search_.setup(pts, guess, map_, half_cells, half_steps, params_.angle_step_rad, 0, matcher_.max_range_m) !=
      Status::kOk)
    return r;
  const GridPose best = search_.branch_and_bound();
  const int judged = best.score >= 0 ? search_.scored_points(best.k) : 0;
  const float denom = static_cast<float>(std::max(1, judged)) * kCellMax;
  r.points = static_cast<uint16_t>(judged);
  r.score = static_cast<float>(std::max(0, best.score)) / denom;
  const int guess_judged = search_.scored_points(0);
  r.guess_score =
      static_cast<float>(search_.score(0, 0, 0)) / (static_cast<float>(std::max(1, guess_judged)) * kCellMax);
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
  const Pose2 found =
      search_.pose_of(static_cast<float>(best.k), static_cast<float>(best.tx), static_cast<float>(best.ty));
  r.see_through = see_through_fraction(pts, scan, found);
  if (r.see_through > params_.max_see_through) {
    r.outcome = RelocaliseOutcome::kSeesThrough;
    return r;
  }
  r.returns_in_free = returns_in_free_fraction(best);
  if (r.returns_in_free > params_.max_returns_in_free) {
    r.outcome = RelocaliseOutcome::kReturnsInFree;
    return r;
  }
  r.pose = found;
  r.outcome = RelocaliseOutcome::kFixed;
  return r;
}

}  // namespace kestrel::scan_matching
