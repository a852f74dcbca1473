// The fake Hokuyos: datasheet noise, range codes, dropouts, rotating-mirror timing and the
// mirror altimeter, driven by synthetic vehicle states (no dynamics involved).
#include <gtest/gtest.h>

#include <cmath>

#include "kestrel/sim/sim_laser.hpp"
#include "kestrel/sim/world_parser.hpp"

namespace kestrel::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

World make(const std::string& text) {
  auto r = parse_world(text, "test");
  EXPECT_TRUE(r.ok) << r.error;
  return r.world;
}

VehicleState at(TimeUs t, double x, double y, double z, double yaw = 0) {
  VehicleState s;
  s.stamp = t;
  s.position_m = {x, y, z};
  s.yaw_rad = yaw;
  s.on_ground = false;
  return s;
}

// Steps a static pose for `seconds`, calling f(scan) for each completed scan.
template <class F>
void run_static(SimLaser& laser, double x, double y, double z, double seconds, F&& f) {
  for (int64_t ms = 0; ms < static_cast<int64_t>(seconds * 1000); ++ms) {
    if (laser.on_step(at(TimeUs{ms * 1000}, x, y, z), at(TimeUs{(ms + 1) * 1000}, x, y, z))) {
      LaserScan s;
      ASSERT_EQ(laser.poll(s), Status::kOk);
      EXPECT_EQ(laser.poll(s), Status::kNoData);
      f(s);
    }
  }
}

// Residuals of every beam hitting a wall x = wall_x ahead (true range wall_x / cos(angle)),
// normalised by the model's sigma at the true range, over `seconds` of scans: many samples
// from few scans keeps the test fast under qemu-arm.
struct Stats {
  double mean_m = 0;     // mean residual, m
  double z_std = 0;      // standard deviation of the normalised residuals (1 if the model holds)
  double sigma_m = 0;    // mean model sigma over the used beams
  int n = 0, codes = 0;
};

Stats wall_stats(const LaserParams& p, double wall_x, double seconds, double r_lo, double r_hi) {
  World w = make("start 0 0 1 0\nwall " + std::to_string(wall_x) + " -200 " + std::to_string(wall_x) + " 200\n");
  RayCaster rc(w);
  SimLaser laser(p, rc, Rng(17), nullptr);
  double s1 = 0, z1 = 0, z2 = 0, sg = 0;
  Stats st;
  run_static(laser, 0, 0, 1.0, seconds, [&](const LaserScan& s) {
    for (std::size_t i = 0; i < s.beam_count; ++i) {
      const double c = std::cos(s.angle_of(i));
      if (c < 0.3) continue;
      const double truth = wall_x / c;
      if (truth < r_lo || truth > r_hi) continue;
      const uint16_t r = s.range_mm[i];
      if (!LaserScan::is_return(r)) {
        ++st.codes;
        continue;
      }
      const double e = r * 1e-3 - truth, sigma = p.sigma_at(truth);
      s1 += e;
      z1 += e / sigma;
      z2 += (e / sigma) * (e / sigma);
      sg += sigma;
      ++st.n;
    }
  });
  st.mean_m = s1 / st.n;
  st.z_std = std::sqrt(std::max(0.0, z2 / st.n - (z1 / st.n) * (z1 / st.n)));
  st.sigma_m = sg / st.n;
  return st;
}

TEST(SimLaser, GeometryOfBothModels) {
  const hal::LaserGeometry u = LaserParams::utm30lx().geometry();
  EXPECT_EQ(u.beam_count, 1081);
  EXPECT_NEAR(u.first_angle_rad, -135 * kPi / 180, 1e-6);
  EXPECT_NEAR(u.first_angle_rad + u.angle_step_rad * 1080, 135 * kPi / 180, 1e-5);
  EXPECT_EQ(u.max_range_mm, 30000);
  EXPECT_EQ(u.scan_period.us, 25000);
  const hal::LaserGeometry g = LaserParams::urg04lx().geometry();
  EXPECT_EQ(g.beam_count, 682);
  EXPECT_NEAR(g.angle_step_rad, 2 * kPi / 1024, 1e-7);
  EXPECT_NEAR(g.angle_step_rad * 681, 239.6 * kPi / 180, 0.01);
  EXPECT_EQ(g.max_range_mm, 4000);
  EXPECT_EQ(g.scan_period.us, 100000);
  EXPECT_STREQ(LaserParams::utm30lx().validate(), "");
  EXPECT_STREQ(LaserParams::urg04lx().validate(), "");
}

