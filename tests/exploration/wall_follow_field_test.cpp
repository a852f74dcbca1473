// Equation-level tests of paper 002's wall-following field (section III, equations 2-4) and of
// its fixed-point implementation against a double-precision reference.
#include "kestrel/exploration/wall_follow_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;
using test::uniform_scan;

// Equations 2-3 in double precision, the oracle of the fixed-point loop.
Eigen::Vector2d reference_field(const LaserScan& s, const WallFollowParams& p) {
  double u = 0, v = 0;
  int n = 0;
  const double rmax = std::min<double>(p.max_range_m, s.max_range_mm * 1e-3);
  for (int i = 0; i < s.beam_count; ++i) {
    if (s.range_mm[i] < kMinValidRangeMm) continue;
    const double r = s.range_mm[i] * 1e-3;
    if (r > rmax + 1e-9) continue;
    const double k = r < p.safe_range_m - 1e-9 ? p.gain_safe : p.gain_wf;
    const double vr = k * (r - p.target_range_m);
    const double a = static_cast<double>(s.first_angle_rad) + static_cast<double>(s.angle_step_rad) * i;
    u += vr * std::cos(a);
    v += vr * std::sin(a);
    ++n;
  }
  double w = 1.0;
  if (p.normalisation == FieldNormalisation::kPerRadian) w = std::fabs(s.angle_step_rad);
  if (p.normalisation == FieldNormalisation::kPerInRangeBeam) w = n > 0 ? 1.0 / n : 0.0;
  return {u * w, v * w};
}

class FieldTest : public ::testing::Test {
 protected:
  FieldResult run(const LaserScan& s, const WallFollowParams& p = {}) {
    EXPECT_EQ(field->configure(BeamGeometry::of(s), p), Status::kOk);
    FieldResult r;
    EXPECT_EQ(field->body_velocity(s, r), Status::kOk);
    return r;
  }
  std::unique_ptr<WallFollowField> field = std::make_unique<WallFollowField>();
  LaserModel urg = LaserModel::urg04lx();
};

TEST_F(FieldTest, WallsAllAtTargetRangeGiveZero) {
  // GIVEN a wall at r_t around the vehicle (every beam returns r_t)
  const FieldResult r = run(uniform_scan(urg, 1000));
  // THEN every incremental velocity of equation 2 is zero
  EXPECT_EQ(r.in_range, urg.beams);
  EXPECT_FLOAT_EQ(r.body_mps.x(), 0.0f);
  EXPECT_FLOAT_EQ(r.body_mps.y(), 0.0f);
}

TEST_F(FieldTest, SingleBeamCloserRepelsFartherAttractsAtTheGainOfEquation2) {
  WallFollowParams p;
  p.normalisation = FieldNormalisation::kPaperSum;  // the plain sum: one beam = one v_ri
  const int beam = 400;                             // left of the nose
  LaserScan s = uniform_scan(urg, range_code::kNoReturn);
  const double a = s.first_angle_rad + s.angle_step_rad * beam;
  for (double r_m : {0.7, 1.0, 2.5}) {
    s.range_mm[beam] = static_cast<uint16_t>(std::lround(r_m * 1000));
    const FieldResult f = run(s, p);
    ASSERT_EQ(f.in_range, 1);
    const double expect = p.gain_wf * (r_m - p.target_range_m);  // equation 2, r >= r_safe
    EXPECT_NEAR(f.body_mps.x(), expect * std::cos(a), 2e-4);
    EXPECT_NEAR(f.body_mps.y(), expect * std::sin(a), 2e-4);
    // Along the beam: negative (away from the wall) when closer, positive when farther.
    const double along = f.body_mps.x() * std::cos(a) + f.body_mps.y() * std::sin(a);
    if (r_m < 1.0) {
      EXPECT_LT(along, 0.0);
    } else if (r_m > 1.0) {
      EXPECT_GT(along, 0.0);
    } else {
      EXPECT_NEAR(along, 0.0, 1e-6);
    }
  }
}

