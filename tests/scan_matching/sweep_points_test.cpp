// The integer points pass (sweep_points.hpp) against the float formula it replaced, evaluated
// here in double: the same points, each within 0.02 mm out to 30 m (the Q30 turn per beam,
// rounded, is the largest term: half of 2^-30 rad over 1080 beams is 15 um at 30 m; the
// search's finest grid is 0.16 mm), and the same skip rules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kestrel/scan_matching/sweep_points.hpp"

namespace kestrel::scan_matching {
namespace {

// A UTM-30LX-like scan whose ranges walk pseudo-randomly over [20 mm, max_mm), with a few
// range codes (no return) among them.
LaserScan scan_of(uint16_t beams, float fov, int64_t interval_us, uint16_t max_mm) {
  LaserScan s;
  s.beam_count = beams;
  s.first_angle_rad = -fov / 2;
  s.angle_step_rad = fov / static_cast<float>(beams - 1);
  s.max_range_mm = max_mm;
  s.beam_interval = Duration::from_us(interval_us);
  uint32_t state = 12345;
  for (uint16_t i = 0; i < beams; ++i) {
    state = state * 1664525u + 1013904223u;
    s.range_mm[i] = i % 17 == 0 ? range_code::kDropout : static_cast<uint16_t>(20 + (state >> 8) % (max_mm - 20u));
  }
  return s;
}

// The former ScanMatcher::to_points and ::deskew, in double.
struct Point { double x, y; uint16_t beam; };
std::vector<Point> reference(const LaserScan& scan, float min_mm, float end_mm, const SweepMotion& m, bool deskew) {
  std::vector<Point> out;
  const double c = std::cos(static_cast<double>(m.heading_rad)), s = std::sin(static_cast<double>(m.heading_rad));
  const double vx = c * m.vx_mps + s * m.vy_mps, vy = -s * m.vx_mps + c * m.vy_mps;
  const double step_s = scan.beam_interval.seconds();
  for (uint16_t i = 0; i < scan.beam_count; ++i) {
    const uint16_t r = scan.range_mm[i];
    if (!LaserScan::is_return(r) || static_cast<float>(r) < min_mm || static_cast<float>(r) >= end_mm) continue;
    const double a0 = scan.angle_of(i);
    const double x = r * 1e-3 * std::cos(a0), y = r * 1e-3 * std::sin(a0);
    if (!deskew) {
      out.push_back({x, y, i});
      continue;
    }
    const double t = step_s * i, a = m.yaw_rate_radps * t, ca = 1 - 0.5 * a * a;
    out.push_back({ca * x - a * y + vx * t, a * x + ca * y + vy * t, i});
  }
  return out;
}

// The largest distance between the pass's points and the reference's (which must be the same
// beams), in metres.
double max_error(const ScanPoints& p, const std::vector<Point>& ref) {
  EXPECT_EQ(p.count, ref.size());
  double worst = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(p.count, ref.size()); ++i) {
    EXPECT_EQ(p.beam[i], ref[i].beam);
    worst = std::max(worst, std::hypot(p.x[i] - ref[i].x, p.y[i] - ref[i].y));
  }
  return worst;
}

TEST(SweepPoints, AgreesWithTheFloatFormula) {
  // Instantaneous; the deskew test's sweep (0.8 rad/s, 0.5 m/s); fast, turning the other way
  // at a heading where both velocity components matter; barely moving; the bounds' edge.
  const SweepMotion motions[] = {{0, 0, 0, 0},         {0.1f, 0.5f, 0, 0.8f},       {-2.0f, 3.0f, 2.0f, -3.0f},
                                 {1.0f, -0.01f, 0.02f, 1e-3f}, {0.7f, -1.2f, 0.4f, 2.5f}};
  for (const int64_t interval_us : {17, 98}) {
    const LaserScan scan = scan_of(1081, 4.712389f, interval_us, 30000);
    BeamTable table;
    table.update(scan);
    for (const SweepMotion& m : motions) {
      ScanPoints p;
      sweep_to_points(scan, table, 20.0f, 30000.0f, m, p);
      const bool moving = m.vx_mps != 0 || m.vy_mps != 0 || m.yaw_rate_radps != 0;
      EXPECT_LT(max_error(p, reference(scan, 20.0f, 30000.0f, m, moving)), 0.02e-3)
          << "interval " << interval_us << " us, yaw rate " << m.yaw_rate_radps;
    }
  }
}

// The longest range a uint16 holds, turned by a whole radian and carried 16 m over the sweep:
// the fixed point stays inside int32 (the sanitizer build would stop on an overflow).
TEST(SweepPoints, HoldsTheLongestRangeAtTheMotionBounds) {
  LaserScan scan = scan_of(1081, 4.712389f, 100, 65535);
  for (uint16_t i = 0; i < scan.beam_count; ++i) scan.range_mm[i] = 65535;
  BeamTable table;
  table.update(scan);
  const float sweep_s = 1080 * 1e-4f;
  for (const float sign : {-1.0f, 1.0f}) {
    const SweepMotion m{0.3f, sign * 0.999f * kMaxSweepTravelM / sweep_s, 0, sign * 0.999f * kMaxSweepTurnRad / sweep_s};
    ScanPoints p;
    ASSERT_EQ(sweep_to_points(scan, table, 20.0f, 70000.0f, m, p), 1081);
    EXPECT_LT(max_error(p, reference(scan, 20.0f, 70000.0f, m, true)), 0.05e-3);
  }
}

// The points are left as the instantaneous pass gives them, bit for bit, when there is nothing
// to correct with or the motion is beyond the bounds.
TEST(SweepPoints, SkipsWhatItCannotCorrectWith) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  LaserScan scan = scan_of(682, 4.18f, 98, 4000);
  BeamTable table;
  table.update(scan);
  ScanPoints still;
  sweep_to_points(scan, table, 20.0f, 4000.0f, SweepMotion{}, still);
  const auto same_as_still = [&](const LaserScan& s, const SweepMotion& m) {
    ScanPoints p;
    sweep_to_points(s, table, 20.0f, 4000.0f, m, p);
    if (p.count != still.count) return false;
    for (uint16_t i = 0; i < p.count; ++i)
      if (p.x[i] != still.x[i] || p.y[i] != still.y[i] || p.beam[i] != still.beam[i]) return false;
    return true;
  };
  const SweepMotion turning{0, 0.5f, 0, 0.8f};
  EXPECT_FALSE(same_as_still(scan, turning));
  EXPECT_TRUE(same_as_still(scan, {nan, 0.5f, 0, 0.8f}));
  EXPECT_TRUE(same_as_still(scan, {0, nan, 0, 0.8f}));
  EXPECT_TRUE(same_as_still(scan, {0, 0.5f, inf, 0.8f}));
  EXPECT_TRUE(same_as_still(scan, {0, 0.5f, 0, nan}));
  EXPECT_TRUE(same_as_still(scan, {0, 0.5f, 0, 1e6f}));           // beyond a radian per sweep
  EXPECT_TRUE(same_as_still(scan, {0, 0, 300.0f, 0}));            // beyond 16 m per sweep
  EXPECT_TRUE(same_as_still(scan, {0, 1e30f, 0, 0}));             // a product that overflows
  for (const int64_t us : {0, -98}) {
    LaserScan s = scan;
    s.beam_interval = Duration::from_us(us);
    EXPECT_TRUE(same_as_still(s, turning)) << us;
  }
}

