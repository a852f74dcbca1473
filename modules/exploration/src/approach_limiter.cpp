#include "kestrel/exploration/approach_limiter.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::exploration {
namespace {
constexpr int kQ = BeamDirections::kFracBits;
constexpr int64_t kRound = int64_t{1} << (kQ - 1);
// Below this (mm/s) a broken bound is rounding, not motion.
constexpr int32_t kToleranceMmps = 2;
// The blind arc behind the laser is bounded at these directions (5 degrees apart).
constexpr double kBlindSpacingRad = 5.0 * M_PI / 180.0;
// Commands are clamped to this before the integer loop (far beyond any flight speed).
constexpr float kMaxCommandMmps = 20000.0f;
}  // namespace

Status ApproachLimiter::configure(const ApproachParams& params, const BeamGeometry& geometry) {
  enabled_ = false;
  if (params.validate() != Status::kOk || geometry.validate() != Status::kOk) return Status::kInvalidArgument;
  stop_mm_ = static_cast<int32_t>(std::lround(params.stop_distance_m * 1000.0f));
  gain_q8_ = std::max<int32_t>(1, static_cast<int32_t>(std::lround(params.gain * 256.0f)));
  max_mm_ = geometry.max_range_mm;
  blind_bound_mmps_ = static_cast<int32_t>(std::lround(params.blind_speed_mps * 1000.0f));
  // The arc the laser does not see, from its last beam round to its first, sampled every
  // kBlindSpacingRad strictly inside (the edge beams themselves are seen).
  const double step = std::fabs(static_cast<double>(geometry.angle_step_rad));
  const double fov = step * (geometry.beam_count - 1);
  const double ccw_end = geometry.angle_step_rad > 0 ? geometry.first_angle_rad + fov : geometry.first_angle_rad;
  const double blind = 2.0 * M_PI - fov;
  const int samples =
      std::clamp(static_cast<int>(std::floor(blind / kBlindSpacingRad)), 0, static_cast<int>(kMaxBlind));
  blind_count_ = static_cast<uint8_t>(samples);
  for (int k = 0; k < samples; ++k) {
    const double a = ccw_end + blind * (k + 1) / (samples + 1);
    blind_cos_[k] = BeamDirections::Trig::from_double(std::cos(a));
    blind_sin_[k] = BeamDirections::Trig::from_double(std::sin(a));
  }
  enabled_ = params.enabled;
  return Status::kOk;
}

