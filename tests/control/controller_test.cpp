// The controller: sign conventions of AttitudeSetpoint, closed-loop behaviour on the model of
// paper 000 equation 1, saturation, bad inputs and the allocation guard.
#include "kestrel/control/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <random>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/core/angle.hpp"

namespace kestrel::control {
namespace {

NavState hover_at(Eigen::Vector3f p, float heading = 0.0f) {
  NavState n;
  n.valid = true;
  n.position_m = p;
  n.heading_rad = heading;
  return n;
}

GuidanceSetpoint hold(Eigen::Vector3f p, float heading = 0.0f) {
  GuidanceSetpoint s;
  s.position_m = p;
  s.heading_rad = heading;
  return s;
}

TEST(Controller, SignConventionsFollowAttitudeSetpoint) {
  const Controller c;
  const float hover = c.params().model.hover_thrust();
  EXPECT_FLOAT_EQ(hover, 0.5f);
  // At the set-point: level, hover thrust, no yaw rate, no flags.
  ControlOutput o = c.step(hover_at({0, 0, 1}), hold({0, 0, 1}));
  EXPECT_FLOAT_EQ(o.command.pitch_rad, 0.0f);
  EXPECT_FLOAT_EQ(o.command.roll_rad, 0.0f);
  EXPECT_FLOAT_EQ(o.command.thrust, 0.5f);
  EXPECT_EQ(o.flags, 0u);
  // Target ahead (+x body): pitch > 0. Target to the left (+y body): roll > 0.
  o = c.step(hover_at({0, 0, 1}), hold({0.3f, 0, 1}));
  EXPECT_GT(o.command.pitch_rad, 0.0f);
  EXPECT_NEAR(o.command.roll_rad, 0.0f, 1e-6f);
  o = c.step(hover_at({0, 0, 1}), hold({0, 0.3f, 1}));
  EXPECT_GT(o.command.roll_rad, 0.0f);
  EXPECT_NEAR(o.command.pitch_rad, 0.0f, 1e-6f);
  // Facing +y (heading pi/2), a target at +x world is to the right: roll < 0.
  o = c.step(hover_at({0, 0, 1}, kPi<float> / 2), hold({0.3f, 0, 1}, kPi<float> / 2));
  EXPECT_LT(o.command.roll_rad, 0.0f);
  EXPECT_NEAR(o.command.pitch_rad, 0.0f, 1e-6f);
  // Too low: more thrust. Heading left of the set-point (psi > ref): turn clockwise.
  o = c.step(hover_at({0, 0, 0.8f}), hold({0, 0, 1}));
  EXPECT_GT(o.command.thrust, 0.5f);
  o = c.step(hover_at({0, 0, 1}, 0.2f), hold({0, 0, 1}, 0.0f));
  EXPECT_LT(o.command.yaw_rate_radps, 0.0f);
  // The shortest way round: from 3.0 rad to -3.0 rad is counter-clockwise.
  o = c.step(hover_at({0, 0, 1}, 3.0f), hold({0, 0, 1}, -3.0f));
  EXPECT_GT(o.command.yaw_rate_radps, 0.0f);
}

// Simulates equation 1 (with offsets the controller knows) from the commands at 40 Hz.
struct ModelSim {
  VehicleModel m;
  Eigen::Vector3f p = Eigen::Vector3f::Zero(), v = Eigen::Vector3f::Zero();
  float psi = 0.0f;
  void step(const AttitudeSetpoint& u, float dt) {
    const float axb = m.pitch.k * u.pitch_rad + m.pitch.b;
    const float ayb = m.roll.k * u.roll_rad + m.roll.b;
    const Eigen::Vector3f a(std::cos(psi) * axb - std::sin(psi) * ayb, std::sin(psi) * axb + std::cos(psi) * ayb,
                            m.thrust.k * u.thrust + m.thrust.b);
    p += v * dt + 0.5f * a * dt * dt;
    v += a * dt;
    psi = wrap_angle(psi + (m.yaw.k * u.yaw_rate_radps + m.yaw.b) * dt);
  }
  NavState nav(TimeUs t) const {
    NavState n = hover_at(p, psi);
    n.velocity_mps = v;
    n.stamp = t;
    return n;
  }
};

TEST(Controller, ClosedLoopReachesPositionAndHeadingSetpoints) {
  VehicleModel model;
  model.pitch.b = 0.3f;
  model.roll.b = -0.2f;
  model.thrust = {18.0f, -9.5f};
  model.yaw.b = 0.05f;
  const Result<ControllerParams> params = design_controller(model, LqrWeights{}, 0.025);
  ASSERT_TRUE(params.ok());
  const Controller c(params.value());
  ModelSim sim;
  sim.m = model;
  sim.p = Eigen::Vector3f(0, 0, 0.5f);
  const GuidanceSetpoint sp = hold({2.0f, -1.0f, 1.0f}, 1.2f);
  uint32_t seen = 0;
  for (int i = 0; i < 800; ++i) {  // 20 s
    const ControlOutput o = c.step(sim.nav(TimeUs::from_us(i * 25000)), sp);
    seen |= o.flags;
    sim.step(o.command, 0.025f);
  }
  EXPECT_LT((sim.p - sp.position_m).norm(), 0.01f);
  EXPECT_LT(sim.v.norm(), 0.01f);
  EXPECT_NEAR(angle_diff(sim.psi, sp.heading_rad), 0.0f, 0.01f);
  EXPECT_NE(seen & control_flag::kClippedError, 0u);  // a 2.2 m step is clipped to 1.5 m
}

TEST(Controller, VelocityModeTracksVelocityAndHoldsAltitude) {
  const Controller c;
  ModelSim sim;
  sim.p = Eigen::Vector3f(0, 0, 1.0f);
  GuidanceSetpoint sp;
  sp.mode = GuidanceSetpoint::Mode::kVelocity;
  sp.velocity_mps = Eigen::Vector3f(0.5f, 0.2f, 0.0f);
  sp.position_m = Eigen::Vector3f(100.0f, 100.0f, 1.2f);  // x, y ignored in this mode
  sp.heading_rad = 0.5f;
  for (int i = 0; i < 600; ++i) sim.step(c.step(sim.nav(TimeUs::from_us(i * 25000)), sp).command, 0.025f);
  EXPECT_NEAR(sim.v.x(), 0.5f, 0.01f);
  EXPECT_NEAR(sim.v.y(), 0.2f, 0.01f);
  EXPECT_NEAR(sim.p.z(), 1.2f, 0.01f);
}

TEST(Controller, SaturatesEveryCommandAndFlagsIt) {
  const Controller c;
  const ControllerParams& p = c.params();
  NavState far = hover_at({0, 0, 1});
  far.velocity_mps = Eigen::Vector3f(-5.0f, 5.0f, -5.0f);
  const ControlOutput o = c.step(far, hold({50.0f, -50.0f, 20.0f}, 3.0f));
  EXPECT_FLOAT_EQ(o.command.pitch_rad, p.max_tilt_rad);
  EXPECT_FLOAT_EQ(o.command.roll_rad, -p.max_tilt_rad);
  EXPECT_FLOAT_EQ(o.command.thrust, p.max_thrust);
  EXPECT_FLOAT_EQ(std::abs(o.command.yaw_rate_radps), p.max_yaw_rate_radps);
  using namespace control_flag;
  EXPECT_EQ(o.flags & (kSatPitch | kSatRoll | kSatThrust | kSatYawRate | kClippedError),
            kSatPitch | kSatRoll | kSatThrust | kSatYawRate | kClippedError);
  NavState falling = hover_at({0, 0, 30.0f});
  const ControlOutput low = c.step(falling, hold({0, 0, 0.0f}));
  EXPECT_FLOAT_EQ(low.command.thrust, p.min_thrust);
  EXPECT_NE(low.flags & kSatThrust, 0u);
}

TEST(Controller, NonFiniteOrInvalidInputsGiveTheSafeOutput) {
  const Controller c;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto expect_safe = [&](const ControlOutput& o, uint32_t flag) {
    EXPECT_EQ(o.command.pitch_rad, 0.0f);
    EXPECT_EQ(o.command.roll_rad, 0.0f);
    EXPECT_EQ(o.command.yaw_rate_radps, 0.0f);
    EXPECT_FLOAT_EQ(o.command.thrust, 0.5f);
    EXPECT_EQ(o.flags, flag);
  };
  NavState n = hover_at({0, 0, 1});
  n.valid = false;
  expect_safe(c.step(n, hold({0, 0, 1})), control_flag::kInvalidNav);
  for (int field = 0; field < 3; ++field) {
    NavState bad = hover_at({0, 0, 1});
    if (field == 0) bad.position_m.y() = nan;
    if (field == 1) bad.velocity_mps.z() = inf;
    if (field == 2) bad.heading_rad = nan;
    expect_safe(c.step(bad, hold({0, 0, 1})), control_flag::kInvalidNav);
    GuidanceSetpoint sp = hold({0, 0, 1});
    if (field == 0) sp.position_m.x() = nan;
    if (field == 1) sp.velocity_mps.y() = -inf;
    if (field == 2) sp.heading_rad = nan;
    expect_safe(c.step(hover_at({0, 0, 1}), sp), control_flag::kInvalidSetpoint);
  }
  // Huge but finite inputs still give finite, saturated commands.
  const ControlOutput o = c.step(hover_at({3e38f, -3e38f, 3e38f}, 1e30f), hold({-3e38f, 3e38f, -3e38f}));
  EXPECT_TRUE(std::isfinite(o.command.pitch_rad) && std::isfinite(o.command.roll_rad) &&
              std::isfinite(o.command.thrust) && std::isfinite(o.command.yaw_rate_radps));
  // Invalid parameters are refused; a controller built with them uses the defaults.
  ControllerParams bad = default_controller_params();
  bad.max_tilt_rad = nan;
  Controller c2(bad);
  EXPECT_EQ(c2.set_params(bad), Status::kInvalidArgument);
  EXPECT_EQ(c2.params().max_tilt_rad, default_controller_params().max_tilt_rad);
  EXPECT_EQ(c2.set_params(ControllerParams{}), Status::kInvalidArgument);  // zero gains
}

// Property: whatever finite NavState and set-point arrive (ordinary, huge, tiny, subnormal, any
// heading, either mode), the command is finite and inside its limits, and any flagged safe
// output is exactly level at hover thrust. Errors that overflow float (a state at 3e38 m and
// a set-point at -3e38 m: the difference is inf) give the safe output flagged kInvalidNav, as
// the header documents. 5000 draws with a fixed seed.
TEST(Controller, AnyFiniteInputGivesABoundedFiniteCommand) {
  const Controller c;
  const ControllerParams& p = c.params();
  const float fmax = std::numeric_limits<float>::max();
  const float pool[] = {0.0f, 1.0f, -2.5f, 1e-40f, -1e-30f, 1e4f, -1e6f, 1e30f, -1e30f, fmax, -fmax};
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> which(0, std::size(pool) - 1);
  std::uniform_real_distribution<float> ordinary(-3.0f, 3.0f);
  auto draw = [&] { return rng() % 2 == 0 ? ordinary(rng) : pool[which(rng)]; };
  int safe = 0;
  for (int i = 0; i < 5000; ++i) {
    NavState n = hover_at({draw(), draw(), draw()}, draw());
    n.velocity_mps = Eigen::Vector3f(draw(), draw(), draw());
    GuidanceSetpoint sp = hold({draw(), draw(), draw()}, draw());
    sp.velocity_mps = Eigen::Vector3f(draw(), draw(), draw());
    sp.mode = rng() % 2 == 0 ? GuidanceSetpoint::Mode::kPosition : GuidanceSetpoint::Mode::kVelocity;
    const ControlOutput o = c.step(n, sp);
    const AttitudeSetpoint& a = o.command;
    ASSERT_TRUE(std::isfinite(a.pitch_rad) && std::isfinite(a.roll_rad) && std::isfinite(a.thrust) &&
                std::isfinite(a.yaw_rate_radps)) << "draw " << i;
    EXPECT_LE(std::abs(a.pitch_rad), p.max_tilt_rad);
    EXPECT_LE(std::abs(a.roll_rad), p.max_tilt_rad);
    EXPECT_GE(a.thrust, p.min_thrust);
    EXPECT_LE(a.thrust, p.max_thrust);
    EXPECT_LE(std::abs(a.yaw_rate_radps), p.max_yaw_rate_radps);
    EXPECT_EQ(o.flags & control_flag::kInvalidSetpoint, 0u);
    if ((o.flags & control_flag::kInvalidNav) != 0) {
      ++safe;
      EXPECT_EQ(o.flags, control_flag::kInvalidNav);
      EXPECT_EQ(a.pitch_rad, 0.0f);
      EXPECT_EQ(a.roll_rad, 0.0f);
      EXPECT_EQ(a.yaw_rate_radps, 0.0f);
      EXPECT_FLOAT_EQ(a.thrust, 0.5f);
    }
  }
  EXPECT_GT(safe, 0);  // the overflowing pairs were drawn
  const ControlOutput o = c.step(hover_at({fmax, 0, 1}), hold({-fmax, 0, 1}));
  EXPECT_EQ(o.flags, control_flag::kInvalidNav);
  EXPECT_FLOAT_EQ(o.command.thrust, 0.5f);
}

TEST(Controller, StepDoesNotAllocate) {
  const Controller c;
  ModelSim sim;
  alloc_guard::Scope guard;
  for (int i = 0; i < 100; ++i)
    sim.step(c.step(sim.nav(TimeUs::from_us(i * 25000)), hold({1, 1, 1}, 1)).command, 0.025f);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::control
