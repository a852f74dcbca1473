#pragma once
// Discrete-time linear quadratic regulator by fixed-point iteration of the discrete algebraic
// Riccati equation (paper 000 section 4 used Matlab's LQR toolbox for the same gains):
//   P <- Q + A'PA - A'PB (R + B'PB)^-1 B'PA,   K = (R + B'PB)^-1 B'PA,   u = -K x.
// Fixed-size Eigen in double precision; the iteration stops when P changes by less than `tol`
// relative to its size. An unstabilisable pair or bad weights make P grow without bound or go
// non-finite: that is reported (kNotFinite, kTimeout), never returned as gains.
//
// API
//   Status solve_dlqr<N, M>(A, B, Q, R, K, options)
//   the second-order model: double_integrator(dt, k) -> {A, B} with input in command units
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "kestrel/core/status.hpp"

namespace kestrel::control {

struct DlqrOptions {
  int max_iterations = 100000;
  double tol = 1e-12;
};

template <int N, int M>
Status solve_dlqr(const Eigen::Matrix<double, N, N>& A, const Eigen::Matrix<double, N, M>& B,
                  const Eigen::Matrix<double, N, N>& Q, const Eigen::Matrix<double, M, M>& R,
                  Eigen::Matrix<double, M, N>& K, const DlqrOptions& options = {}) {
  if (!A.allFinite() || !B.allFinite() || !Q.allFinite() || !R.allFinite()) return Status::kNotFinite;
  // Q must be positive semi-definite, R positive definite
  // (Cholesky without pivoting: Eigen's pivoting LDLT trips GCC 12's array-bounds check at 1x1.)
  if (Eigen::LLT<Eigen::Matrix<double, M, M>>(R).info() != Eigen::Success) return Status::kInvalidArgument;
  const double q_eps = 1e-12 * (1.0 + Q.cwiseAbs().maxCoeff());
  const Eigen::Matrix<double, N, N> Q_shift = Q + q_eps * Eigen::Matrix<double, N, N>::Identity();
  if (Eigen::LLT<Eigen::Matrix<double, N, N>>(Q_shift).info() != Eigen::Success) return Status::kInvalidArgument;
  Eigen::Matrix<double, N, N> P = Q;
  K.setZero();
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Matrix<double, M, M> S = R + B.transpose() * P * B;
    const Eigen::Matrix<double, M, N> BtPA = B.transpose() * P * A;
    // Column by column: a matrix right-hand side goes through Eigen's blocked triangular
    // solve, whose scratch is an alloca of unbounded size on the stack (the budget checker
    // refuses those); a vector right-hand side does not.
    const Eigen::LLT<Eigen::Matrix<double, M, M>> llt(S);
    Eigen::Matrix<double, M, N> Kn;
    for (int c = 0; c < N; ++c) {
      const Eigen::Matrix<double, M, 1> rhs = BtPA.col(c);
      Kn.col(c) = llt.solve(rhs);
    }
    Eigen::Matrix<double, N, N> Pn = Q + A.transpose() * P * A - BtPA.transpose() * Kn;
    Pn = 0.5 * (Pn + Pn.transpose());
    if (!Pn.allFinite() || Pn.norm() > 1e30) return Status::kNotFinite;
    const double change = (Pn - P).norm();
    P = Pn;
    K = Kn;
    if (change <= options.tol * (1.0 + P.norm())) return Status::kOk;
  }
  return Status::kTimeout;
}

// Paper 000 equation 1 for one axis, sampled every dt seconds with the command held:
// state [s, s'], input u, s'' = k u (the offset b is cancelled by the feed-forward).
struct DiscreteModel2 {
  Eigen::Matrix2d A;
  Eigen::Vector2d B;
};

inline DiscreteModel2 double_integrator(double dt, double k) {
  DiscreteModel2 m;
  m.A << 1.0, dt, 0.0, 1.0;
  m.B << 0.5 * k * dt * dt, k * dt;
  return m;
}

}  // namespace kestrel::control
