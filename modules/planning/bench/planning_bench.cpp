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

namespace {
using namespace kestrel;
using namespace kestrel::planning;

struct Seg {
  float ax, ay, bx, by;
};
// A 15 x 10 m hall split by a wall with a 1 m door, a pillar and a desk.
constexpr Seg kHall[] = {{0, 0, 15, 0},   {15, 0, 15, 10}, {15, 10, 0, 10},  {0, 10, 0, 0},     {7, 0, 7, 4.5f},
                         {7, 5.5f, 7, 10}, {3, 3, 3.4f, 3}, {3.4f, 3, 3.4f, 3.4f}, {3.4f, 3.4f, 3, 3.4f},
                         {3, 3.4f, 3, 3},  {10, 7, 12, 7}, {12, 7, 12, 8},   {12, 8, 10, 8},    {10, 8, 10, 7}};

LaserScan scan_at(const Pose2& at, uint16_t beams, float fov, uint16_t max_range_mm) {
  LaserScan s;
  s.beam_count = beams;
  s.angle_step_rad = fov / static_cast<float>(beams - 1);
  s.first_angle_rad = -0.5f * fov;
  s.max_range_mm = max_range_mm;
  for (uint16_t i = 0; i < beams; ++i) {
    const float a = at.theta + s.angle_of(i), dx = std::cos(a), dy = std::sin(a);
    float best = 1e9f;
    for (const Seg& g : kHall) {
      const float ex = g.bx - g.ax, ey = g.by - g.ay, den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-9f) continue;
      const float wx = g.ax - at.x, wy = g.ay - at.y;
      const float t = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
      if (t > 0.02f && u >= 0 && u <= 1 && t < best) best = t;
    }
    s.range_mm[i] = best * 1000.0f < max_range_mm ? static_cast<uint16_t>(best * 1000.0f) : range_code::kNoReturn;
  }
  return s;
}

struct Laser {
  uint16_t beams;
  float fov;
  uint16_t max_range_mm;
};
constexpr Laser kUrg{683, 4.1888f, 4000}, kUtm{1081, 4.7124f, 30000};

// The hall drawn from a walk along it and through the door.
std::unique_ptr<OccupancyGrid> drawn_hall(const Laser& l) {
  auto grid = std::make_unique<OccupancyGrid>();
  if (grid->configure(GridParams{}, {2, 2}, l.beams, -0.5f * l.fov, l.fov / static_cast<float>(l.beams - 1)) != Status::kOk)
    return nullptr;
  for (int k = 0; k < 60; ++k) {
    const float t = static_cast<float>(k) / 59.0f;
    const Pose2 at{1.5f + 12.0f * t, 5.0f + 3.0f * std::sin(6.0f * t), 0.3f * static_cast<float>(k)};
    const auto s = std::make_unique<LaserScan>(scan_at(at, l.beams, l.fov, l.max_range_mm));
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
  const auto s = std::make_unique<LaserScan>(scan_at(at, l.beams, l.fov, l.max_range_mm));
  for (auto _ : state) benchmark::DoNotOptimize(grid->draw(*s, at));
}
BENCHMARK_CAPTURE(BM_draw, urg04lx_683, kUrg)->Name("planning/draw/urg04lx_683");
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

// The search from the walk's start, and the path from there to the far room's corner.
void BM_search_and_path(benchmark::State& state) {
  auto grid = drawn_hall(kUrg);
  auto dist = std::make_unique<ObstacleDistance>();
  auto search = std::make_unique<GridSearch>();
  auto cells = std::make_unique<PathCells>();
  auto points = std::make_unique<PathPoints>();
  const CellBox box = grid->drawn().grown(2);
  dist->compute(*grid, box);
  Cell start, goal;
  if (!grid->geometry().to_cell(1.5f, 5.0f, start) || !grid->geometry().to_cell(13.5f, 8.5f, goal)) {
    state.SkipWithError("cells");
    return;
  }
  for (auto _ : state) {
    if (search->run(*grid, *dist, box, start, default_costs()) != Status::kOk) state.SkipWithError("search");
    (void)search->path_to(goal, *cells);
    (void)simplify_path(*grid, *dist, *cells, *points);
    benchmark::DoNotOptimize(points->size());
  }
  state.counters["path_cells"] = static_cast<double>(cells->size());
  state.counters["legs"] = static_cast<double>(points->size());
  state.counters["peak_open"] = static_cast<double>(search->peak_open());
}
BENCHMARK(BM_search_and_path)->Name("planning/search_and_path/hall_15x10m");

}  // namespace
