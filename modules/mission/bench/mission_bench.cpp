// The flight home's stall step (mission_controller.hpp, trail_alignment.hpp): the newest scan
// drawn as free space and the trail's next eight breadcrumbs laid onto it. This runs once each
// return_realign_s while the way home is stalled, on top of that guidance step's usual work.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>

#include "kestrel/core/scan_free_space.hpp"
#include "kestrel/mission/trail_alignment.hpp"
#include "synthetic_world.hpp"

namespace {

using kestrel::Point2;
using kestrel::Pose2;

// gt-building's corridor (test::corridor_with_a_door): held off the north wall beside the door,
// the trail drawn 0.8 m east of where it lies now (the stall of gt-building's URG-04LX seed 59).
void BM_TrailAlignment(benchmark::State& state, const kestrel::test::LaserModel& laser) {
  const kestrel::test::SegmentWorld world = kestrel::test::corridor_with_a_door();
  const Pose2 at{4.6f, 8.55f, static_cast<float>(M_PI / 2)};
  const kestrel::LaserScan scan = world.scan(laser, at.x, at.y, at.theta);
  const std::array<Point2, 8> ahead{{{4.8f, 8.9f}, {4.8f, 9.3f}, {4.8f, 9.7f}, {4.7f, 10.1f},
                                     {4.6f, 10.5f}, {4.6f, 10.9f}, {4.6f, 11.3f}, {4.5f, 11.7f}}};
  static kestrel::ScanFreeSpace free_space;  // the mission's member: not on the stack
  bool found = false;
  for (auto _ : state) {
    (void)free_space.build(scan, at, 0.3f, 0.5f);
    Point2 offset;
    found = kestrel::mission::find_trail_offset(free_space, ahead, 0.8f, {}, 0.45f, offset);
    benchmark::DoNotOptimize(offset);
  }
  if (!found) state.SkipWithError("no offset found: the case no longer measures a realignment");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_TrailAlignment, urg04lx_682, kestrel::test::LaserModel::urg04lx())
    ->Name("mission/trail_alignment/urg04lx_682");
BENCHMARK_CAPTURE(BM_TrailAlignment, utm30lx_1081, kestrel::test::LaserModel::utm30lx())
    ->Name("mission/trail_alignment/utm30lx_1081");

}  // namespace
