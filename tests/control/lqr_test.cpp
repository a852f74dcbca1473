// Discrete LQR by Riccati iteration: closed form in the scalar case, stabilising gains for the
// second-order model of paper 000 equation 1, and refusals for bad problems.
#include "kestrel/control/lqr.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "kestrel/control/controller_params.hpp"

namespace kestrel::control {
namespace {

// Scalar integrator x' = x + b u: P solves b^2 P^2 - q b^2 P - q r = 0.
TEST(Dlqr, ScalarCaseMatchesTheClosedForm) {
  const double b = 0.05, q = 2.0, r = 0.5;
  const Eigen::Matrix<double, 1, 1> A(1.0), B(b), Q(q), R(r);
  Eigen::Matrix<double, 1, 1> K;
  ASSERT_EQ((solve_dlqr<1, 1>(A, B, Q, R, K)), Status::kOk);
  const double P = (q * b * b + std::sqrt(q * q * b * b * b * b + 4.0 * b * b * q * r)) / (2.0 * b * b);
  EXPECT_NEAR(K(0), b * P / (r + b * b * P), 1e-9);
}

// GIVEN the nominal model at 40 Hz (and a slower 10 Hz loop, and a weaker vehicle), THEN the
// LQR gains put every closed-loop eigenvalue of A - B K strictly inside the unit circle.
TEST(Dlqr, GainsStabiliseTheSecondOrderModel) {
  for (const double dt : {0.025, 0.1}) {
    for (const double k : {kGravity * 1.0, kGravity * 0.5, 2.0 * kGravity}) {
      const DiscreteModel2 m = double_integrator(dt, k);
      Eigen::Matrix<double, 1, 2> K;
      ASSERT_EQ((solve_dlqr<2, 1>(m.A, m.B, Eigen::Vector2d(4.0, 1.0).asDiagonal(),
                                  Eigen::Matrix<double, 1, 1>(40.0), K)),
                Status::kOk);
      const Eigen::Matrix2d closed = m.A - m.B * K;
      const Eigen::EigenSolver<Eigen::Matrix2d> es(closed);
      for (int i = 0; i < 2; ++i) {
        EXPECT_LT(std::abs(es.eigenvalues()(i)), 0.9999) << "dt " << dt << " k " << k;
      }
      // The open loop is not stable (double eigenvalue 1): the gains are doing the work.
      EXPECT_GT(K(0), 0.0);
      EXPECT_GT(K(1), 0.0);
    }
  }
}

TEST(Dlqr, DesignedControllerIsStableOnEveryAxis) {
  const Result<ControllerParams> r = design_controller(VehicleModel{}, LqrWeights{}, 0.025);
  ASSERT_TRUE(r.ok());
  const ControllerParams& p = r.value();
  EXPECT_EQ(validate(p), Status::kOk);
  const struct {
    double k;
    float kp, kd;
  } axes[] = {{p.model.pitch.k, p.gain_x_p, p.gain_x_d}, {p.model.roll.k, p.gain_y_p, p.gain_y_d},
              {p.model.thrust.k, p.gain_z_p, p.gain_z_d}};
  for (const auto& a : axes) {
    const DiscreteModel2 m = double_integrator(0.025, a.k);
    Eigen::Matrix<double, 1, 2> K(a.kp, a.kd);
    const Eigen::EigenSolver<Eigen::Matrix2d> es(m.A - m.B * K);
    for (int i = 0; i < 2; ++i) EXPECT_LT(std::abs(es.eigenvalues()(i)), 0.9999);
  }
  EXPECT_LT(std::abs(1.0 - p.model.yaw.k * 0.025 * p.gain_yaw), 1.0);
  // The default controller is this design.
  const ControllerParams d = default_controller_params();
  EXPECT_EQ(d.gain_x_p, p.gain_x_p);
  EXPECT_EQ(d.gain_yaw, p.gain_yaw);
}

TEST(Dlqr, RefusesBadProblems) {
  const DiscreteModel2 m = double_integrator(0.025, kGravity);
  Eigen::Matrix<double, 1, 2> K;
  const Eigen::Matrix2d Q = Eigen::Matrix2d::Identity();
  EXPECT_EQ((solve_dlqr<2, 1>(m.A, m.B, Q, Eigen::Matrix<double, 1, 1>(0.0), K)), Status::kInvalidArgument);
  EXPECT_EQ((solve_dlqr<2, 1>(m.A, m.B, -Q, Eigen::Matrix<double, 1, 1>(1.0), K)), Status::kInvalidArgument);
  Eigen::Matrix2d A_nan = m.A;
  A_nan(0, 1) = std::nan("");
  EXPECT_EQ((solve_dlqr<2, 1>(A_nan, m.B, Q, Eigen::Matrix<double, 1, 1>(1.0), K)), Status::kNotFinite);
  // Unstable and uncontrollable (B = 0, eigenvalue 1.5): P grows without bound.
  Eigen::Matrix2d A_bad = Eigen::Matrix2d::Identity() * 1.5;
  EXPECT_NE((solve_dlqr<2, 1>(A_bad, Eigen::Vector2d::Zero(), Q, Eigen::Matrix<double, 1, 1>(1.0), K)), Status::kOk);
  EXPECT_EQ(design_controller(VehicleModel{}, LqrWeights{}, 0.0).status(), Status::kInvalidArgument);
  VehicleModel reversed;
  reversed.pitch.k = -kGravity;
  EXPECT_EQ(design_controller(reversed, LqrWeights{}, 0.025).status(), Status::kInvalidArgument);
}

}  // namespace
}  // namespace kestrel::control