TEST(SimLaser, Utm30lxNoiseMatchesTheDatasheet) {
  LaserParams p = LaserParams::utm30lx();
  p.dropout_probability = 0;
  p.deflected_beams = 0;
  // Up to 10 m: sigma 10 mm.
  const Stats near = wall_stats(p, 5, 0.5, 0.1, 9.9);
  EXPECT_GT(near.n, 5000);
  EXPECT_EQ(near.codes, 0);
  EXPECT_NEAR(near.sigma_m, 0.010, 1e-9);
  EXPECT_NEAR(near.mean_m, 0.0, 0.001);
  EXPECT_NEAR(near.z_std, 1.0, 0.04);
  // 10 to 30 m: sigma 30 mm.
  const Stats far = wall_stats(p, 15, 0.5, 10.1, 29.9);
  EXPECT_GT(far.n, 3000);
  EXPECT_NEAR(far.sigma_m, 0.030, 1e-9);
  EXPECT_NEAR(far.mean_m, 0.0, 0.003);
  EXPECT_NEAR(far.z_std, 1.0, 0.05);
  // Beyond 30 m: no return.
  const Stats none = wall_stats(p, 35, 0.1, 0, 1e9);
  EXPECT_EQ(none.n, 0);
  EXPECT_GT(none.codes, 1000);
}

TEST(SimLaser, Urg04lxNoiseAndRangeLimits) {
  LaserParams p = LaserParams::urg04lx();
  p.dropout_probability = 0;
  // 1 % of the range between 1 and 4 m.
  const Stats mid = wall_stats(p, 2, 1.0, 1.0, 3.99);
  EXPECT_GT(mid.n, 2000);
  EXPECT_GT(mid.sigma_m, 0.02);
  EXPECT_NEAR(mid.mean_m, 0.0, 0.002);
  EXPECT_NEAR(mid.z_std, 1.0, 0.05);
  // 10 mm below 1 m.
  const Stats near = wall_stats(p, 0.5, 1.0, 0.02, 0.99);
  EXPECT_NEAR(near.sigma_m, 0.010, 1e-9);
  EXPECT_NEAR(near.z_std, 1.0, 0.05);
  // Beyond 4 m: no return.
  const Stats far = wall_stats(p, 5, 0.3, 0, 1e9);
  EXPECT_EQ(far.n, 0);
  EXPECT_GT(far.codes, 500);
  // Nearer than 2 cm: the too-near code.
  const std::size_t ahead = 341;  // about 0 rad: the first beam is 340.5 steps to the right
  World w = make("start 0 0 1 0\nwall 0.015 -1 0.015 1\n");
  RayCaster rc(w);
  SimLaser laser(p, rc, Rng(1), nullptr);
  int too_near = 0;
  run_static(laser, 0, 0, 1, 0.2, [&](const LaserScan& s) { too_near += s.range_mm[ahead] == range_code::kTooNear; });
  EXPECT_EQ(too_near, 2);
}

TEST(SimLaser, GlassGivesNoReturnAndDropoutsHappenAtTheirRate) {
  LaserParams p = LaserParams::utm30lx();
  p.deflected_beams = 0;
  p.dropout_probability = 0.05;
  World w = make("start 0 0 1 0\nwall 5 -30 5 30 glass\nwall -5 -30 -5 30\nwall -5 30 5 30\nwall -5 -30 5 -30\n");
  RayCaster rc(w);
  SimLaser laser(p, rc, Rng(3), nullptr);
  int glass_ret = 0, dropouts = 0, returns = 0;
  run_static(laser, 0, 0, 1, 1.0, [&](const LaserScan& s) {
    glass_ret += LaserScan::is_return(s.range_mm[540]) ? 1 : 0;
    for (std::size_t i = 0; i < s.beam_count; ++i) {
      returns += LaserScan::is_return(s.range_mm[i]) ? 1 : 0;
      dropouts += s.range_mm[i] == range_code::kDropout ? 1 : 0;
    }
  });
  EXPECT_EQ(glass_ret, 0);
  // Beams through the glass (or beyond 30 m) have no return and cannot drop out; of the
  // others 5 % drop out.
  EXPECT_GT(returns, 5000);
  EXPECT_NEAR(static_cast<double>(dropouts) / (returns + dropouts), 0.05, 0.008);
}

