#include "kestrel/slam/scan_fit.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::slam {

void thin_to_map_scan(const scan_matching::ScanPoints& in, float cell_m, uint16_t max_points, MapScan& out) {
  out.count = 0;
  if (in.count == 0 || max_points == 0 || !(cell_m > 0.0f)) return;
  const uint16_t n = std::min<uint16_t>(in.count, static_cast<uint16_t>(kMaxScanPoints));
  const uint16_t stride = static_cast<uint16_t>((n + max_points - 1) / max_points);
  const float to_sub = kSub / cell_m;
  constexpr float kReach = static_cast<float>(kMapSide) * kSub;
  for (uint16_t i = 0; i < n && out.count < max_points; i += stride) {
    const float x = in.x[i] * to_sub, y = in.y[i] * to_sub;
    if (!(std::fabs(x) < kReach && std::fabs(y) < kReach)) continue;  // also drops NaN
    out.point[out.count++] = {static_cast<int32_t>(std::lround(x)), static_cast<int32_t>(std::lround(y))};
  }
}

ScanPlacement::ScanPlacement(const SlamMap& map, const Pose2& pose)
    : origin_(map.to_sub(pose.x, pose.y)),
      cos_q12_(static_cast<int32_t>(std::lround(std::cos(pose.theta) * 4096.0f))),
      sin_q12_(static_cast<int32_t>(std::lround(std::sin(pose.theta) * 4096.0f))) {}

uint32_t mean_level(const SlamMap& map, const MapScan& scan, const Pose2& pose) {
  if (scan.count == 0) return uint32_t{kUnknown} << kSubBits;
  const ScanPlacement at(map, pose);
  uint32_t sum = 0;  // at most 2048 * 65280: fits
  for (uint16_t i = 0; i < scan.count; ++i) sum += map.sample(at.place(scan.point[i]));
  return sum / scan.count;
}

float known_share(const SlamMap& map, const MapScan& scan, const Pose2& pose) {
  if (scan.count == 0) return 0.0f;
  const ScanPlacement at(map, pose);
  uint32_t known = 0;
  for (uint16_t i = 0; i < scan.count; ++i) {
    const SubPoint p = at.place(scan.point[i]);
    known += map.at(p.x >> kSubBits, p.y >> kSubBits) != kUnknown ? 1u : 0u;
  }
  return static_cast<float>(known) / static_cast<float>(scan.count);
}

namespace {

// Roughly standard normal: the sum of four uniforms, centred and scaled to unit variance.
float normal(Prng& prng) {
  const float s = prng.uniform() + prng.uniform() + prng.uniform() + prng.uniform();
  return (s - 2.0f) * 1.7320508f;
}

}  // namespace

FitResult monte_carlo_search(const SlamMap& map, const MapScan& scan, const Pose2& start, SearchSpread spread,
                             SearchAnchor anchor, uint32_t iterations, Prng& prng) {
  FitResult r;
  r.pose = start;
  r.level = r.cost = r.prior_level = mean_level(map, scan, start);
  const auto charge = [&](const Pose2& c) {
    const float dx = c.x - start.x, dy = c.y - start.y, dt = wrap_angle(c.theta - start.theta);
    const float levels = anchor.per_m2 * (dx * dx + dy * dy) + anchor.per_rad2 * dt * dt;
    return static_cast<uint32_t>(std::min(levels, 255.0f) * kSub);
  };
  const uint32_t patience = std::max<uint32_t>(1, iterations / 5);
  uint32_t fails = 0;
  for (uint32_t i = 0; i < iterations; ++i) {
    const Pose2 c{r.pose.x + normal(prng) * spread.xy_m, r.pose.y + normal(prng) * spread.xy_m,
                  wrap_angle(r.pose.theta + normal(prng) * spread.theta_rad)};
    const uint32_t l = mean_level(map, scan, c);
    const uint32_t cost = l + charge(c);
    if (cost < r.cost) {
      r.pose = c;
      r.level = l;
      r.cost = cost;
      fails = 0;
    } else if (++fails >= patience) {
      spread.xy_m *= 0.5f;
      spread.theta_rad *= 0.5f;
      fails = 0;
    }
  }
  return r;
}

FitCurvature fit_curvature(const SlamMap& map, const MapScan& scan, const Pose2& at, float h_m) {
  const auto f = [&](float dx, float dy) {
    return static_cast<float>(mean_level(map, scan, Pose2{at.x + dx, at.y + dy, at.theta})) / kSub;
  };
  const float f0 = f(0, 0), fx = f(h_m, 0), fy = f(0, h_m);
  const float h2 = h_m * h_m;
  const float a = (fx + f(-h_m, 0) - 2.0f * f0) / h2;
  const float c = (fy + f(0, -h_m) - 2.0f * f0) / h2;
  const float b = (f(h_m, h_m) - fx - fy + f0) / h2;
  // Eigen-directions of [[a, b], [b, c]]: the first at angle phi, the second across it.
  const float mean = 0.5f * (a + c), half = std::sqrt(0.25f * (a - c) * (a - c) + b * b);
  return {0.5f * std::atan2(2.0f * b, a - c), mean + half, mean - half};
}

Pose2 supported_move(const FitCurvature& k, const Pose2& start, const Pose2& best, float min_curvature) {
  const float u1x = std::cos(k.first_rad), u1y = std::sin(k.first_rad);
  float mx = best.x - start.x, my = best.y - start.y;
  const float along1 = mx * u1x + my * u1y, along2 = -mx * u1y + my * u1x;
  const float keep1 = k.first >= min_curvature ? along1 : 0.0f;
  const float keep2 = k.second >= min_curvature ? along2 : 0.0f;
  mx = keep1 * u1x - keep2 * u1y;
  my = keep1 * u1y + keep2 * u1x;
  if (!std::isfinite(mx) || !std::isfinite(my)) return start;
  return {start.x + mx, start.y + my, best.theta};
}

}  // namespace kestrel::slam
