// The compact SLAM's cost per scan (level 3): the Monte Carlo search, the curvature test and
// the drawing, on a map that already holds the room. Set-up allocates (the 1 MiB map); the
// timed loop does not.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "kestrel/slam/compact_slam.hpp"

namespace {
using namespace kestrel;
using namespace kestrel::slam;

// An 8 x 6 m room with a doorway and a pillar, as returns of a laser of `beams` beams over
// `fov` radians and `reach` metres seen from `at` (sensor frame).
scan_matching::ScanPoints room_points(const Pose2& at, int beams, float fov, float reach) {
  struct Seg { float ax, ay, bx, by; };
  const Seg segs[] = {{-4, -3, 4, -3}, {4, -3, 4, 3}, {4, 3, 0.5f, 3}, {-0.5f, 3, -4, 3}, {-4, 3, -4, -3},
                      {1.5f, -1.2f, 2.1f, -1.2f}, {2.1f, -1.2f, 2.1f, -0.6f}, {2.1f, -0.6f, 1.5f, -0.6f},
                      {1.5f, -0.6f, 1.5f, -1.2f}};
  scan_matching::ScanPoints p;
  p.angle_step_rad = fov / static_cast<float>(beams);
  for (int i = 0; i < beams; ++i) {
    const float rel = -0.5f * fov + p.angle_step_rad * (static_cast<float>(i) + 0.5f);
    const float a = at.theta + rel, dx = std::cos(a), dy = std::sin(a);
    float best = 1e9f;
    for (const Seg& g : segs) {
      const float ex = g.bx - g.ax, ey = g.by - g.ay, den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-9f) continue;
      const float wx = g.ax - at.x, wy = g.ay - at.y;
      const float t = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
      if (t > 0.02f && u >= 0 && u <= 1 && t < best) best = t;
    }
    if (best >= reach) continue;
    p.x[p.count] = best * std::cos(rel);
    p.y[p.count] = best * std::sin(rel);
    p.range_mm[p.count] = static_cast<uint16_t>(best * 1000.0f);
    p.beam[p.count] = static_cast<uint16_t>(i);
    ++p.count;
  }
  return p;
}

void run(benchmark::State& state, int beams, float fov, float reach) {
  // Benchmark set-up, never flown: the map, the SLAM and the point sets are allocated before
  // the timed loop, because they are too large for the benchmark thread's stack.
  auto map = std::make_unique<SlamMap>();
  auto slam = std::make_unique<CompactSlam>(*map);
  SlamParams params;
  if (slam->configure(params) != Status::kOk) {
    state.SkipWithError("configure");
    return;
  }
  // Draw the room from a few poses, then match a scan taken between them from a prior 5 cm
  // and a degree off: the search does its full count of candidates every time.
  for (int k = 0; k <= static_cast<int>(params.warmup_scans) + 8; ++k) {
    const Pose2 at{-1.0f + 0.3f * static_cast<float>(k % 8), 0.2f * static_cast<float>(k % 3),
                   0.4f * static_cast<float>(k)};
    const auto pts = std::make_unique<scan_matching::ScanPoints>(room_points(at, beams, fov, reach));
    (void)slam->process(*pts, at);
  }
  const Pose2 truth{0.4f, -0.3f, 0.7f};
  const auto pts = std::make_unique<scan_matching::ScanPoints>(room_points(truth, beams, fov, reach));
  const Pose2 prior{truth.x + 0.04f, truth.y - 0.03f, truth.theta + 0.017f};
  for (auto _ : state) benchmark::DoNotOptimize(slam->process(*pts, prior));
}

void BM_SlamUrg(benchmark::State& state) { run(state, 682, 4.18879f, 4.0f); }
void BM_SlamUtm(benchmark::State& state) { run(state, 1081, 4.71239f, 30.0f); }
BENCHMARK(BM_SlamUrg)->Name("slam/process_urg04lx");
BENCHMARK(BM_SlamUtm)->Name("slam/process_utm30lx");

}  // namespace