TEST(SimLaser, EachBeamIsTakenAtItsOwnTimeDuringTheSweep) {
  // The vehicle flies at 4 m/s towards a wall 10 m ahead: beams later in the sweep see it
  // closer, by exactly the distance flown since the first beam.
  LaserParams p = LaserParams::utm30lx();
  p.deflected_beams = 0;
  p.dropout_probability = 0;
  p.sigma_near_m = p.sigma_far_m = 0;
  World w = make("start 0 0 1 0\nwall 10 -50 10 50\n");
  RayCaster rc(w);
  SimLaser laser(p, rc, Rng(1), nullptr);
  const double v = 4.0;
  LaserScan scan;
  bool got = false;
  for (int64_t ms = 0; ms < 60 && !got; ++ms) {
    const double x0 = v * ms * 1e-3, x1 = v * (ms + 1) * 1e-3;
    if (laser.on_step(at(TimeUs{ms * 1000}, x0, 0, 1), at(TimeUs{(ms + 1) * 1000}, x1, 0, 1)) && ms > 30) {
      ASSERT_EQ(laser.poll(scan), Status::kOk);
      got = true;
    }
  }
  ASSERT_TRUE(got);
  EXPECT_EQ(scan.stamp.us, 25000);
  EXPECT_EQ(scan.beam_interval.us, 17);
  for (std::size_t i : {400u, 540u, 680u}) {
    const double t = scan.time_of(i).seconds();
    const double want = (10 - v * t) / std::cos(scan.angle_of(i));
    EXPECT_NEAR(scan.range_mm[i] * 1e-3, want, 0.0011) << i;
  }
  // The difference between the first and the last beam looking at the wall is visible.
  const double t400 = scan.time_of(400).seconds(), t680 = scan.time_of(680).seconds();
  EXPECT_GT((t680 - t400) * v, 0.015);
}

TEST(SimLaser, ScansArriveAtTheScanRateAndPollGivesTheNewest) {
  World w = make("start 0 0 1 0\nwall 5 -30 5 30\n");
  RayCaster rc(w);
  SimLaser laser(LaserParams::utm30lx(), rc, Rng(1), nullptr);
  int completed = 0;
  for (int64_t ms = 0; ms < 1000; ++ms)
    completed += laser.on_step(at(TimeUs{ms * 1000}, 0, 0, 1), at(TimeUs{(ms + 1) * 1000}, 0, 0, 1)) ? 1 : 0;
  EXPECT_EQ(completed, 40);
  LaserScan s;
  ASSERT_EQ(laser.poll(s), Status::kOk);  // only the newest of the 40 unread scans
  EXPECT_EQ(s.stamp.us, 39 * 25000);
  EXPECT_EQ(laser.poll(s), Status::kNoData);
}

TEST(SimLaser, MirrorBeamsMeasureHeight) {
  World w = make("start 0 0 1 0\nwall 5 -30 5 30\n");
  RayCaster rc(w);
  SimAltimeter alt;
  SimLaser laser(LaserParams::utm30lx(), rc, Rng(5), &alt);
  EXPECT_TRUE(alt.has_source());
  double sum = 0;
  int n = 0;
  run_static(laser, 0, 0, 1.25, 1.0, [&](const LaserScan& s) {
    for (int i = 0; i < 20; ++i) EXPECT_EQ(s.range_mm[static_cast<std::size_t>(i)], range_code::kDeflected);
    EXPECT_TRUE(LaserScan::is_return(s.range_mm[540]));
  });
  AltimeterSample a;
  while (alt.poll(a) == Status::kOk) {
    sum += a.height_m;
    ++n;
    EXPECT_GT(a.variance_m2, 0);
  }
  EXPECT_EQ(n, 40);
  EXPECT_NEAR(sum / n, 1.25, 0.003);
  // Without deflected beams there is no altimeter source.
  SimAltimeter none;
  LaserParams no_mirror = LaserParams::urg04lx();
  no_mirror.deflected_beams = 0;
  SimLaser urg(no_mirror, rc, Rng(5), &none);
  EXPECT_FALSE(none.has_source());
  EXPECT_EQ(none.poll(a), Status::kNoData);
}

}  // namespace
}  // namespace kestrel::sim