TEST_F(FieldTest, SafeGainDominatesInsideSafeRadius) {
  WallFollowParams p;
  p.normalisation = FieldNormalisation::kPaperSum;
  p.safe_range_m = 0.5f;  // round numbers for the expected values below
  LaserScan s = uniform_scan(urg, range_code::kNoReturn);
  s.range_mm[341] = 499;  // just inside r_safe = 0.5: K_safe
  const FieldResult inside = run(s, p);
  s.range_mm[341] = 500;  // on r_safe: K_wf
  const FieldResult outside = run(s, p);
  EXPECT_EQ(inside.in_safe, 1);
  EXPECT_EQ(outside.in_safe, 0);
  const double a = s.first_angle_rad + s.angle_step_rad * 341;
  EXPECT_NEAR(inside.body_mps.norm(), p.gain_safe * 0.501, 1e-3);
  EXPECT_NEAR(outside.body_mps.norm(), p.gain_wf * 0.5, 1e-3);
  EXPECT_GT(inside.body_mps.norm(), 20.0f * outside.body_mps.norm());
  EXPECT_LT(inside.body_mps.x() * std::cos(a) + inside.body_mps.y() * std::sin(a), 0.0);  // repels
  // One beam inside r_safe outweighs many far beams pulling the other way.
  LaserScan mixed = uniform_scan(urg, range_code::kNoReturn);
  for (int i = 300; i < 382; ++i) mixed.range_mm[i] = 300;   // obstacle ahead at 0.3 m
  for (int i = 0; i < 100; ++i) mixed.range_mm[i] = 3900;    // far wall behind-right
  for (int i = 582; i < 682; ++i) mixed.range_mm[i] = 3900;  // far wall behind-left
  EXPECT_LT(run(mixed).body_mps.x(), -0.5f);
}

TEST_F(FieldTest, StraightWallAheadHasItsEquilibriumWhereTheIntegralVanishes) {
  // A long wall across the nose at distance h, beams in range up to R: per radian, the x field is
  // K_wf * integral over |theta| < acos(h/R) of (h - r_t cos theta) = 2 K_wf (h alpha - r_t sin alpha).
  const WallFollowParams p;
  const double R = p.max_range_m, rt = p.target_range_m;
  auto integral = [&](double h) {
    const double al = std::acos(h / R);
    return h * al - rt * std::sin(al);
  };
  double lo = 0.55, hi = rt;
  for (int i = 0; i < 60; ++i) ((integral(0.5 * (lo + hi)) < 0) ? lo : hi) = 0.5 * (lo + hi);
  const double h_star = 0.5 * (lo + hi);
  EXPECT_LT(h_star, rt);  // a straight wall settles nearer than r_t: oblique beams are long
  auto field_at = [&](double h) {
    SegmentWorld w;
    w.add(h, -100, h, 100);
    return run(w.scan(urg, 0, 0, 0)).body_mps;
  };
  for (double h : {h_star - 0.05, h_star + 0.05, 1.5, 2.5}) {
    const Eigen::Vector2f f = field_at(h);
    EXPECT_NEAR(f.x(), 2 * p.gain_wf * integral(h), 0.01) << "h=" << h;
    EXPECT_NEAR(f.y(), 0.0f, 1e-3) << "symmetric about the x axis";
  }
  EXPECT_LT(field_at(h_star - 0.05).x(), 0.0f);  // closer: repelled
  EXPECT_GT(field_at(h_star + 0.05).x(), 0.0f);  // farther: attracted
  EXPECT_NEAR(field_at(h_star).x(), 0.0f, 0.004f);
}

TEST_F(FieldTest, FixedPointMatchesDoubleReference) {
  std::mt19937 rng(7);
  for (LaserModel m : {LaserModel::urg04lx(), LaserModel::utm30lx()}) {
    for (auto norm :
         {FieldNormalisation::kPerRadian, FieldNormalisation::kPaperSum, FieldNormalisation::kPerInRangeBeam}) {
      WallFollowParams p;
      p.normalisation = norm;
      p.max_range_m = m.max_range_mm > 4000 ? 10.0f : 4.0f;
      for (int trial = 0; trial < 20; ++trial) {
        LaserScan s = uniform_scan(m, 0);
        std::uniform_int_distribution<int> range(0, m.max_range_mm + 500);
        for (int i = 0; i < m.beams; ++i) {
          const int r = range(rng);
          s.range_mm[i] = static_cast<uint16_t>(r < 60 ? r % 4 : std::min(r, 65535));  // some codes
        }
        const FieldResult f = run(s, p);
        const Eigen::Vector2d ref = reference_field(s, p);
        const double tol = 1e-4 * (1.0 + ref.norm()) + 2e-4 * std::fabs(ref.norm());
        EXPECT_NEAR(f.body_mps.x(), ref.x(), tol);
        EXPECT_NEAR(f.body_mps.y(), ref.y(), tol);
      }
    }
  }
}