ApproachResult ApproachLimiter::limit(const LaserScan& scan, const BeamDirections& directions,
                                      Eigen::Vector2f& v, std::span<const VirtualReturn> virtual_returns) const {
  ApproachResult out;
  if (!enabled_) return out;
  std::array<Virtual, kMaxVirtual> extra_store{};
  std::size_t extras = 0;
  for (const VirtualReturn& vr : virtual_returns) {
    if (extras == kMaxVirtual) break;
    if (!std::isfinite(vr.dir_x) || !std::isfinite(vr.dir_y) || !std::isfinite(vr.range_m)) continue;
    const float range_mm = std::clamp(vr.range_m * 1000.0f, 0.0f, 60000.0f);
    extra_store[extras++] = {BeamDirections::Trig::from_double(vr.dir_x).raw(),
                             BeamDirections::Trig::from_double(vr.dir_y).raw(),
                             (int64_t{gain_q8_} * (std::lround(range_mm) - stop_mm_)) >> 8};
  }
  const std::span<const Virtual> extra(extra_store.data(), extras);
  if (!v.allFinite()) v.setZero();
  const Eigen::Vector2f in = v;
  // 64-bit: a push-out inside stop_distance adds to the command, so no small bound holds.
  int64_t vx = std::lround(std::clamp(v.x() * 1000.0f, -kMaxCommandMmps, kMaxCommandMmps));
  int64_t vy = std::lround(std::clamp(v.y() * 1000.0f, -kMaxCommandMmps, kMaxCommandMmps));

  const uint16_t* r = scan.range_mm.data();
  const BeamDirections::Trig* c = directions.cos.data();
  const BeamDirections::Trig* s = directions.sin.data();
  const std::size_t n = std::min<std::size_t>(scan.beam_count, kMaxBeams);
  // Cut by the most broken bound first: cutting in beam order would let each of a wall's
  // beams shave a little in turn and leave a command well inside the feasible set (and
  // lopsided); the worst one first lands on or near the closest feasible command.
  for (;;) {
    // A return whose bound is above the command's speed cannot be broken by it.
    const int64_t speed = std::lround(std::hypot(static_cast<float>(vx), static_cast<float>(vy))) + 1;
    const int64_t reach = stop_mm_ + (speed * 256) / gain_q8_ + 1;
    const int32_t far_mm = static_cast<int32_t>(std::min<int64_t>(reach, max_mm_));
    int64_t worst = kToleranceMmps;
    int64_t worst_c = 0, worst_s = 0;
    bool broken = false;
    for (std::size_t i = 0; i < n; ++i) {
      const int32_t ri = r[i];
      if (ri < kMinValidRangeMm || ri > far_mm) continue;
      const int64_t closing = (vx * c[i].raw() + vy * s[i].raw() + kRound) >> kQ;  // mm/s towards it
      const int64_t bound = (int64_t{gain_q8_} * (ri - stop_mm_)) >> 8;
      if (closing - bound > worst) {
        worst = closing - bound;
        worst_c = c[i].raw();
        worst_s = s[i].raw();
        broken = true;
      }
    }
    for (const Virtual& e : extra) {
      const int64_t closing = (vx * e.c + vy * e.s + kRound) >> kQ;
      if (closing - e.bound > worst) {
        worst = closing - e.bound;
        worst_c = e.c;
        worst_s = e.s;
        broken = true;
      }
    }
    if (speed > blind_bound_mmps_) {
      for (std::size_t k = 0; k < blind_count_; ++k) {
        const int64_t closing = (vx * blind_cos_[k].raw() + vy * blind_sin_[k].raw() + kRound) >> kQ;
        if (closing - blind_bound_mmps_ > worst) {
          worst = closing - blind_bound_mmps_;
          worst_c = blind_cos_[k].raw();
          worst_s = blind_sin_[k].raw();
          broken = true;
        }
      }
    }
    if (!broken) break;
    if (out.cuts == kMaxCuts) {
      // Not settled: a wall's returns bound the command along a curve, and cuts on its tangents
      // close in on it slowly. What is left is scaled away, which the command's direction
      // survives: a scaled command closes on each return in proportion, so the largest factor
      // that keeps every bound is the smallest bound / closing.
      scale_to_bounds(scan, directions, extra, vx, vy, out);
      break;
    }
    vx -= (worst * worst_c + kRound) >> kQ;
    vy -= (worst * worst_s + kRound) >> kQ;
    ++out.cuts;
  }
  v = {static_cast<float>(vx) * 1e-3f, static_cast<float>(vy) * 1e-3f};
  out.removed_mps = (in - v).norm();
  return out;
}

void ApproachLimiter::scale_to_bounds(const LaserScan& scan, const BeamDirections& directions,
                                      std::span<const Virtual> extra, int64_t& vx, int64_t& vy,
                                      ApproachResult& out) const {
  constexpr int64_t kOne = int64_t{1} << 16;
  int64_t factor = kOne;  // Q16
  const std::size_t n = std::min<std::size_t>(scan.beam_count, kMaxBeams);
  auto fit = [&](int64_t closing, int64_t bound) {
    if (closing <= bound + kToleranceMmps) return;
    // Inside stop_distance (bound <= 0) no factor helps: the command stops.
    factor = bound <= 0 ? 0 : std::min(factor, (bound * kOne) / closing);
  };
  for (std::size_t i = 0; i < n && factor > 0; ++i) {
    const int32_t ri = scan.range_mm[i];
    if (ri < kMinValidRangeMm || ri > max_mm_) continue;
    fit((vx * directions.cos[i].raw() + vy * directions.sin[i].raw() + kRound) >> kQ,
        (int64_t{gain_q8_} * (ri - stop_mm_)) >> 8);
  }
  for (const Virtual& e : extra) fit((vx * e.c + vy * e.s + kRound) >> kQ, e.bound);
  for (std::size_t k = 0; k < blind_count_ && factor > 0; ++k)
    fit((vx * blind_cos_[k].raw() + vy * blind_sin_[k].raw() + kRound) >> kQ, blind_bound_mmps_);
  vx = (vx * factor) / kOne;
  vy = (vy * factor) / kOne;
  out.scaled = true;
  out.stopped = factor == 0;
}

}  // namespace kestrel::exploration
