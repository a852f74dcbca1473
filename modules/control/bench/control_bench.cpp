// The controller's per-cycle cost: one LQR state-feedback step from NavState to AttitudeSetpoint.
#include <benchmark/benchmark.h>

#include "kestrel/control/controller.hpp"

namespace {

void BM_LqrStep(benchmark::State& state) {
  const kestrel::control::Controller controller;
  kestrel::NavState nav;
  nav.valid = true;
  nav.position_m = Eigen::Vector3f(0.3f, -0.2f, 0.9f);
  nav.velocity_mps = Eigen::Vector3f(0.1f, 0.05f, 0.0f);
  nav.heading_rad = 0.4f;
  kestrel::GuidanceSetpoint sp;
  sp.position_m = Eigen::Vector3f(1.0f, 0.0f, 1.0f);
  float t = 0;
  for (auto _ : state) {
    nav.position_m.x() = 0.3f + 1e-6f * t;
    t += 1.0f;
    benchmark::DoNotOptimize(controller.step(nav, sp));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LqrStep)->Name("control/lqr_step");

}  // namespace
