#include "kestrel/exploration/wall_follow_field.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::exploration {

Status WallFollowField::configure(const BeamGeometry& geometry, const WallFollowParams& params) {
  configured_ = false;
  if (geometry.validate() != Status::kOk) return Status::kInvalidArgument;
  Params check;
  check.wall = params;
  if (check.validate() != Status::kOk) return Status::kInvalidArgument;

  geometry_ = geometry;
  directions_.build(geometry);
  target_mm_ = static_cast<int32_t>(std::lround(params.target_range_m * 1000.0f));
  safe_mm_ = static_cast<uint16_t>(std::lround(params.safe_range_m * 1000.0f));
  const long max_mm = std::min<long>(std::lround(params.max_range_m * 1000.0f), geometry.max_range_mm);
  max_mm_ = static_cast<uint16_t>(std::clamp<long>(max_mm, 0, 65535));
  gain_wf_ = params.gain_wf;
  gain_safe_ = params.gain_safe;
  normalisation_ = params.normalisation;
  // Sums are in mm * 2^14; the output is in m/s.
  const float unit = 1.0f / (1000.0f * static_cast<float>(Trig::kOne));
  beam_weight_ = normalisation_ == FieldNormalisation::kPerRadian ? unit * std::fabs(geometry.angle_step_rad) : unit;
  configured_ = true;
  return Status::kOk;
}

Status WallFollowField::body_velocity(const LaserScan& scan, FieldResult& out) const {
  out = FieldResult{};
  if (!configured_) return Status::kNotFound;
  if (!geometry_.matches(scan)) return Status::kInvalidArgument;

  // Nominal (K_wf) and safe (K_safe) sums kept apart: the gains are applied once per scan.
  int64_t nom_x = 0, nom_y = 0, safe_x = 0, safe_y = 0;
  uint32_t n = 0, n_safe = 0;
  uint16_t nearest_mm = 0xFFFFu;
  std::size_t nearest = 0xFFFFu;
  const uint16_t* r = scan.range_mm.data();
  const std::size_t count = geometry_.beam_count;
  const Trig* cos_i = directions_.cos.data();
  const Trig* sin_i = directions_.sin.data();
  for (std::size_t i = 0; i < count; ++i) {
    const uint16_t ri = r[i];
    if (ri < kMinValidRangeMm || ri > max_mm_) continue;  // range codes and far beams
    if (ri < nearest_mm) {
      nearest_mm = ri;
      nearest = i;
    }
    const int32_t d = static_cast<int32_t>(ri) - target_mm_;  // |d| < 2^16, |trig| <= 2^14
    const int32_t px = d * cos_i[i].raw();
    const int32_t py = d * sin_i[i].raw();
    if (ri < safe_mm_) {
      safe_x += px;
      safe_y += py;
      ++n_safe;
    } else {
      nom_x += px;
      nom_y += py;
    }
    ++n;
  }
  out.in_range = static_cast<uint16_t>(n);
  out.in_safe = static_cast<uint16_t>(n_safe);
  out.nearest_beam = static_cast<uint16_t>(nearest);
  out.nearest_mm = n > 0 ? nearest_mm : 0;
  if (n == 0) return Status::kOk;

  float w = beam_weight_;
  if (normalisation_ == FieldNormalisation::kPerInRangeBeam) w /= static_cast<float>(n);
  out.body_mps.x() = w * (gain_wf_ * static_cast<float>(nom_x) + gain_safe_ * static_cast<float>(safe_x));
  out.body_mps.y() = w * (gain_wf_ * static_cast<float>(nom_y) + gain_safe_ * static_cast<float>(safe_y));
  return Status::kOk;
}

Eigen::Vector2f WallFollowField::to_inertial(const Eigen::Vector2f& body, float heading_rad) {
  const float c = std::cos(heading_rad), s = std::sin(heading_rad);
  return {c * body.x() - s * body.y(), s * body.x() + c * body.y()};
}

}  // namespace kestrel::exploration
