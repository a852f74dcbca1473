// The grid planner's costs (level 3 of the frontier explorer): drawing one scan, the obstacle
// distance, the search and the path over a 15 x 10 m hall seen from a walk through it. Set-up
// allocates (the grids are large); the timed loops do not.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "kestrel/planning/grid_search.hpp"
#include "kestrel/planning/obstacle_distance.hpp"
#include "kestrel/planning/occupancy_grid.hpp"
#include "kestrel/planning/path_simplify.hpp"
#include "synthetic_world.hpp"

namespace {
using namespace kestrel;
using namespace kestrel::planning;

// A 15 x 10 m hall split by a wall with a 1 m door, a pillar and a desk.
test::SegmentWorld hall() {
  test::SegmentWorld w;
  w.add_box(0, 0, 15, 10);
  w.add(7, 0, 7, 4.5);
  w.add(7, 5.5, 7, 10);
  w.add_box(3, 3, 3.4, 3.4);
  w.add_box(10, 7, 12, 8);
  return w;
}

using Laser = test::LaserModel;
const Laser kUrg = Laser::urg04lx(), kUtm = Laser::utm30lx();

LaserScan scan_at(const Pose2& at, const Laser& l) { return hall().scan(l, at.x, at.y, at.theta); }

// Benchmarks only, never flown: the grids, scans and planners below are allocated in set-up,
// before each timed loop, because they are too large for the benchmark thread's stack.
// The hall drawn from a walk along it and through the door.
std::unique_ptr<OccupancyGrid> drawn_hall(const Laser& l) {
  auto grid = std::make_unique<OccupancyGrid>();
  if (grid->configure(GridParams{}, {2, 2}, l.beams, static_cast<float>(l.first_angle()),
                      static_cast<float>(l.step())) != Status::kOk)
    return nullptr;
  for (int k = 0; k < 60; ++k) {
    const float t = static_cast<float>(k) / 59.0f;
    const Pose2 at{1.5f + 12.0f * t, 5.0f + 3.0f * std::sin(6.0f * t), 0.3f * static_cast<float>(k)};
    const auto s = std::make_unique<LaserScan>(scan_at(at, l));
    (void)grid->draw(*s, at);
  }
  return grid;
}

void BM_draw(benchmark::State& state, Laser l) {
  auto grid = drawn_hall(l);
  if (!grid) {
    state.SkipWithError("configure");
    return;
  }
  const Pose2 at{5.0f, 4.0f, 0.3f};
  const auto s = std::make_unique<LaserScan>(scan_at(at, l));
  for (auto _ : state) benchmark::DoNotOptimize(grid->draw(*s, at));
}
BENCHMARK_CAPTURE(BM_draw, urg04lx_682, kUrg)->Name("planning/draw/urg04lx_682");
BENCHMARK_CAPTURE(BM_draw, utm30lx_1081, kUtm)->Name("planning/draw/utm30lx_1081");

SearchCosts default_costs() {
  return {ObstacleDistance::units_of(0.3f, 0.12f), ObstacleDistance::units_of(0.9f, 0.12f), 30};
}

void BM_distance(benchmark::State& state) {
  auto grid = drawn_hall(kUrg);
  auto dist = std::make_unique<ObstacleDistance>();
  for (auto _ : state) {
    dist->compute(*grid, grid->drawn().grown(2));
    benchmark::DoNotOptimize(dist->at(10, 10));
  }
}
BENCHMARK(BM_distance)->Name("planning/obstacle_distance/hall_15x10m");

// The search from the walk's start, and the path from there through the door to the far room.
void BM_search_and_path(benchmark::State& state) {
  auto grid = drawn_hall(kUrg);
  auto dist = std::make_unique<ObstacleDistance>();
  auto search = std::make_unique<GridSearch>();
  auto cells = std::make_unique<PathCells>();
  auto points = std::make_unique<PathPoints>();
  const CellBox box = grid->drawn().grown(2);
  dist->compute(*grid, box);
  Cell start, goal;
  if (!grid->geometry().to_cell(1.5f, 5.0f, start) || !grid->geometry().to_cell(12.5f, 4.0f, goal)) {
    state.SkipWithError("cells");
    return;
  }
  for (auto _ : state) {
    if (search->run(*grid, *dist, box, start, default_costs()) != Status::kOk) state.SkipWithError("search");
    if (search->path_to(goal, *cells) != Status::kOk) state.SkipWithError("no path");
    (void)simplify_path(*grid, *dist, *cells, *points);
    benchmark::DoNotOptimize(points->size());
  }
  state.counters["path_cells"] = static_cast<double>(cells->size());
  state.counters["legs"] = static_cast<double>(points->size());
  state.counters["peak_open"] = static_cast<double>(search->peak_open());
}
BENCHMARK(BM_search_and_path)->Name("planning/search_and_path/hall_15x10m");

}  // namespace
