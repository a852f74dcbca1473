// Hot primitives of core: fixed-point arithmetic, the indexed heap, and the scan's check of a
// straight way (the flight home's shortcut, one check per guidance step).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "kestrel/core/clear_path.hpp"
#include "kestrel/core/fixed_point.hpp"
#include "kestrel/core/min_heap.hpp"
#include "synthetic_world.hpp"

namespace {

void BM_FixedMultiplyAccumulate(benchmark::State& state) {
  kestrel::Q16 acc{};
  const kestrel::Q16 a = kestrel::Q16::from_double(0.731);
  kestrel::Q16 b = kestrel::Q16::from_double(1.25);
  for (auto _ : state) {
    for (int i = 0; i < 1024; ++i) acc += a * b;
    benchmark::DoNotOptimize(acc);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 1024);
}
BENCHMARK(BM_FixedMultiplyAccumulate)->Name("core/fixed_mac_1024");

void BM_MinHeapPushPop(benchmark::State& state) {
  static kestrel::MinHeap<int32_t, 1024> heap;
  uint32_t seed = 1;
  for (auto _ : state) {
    heap.clear();
    for (uint16_t i = 0; i < 1024; ++i) {
      seed = seed * 1664525u + 1013904223u;
      (void)heap.push(i, static_cast<int32_t>(seed >> 8));
    }
    while (!heap.empty()) benchmark::DoNotOptimize(heap.pop());
  }
  state.SetItemsProcessed(state.iterations() * 1024);
}
BENCHMARK(BM_MinHeapPushPop)->Name("core/min_heap_1024");

// gt-building's corridor beside the north-west door (y 7..9, the door at x 5..6.2), the
// vehicle held 0.43 m off its north wall facing west, home 2.6 m down the corridor: every beam
// of the corridor's walls is within the path's reach, the worst case of a clear way.
void straight_path_clear_corridor(benchmark::State& state, const kestrel::test::LaserModel& laser) {
  kestrel::test::SegmentWorld w;
  w.add(0, 7, 12, 7);
  w.add(0, 9, 5, 9);
  w.add(6.2, 9, 12, 9);
  w.add(0, 7, 0, 9);
  const kestrel::Pose2 at{4.1f, 8.57f, 3.14159265f};
  const kestrel::LaserScan scan = w.scan(laser, at.x, at.y, at.theta);
  bool clear = false;
  for (auto _ : state) {
    clear = kestrel::straight_path_clear(scan, at, {1.5f, 8.0f}, 0.45f);
    benchmark::DoNotOptimize(clear);
  }
  state.counters["clear"] = clear ? 1 : 0;
}
void BM_StraightPathClearUrg(benchmark::State& s) {
  straight_path_clear_corridor(s, kestrel::test::LaserModel::urg04lx());
}
void BM_StraightPathClearUtm(benchmark::State& s) {
  straight_path_clear_corridor(s, kestrel::test::LaserModel::utm30lx());
}
BENCHMARK(BM_StraightPathClearUrg)->Name("core/straight_path_clear/urg04lx_682");
BENCHMARK(BM_StraightPathClearUtm)->Name("core/straight_path_clear/utm30lx_1081");

}  // namespace
