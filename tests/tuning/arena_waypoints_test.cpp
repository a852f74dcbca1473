// The waypoints kestrel-tune-ekf and kestrel-sysid fly (tuning::arena_waypoints) are also an
// example file, so that a flight the README reports on can be flown with kestrel-sim alone:
// the two must stay the same waypoints.
#include <gtest/gtest.h>

#include <string>

#include "kestrel/autonomy/stack_config.hpp"
#include "kestrel/flight/autonomy_mission.hpp"
#include "kestrel/tuning/flight_log.hpp"

namespace kestrel::tuning {
namespace {

TEST(ArenaWaypoints, TheExampleFileHoldsTheTuningFlightsWaypoints) {
  autonomy::StackConfig stack;
  const std::string path = std::string(KESTREL_SOURCE_DIR) + "/host_sim/flight/examples/iarc_arena_tune.waypoints";
  ASSERT_EQ(flight::load_waypoints(path, stack), "");
  const auto expected = arena_waypoints();
  ASSERT_EQ(stack.waypoints.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const mission::Waypoint& w = stack.waypoints[i];
    EXPECT_NEAR(w.position_m.x(), expected[i](0), 1e-5f) << "waypoint " << i;
    EXPECT_NEAR(w.position_m.y(), expected[i](1), 1e-5f) << "waypoint " << i;
    EXPECT_NEAR(w.position_m.z(), expected[i](2), 1e-5f) << "waypoint " << i;
    // The file gives degrees to three decimals: 1e-3 deg is 2e-5 rad.
    EXPECT_NEAR(w.heading_rad, expected[i](3), 1e-4f) << "waypoint " << i;
  }
}

}  // namespace
}  // namespace kestrel::tuning
