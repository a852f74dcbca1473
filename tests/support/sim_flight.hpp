// What every closed-loop flight test of the autonomy stack sets up the same way: a built-in world in the
// simulator with one laser and seed, the flight stack's options parsed from mission options
// exactly as kestrel-sim parses its --mission-arg, and a metric read back from metrics.json's
// list. A set-up failure (an unknown world, a refused option) is reported to the running test,
// which should stop there: `ASSERT_FALSE(HasFailure())` after the set-up, since these helpers
// return a value and cannot end the test themselves.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "kestrel/flight/autonomy_mission.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::test {

// Returned by value through guaranteed elision: Simulation can be neither copied nor moved.
inline sim::Simulation simulate(std::string_view world_name, const sim::LaserParams& laser,
                                std::uint64_t seed = sim::SimConfig{}.seed) {
  const sim::WorldParseResult world = sim::load_builtin_world(world_name);
  EXPECT_TRUE(world.ok) << world_name << ": " << world.error;
  sim::SimConfig cfg;
  cfg.laser = laser;
  cfg.seed = seed;
  return sim::Simulation(world.world, cfg);
}

// Only the keys given: an absent key keeps the laser's default, which a key's "off" would not.
inline flight::FlightOptions flight_options(mission::MissionKind kind, std::map<std::string, std::string> values) {
  sim::MissionOptions opt;
  opt.values = std::move(values);
  flight::FlightOptions out;
  const std::string err = flight::parse_flight_options(kind, opt, out);
  EXPECT_EQ(err, "") << "the test's own mission options were refused";
  return out;
}

inline double metric(const sim::MissionMetrics& metrics, std::string_view key) {
  for (const auto& [k, v] : metrics)
    if (k == key) return v;
  ADD_FAILURE() << "no metric " << key;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace kestrel::test