TEST_F(FieldTest, PerRadianNormalisationMakesTheGainLaserIndependent) {
  SegmentWorld room;
  room.add_box(-1.2, -0.8, 2.5, 1.9);
  WallFollowParams p;  // kPerRadian, max range 4 m for both lasers
  const Eigen::Vector2f urg_f = run(room.scan(LaserModel::urg04lx(), 0, 0, 0), p).body_mps;
  const Eigen::Vector2f utm_f = run(room.scan(LaserModel::utm30lx(), 0, 0, 0), p).body_mps;
  // The UTM also sees 15 degrees more on each side, so only roughly equal.
  EXPECT_NEAR(urg_f.x(), utm_f.x(), 0.15 * urg_f.norm());
  EXPECT_NEAR(urg_f.y(), utm_f.y(), 0.15 * urg_f.norm() + 0.01);
  p.normalisation = FieldNormalisation::kPaperSum;
  const float urg_sum = run(room.scan(LaserModel::urg04lx(), 0, 0, 0), p).body_mps.norm();
  const float utm_sum = run(room.scan(LaserModel::utm30lx(), 0, 0, 0), p).body_mps.norm();
  EXPECT_GT(utm_sum / urg_sum, 1.3f);  // the plain sum grows with the beam count
}

TEST_F(FieldTest, RangeCodesAndFarBeamsAreNotInRange) {
  LaserScan s = uniform_scan(urg, range_code::kDropout);
  s.range_mm[10] = range_code::kTooNear;
  s.range_mm[11] = range_code::kDeflected;
  s.range_mm[12] = 4001;  // beyond max_range_m = 4 m
  s.range_mm[13] = 1500;
  const FieldResult f = run(s);
  EXPECT_EQ(f.in_range, 1);
  EXPECT_EQ(f.nearest_beam, 13);
  EXPECT_EQ(f.nearest_mm, 1500);
  const FieldResult none = run(uniform_scan(urg, range_code::kNoReturn));
  EXPECT_EQ(none.in_range, 0);
  EXPECT_EQ(none.nearest_beam, 0xFFFF);
  EXPECT_EQ(none.body_mps, Eigen::Vector2f::Zero());
}

TEST_F(FieldTest, RotatesIntoTheInertialFrameWithTheHeading) {
  const Eigen::Vector2f w = WallFollowField::to_inertial({1.0f, 0.0f}, static_cast<float>(M_PI / 2));
  EXPECT_NEAR(w.x(), 0.0f, 1e-6);
  EXPECT_NEAR(w.y(), 1.0f, 1e-6);
  const Eigen::Vector2f w2 = WallFollowField::to_inertial({0.0f, 2.0f}, static_cast<float>(M_PI / 6));
  EXPECT_NEAR(w2.x(), -1.0f, 1e-6);
  EXPECT_NEAR(w2.y(), std::sqrt(3.0f), 1e-6);
}

TEST_F(FieldTest, RefusesBadConfigurationAndForeignScans) {
  FieldResult r;
  EXPECT_EQ(field->body_velocity(uniform_scan(urg, 1000), r), Status::kNotFound);
  WallFollowParams bad;
  bad.safe_range_m = 1.5f;  // r_safe must be below r_t
  EXPECT_EQ(field->configure(BeamGeometry::of(uniform_scan(urg, 0)), bad), Status::kInvalidArgument);
  bad = {};
  bad.gain_wf = NAN;
  EXPECT_EQ(field->configure(BeamGeometry::of(uniform_scan(urg, 0)), bad), Status::kInvalidArgument);
  EXPECT_EQ(field->configure({0, 0.0f, 0.01f, 4000}, {}), Status::kInvalidArgument);
  EXPECT_EQ(field->configure({100, 0.0f, 0.0f, 4000}, {}), Status::kInvalidArgument);
  // Regression (audit): ranges beyond what 16-bit millimetres and the field's 32-bit sums hold
  // were taken, and the field came out with the wrong sign; a step too fine for beam indices.
  bad = {};
  bad.target_range_m = 200.0f;
  EXPECT_EQ(field->configure(BeamGeometry::of(uniform_scan(urg, 0)), bad), Status::kInvalidArgument);
  EXPECT_EQ(field->configure({100, 0.0f, 1e-12f, 4000}, {}), Status::kInvalidArgument);
  EXPECT_FALSE(field->configured());
  ASSERT_EQ(field->configure(BeamGeometry::of(uniform_scan(urg, 0)), {}), Status::kOk);
  EXPECT_EQ(field->body_velocity(uniform_scan(LaserModel::utm30lx(), 1500), r), Status::kInvalidArgument);
  EXPECT_EQ(r.in_range, 0);
}

}  // namespace
}  // namespace kestrel::exploration