// Returns are kept as the float comparisons did (min <= r < end, the end being the sensor's
// maximum: no surface), and range codes never, whatever the minimum.
TEST(SweepPoints, GatesRangesAsTheFloatsDid) {
  LaserScan scan = scan_of(8, 1.0f, 0, 5000);
  const uint16_t ranges[] = {range_code::kNoReturn, range_code::kDeflected, 100, 101, 3999, 4000, 4001, 19};
  for (uint16_t i = 0; i < 8; ++i) scan.range_mm[i] = ranges[i];
  BeamTable table;
  table.update(scan);
  const auto kept = [&](float lo, float end) {
    ScanPoints p;
    sweep_to_points(scan, table, lo, end, SweepMotion{}, p);
    std::vector<uint16_t> r(p.range_mm.begin(), p.range_mm.begin() + p.count);
    return r;
  };
  EXPECT_EQ(kept(0.0f, 4000.0f), (std::vector<uint16_t>{100, 101, 3999}));
  EXPECT_EQ(kept(100.0f, 4000.2f), (std::vector<uint16_t>{100, 101, 3999, 4000}));
  EXPECT_EQ(kept(100.5f, 1e9f), (std::vector<uint16_t>{101, 3999, 4000, 4001}));
  EXPECT_EQ(kept(0.02f * 1000.0f, 0.0f), (std::vector<uint16_t>{}));
}

}  // namespace
}  // namespace kestrel::scan_matching
