#include <gtest/gtest.h>

#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/command_script.hpp"
#include "kestrel/sim/flight_recorder.hpp"
#include "kestrel/sim/mission_registry.hpp"
#include "kestrel/sim/mission_runner.hpp"
#include "temp_file.hpp"

namespace kestrel::sim {
namespace {

TEST(MissionRegistry, FindsManualAndRejectsUnknownNamesAndOptions) {
  ASSERT_NE(find_mission("manual"), nullptr);
  EXPECT_EQ(find_mission("teleport"), nullptr);
  std::string err;
  MissionOptions opt;
  opt.values["speed"] = "3";
  EXPECT_EQ(find_mission("manual")->create(opt, err), nullptr);
  EXPECT_NE(err.find("no option 'speed'"), std::string::npos);
  MissionOptions bad_script;
  bad_script.values["script"] = "/nonexistent/script.txt";
  EXPECT_EQ(find_mission("manual")->create(bad_script, err), nullptr);
  EXPECT_NE(err.find("/nonexistent/script.txt"), std::string::npos);
}

TEST(CommandScript, ParsesAndReportsErrorsWithLines) {
  CommandScript s;
  EXPECT_EQ(s.parse(CommandScript::default_text(), "d"), "");
  EXPECT_GT(s.steps.size(), 10u);
  EXPECT_EQ(s.parse("0 0 0 0.5 0\n1 2 3\n", "s.txt"),
            "s.txt:2: expected 5 numbers: T_S PITCH_DEG ROLL_DEG THRUST YAW_RATE_DPS");
  EXPECT_EQ(s.parse("0 0 0 1.5 0\n", "s.txt"), "s.txt:1: thrust must be between 0 and 1");
  EXPECT_EQ(s.parse("1 0 0 0.5 0\n0.5 0 0 0.5 0\n", "s.txt"), "s.txt:2: time goes backwards");
  EXPECT_EQ(s.parse("0 0 0 0.5 x\n", "s.txt"), "s.txt:1: 'x' is not a number");
  EXPECT_EQ(s.parse("disarm\n", "s.txt"), "s.txt:1: expected 'disarm T_S'");
  EXPECT_EQ(s.parse("# nothing\n", "s.txt"), "s.txt: the script has no commands");
}

// Regression: a step at 1e13 s overflowed TimeUs::from_s and fired at t = 0.
TEST(CommandScript, TimesBeyondTheLongestFlightAreRefused) {
  CommandScript s;
  const std::string want = "s.txt:2: time must be at most 1e6 s (kestrel-sim's longest --duration)";
  EXPECT_EQ(s.parse("0 0 0 0.5 0\n1e13 5 0 0.5 0\n", "s.txt"), want);
  EXPECT_EQ(s.parse("0 0 0 0.5 0\ndisarm 1e300\n", "s.txt"), want);
  EXPECT_EQ(s.parse("0 0 0 0.5 0\ndisarm 1e6\n", "s.txt"), "");
}

// read_text hands the file over as it is (kestrel-sysid passes it on to be parsed once) and
// refuses what load refuses: a file that will not open, a directory.
TEST(CommandScript, ReadTextGivesTheFileOrWhyNot) {
  const std::string path = test::write_temp_file("command_script_read.txt", "0 0 0 0.5 0\n# end\n");
  std::string text;
  EXPECT_EQ(CommandScript::read_text(path, text), "");
  EXPECT_EQ(text, "0 0 0 0.5 0\n# end\n");
  EXPECT_EQ(CommandScript::read_text("/nonexistent/script.txt", text),
            "cannot open '/nonexistent/script.txt'");
  const std::string dir = testing::TempDir();
  EXPECT_EQ(CommandScript::read_text(dir, text), "cannot read '" + dir + "' (is a directory)");
}

TEST(ManualMission, DefaultScriptFliesDownTheArenaHallwayWithoutContact) {
  const auto w = load_builtin_world("iarc-arena");
  ASSERT_TRUE(w.ok);
  SimConfig cfg;
  cfg.laser = LaserParams::urg04lx();  // cheaper; the flight is open loop
  Simulation sim(w.world, cfg);
  FlightRecorder rec(sim.world(), sim.free_space());
  sim.set_observer(&rec);
  std::string err;
  auto mission = find_mission("manual")->create({}, err);
  ASSERT_NE(mission, nullptr) << err;
  const double seconds = KESTREL_SIM_SHORT_TESTS ? 6.0 : 16.0;
  const RunResult r = run_mission(sim, *mission, Duration::from_s(seconds));
  EXPECT_EQ(r.status, Status::kOk);
  EXPECT_FALSE(r.collided) << r.message;
  EXPECT_EQ(r.end.us, static_cast<int64_t>(seconds * 1e6));
  EXPECT_NEAR(sim.truth().position_m.z(), 0.981, 0.01);
  if (KESTREL_SIM_SHORT_TESTS) {
    // 2 s accelerating (from t = 3 s, after the 20 ms command delay and the attitude lag),
    // then cruising at 1.71 m/s: 1.71 m + 1 s.
    EXPECT_NEAR(sim.truth().position_m.x(), 2 + 1.7126 + 1.7126 * 0.98 - 1.7126 * 0.08, 0.05);
    return;
  }
  // Climbed to ~1 m and flew 17 m down the hallway (x from 2 to ~19).
  EXPECT_NEAR(sim.truth().position_m.z(), 0.981, 0.01);
  EXPECT_NEAR(sim.truth().position_m.x(), 19.1, 0.1);
  EXPECT_NEAR(rec.max_speed_mps(), 1.71, 0.02);
  EXPECT_EQ(rec.scans(), static_cast<uint64_t>(seconds * 10));
  EXPECT_GT(rec.coverage(), 0.1);
  EXPECT_GE(rec.rooms_entered(), 1);
  EXPECT_EQ(rec.scan_truth().size(), static_cast<std::size_t>(seconds * 10));
}

}  // namespace
}  // namespace kestrel::sim
