// Hot primitives of core: fixed-point arithmetic and the indexed heap.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "kestrel/core/fixed_point.hpp"
#include "kestrel/core/min_heap.hpp"

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

}  // namespace
