// kestrel-sim's flight options: the operator's keep-out boxes (--mission-arg keepout=...), the
// approach limiter, the perception range and the flight height.
#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>

#include "kestrel/flight/autonomy_mission.hpp"
#include "temp_file.hpp"

namespace kestrel::flight {
namespace {

// Options built by emplace: GCC 12 at -O3 for ARM misreads map[key] = "literal" as an
// overlapping memcpy (-Werror=restrict).
sim::MissionOptions options(std::initializer_list<std::pair<const char*, const char*>> kv) {
  sim::MissionOptions o;
  for (const auto& [k, v] : kv) o.values.emplace(k, v);
  return o;
}

TEST(FlightOptions, KeepOutBoxesParseIntoTheExplorerParameters) {
  const sim::MissionOptions opt = options({{"keepout", "2,8.8,5,9.2;10,10,11,11.5"}});
  FlightOptions f;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, opt, f), "");
  const exploration::SrtParams& srt = f.stack.explorer.srt;
  ASSERT_EQ(srt.keep_out_count, 2);
  EXPECT_FLOAT_EQ(srt.keep_out[0].x_min, 2.0f);
  EXPECT_FLOAT_EQ(srt.keep_out[0].y_min, 8.8f);
  EXPECT_FLOAT_EQ(srt.keep_out[0].x_max, 5.0f);
  EXPECT_FLOAT_EQ(srt.keep_out[0].y_max, 9.2f);
  EXPECT_FLOAT_EQ(srt.keep_out[1].y_max, 11.5f);
  EXPECT_EQ(f.stack.explorer.validate(), Status::kOk);
}

TEST(FlightOptions, MalformedKeepOutsAreRefusedWithAReason) {
  exploration::SrtParams srt;
  EXPECT_NE(parse_keep_outs("", srt), "");
  EXPECT_NE(parse_keep_outs("1,2,3", srt), "");            // three numbers
  EXPECT_NE(parse_keep_outs("1,2,3,x", srt), "");          // not a number
  EXPECT_NE(parse_keep_outs("5,0,1,1", srt), "");          // corners swapped
  EXPECT_NE(parse_keep_outs("0,0,1,1;0,0,1,1;0,0,1,1;0,0,1,1;0,0,1,1", srt), "");  // five boxes
  EXPECT_EQ(parse_keep_outs("0,0,1,1;2,2,3,3", srt), "");
  EXPECT_EQ(srt.keep_out_count, 2);
  // Not an option of the other missions.
  const sim::MissionOptions opt = options({{"keepout", "0,0,1,1"}});
  FlightOptions f;
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, opt, f), "");
}

TEST(FlightOptions, ExploreKnobsReachTheStackAndBadValuesAreRefused) {
  const sim::MissionOptions opt =
      options({{"approach", "off"}, {"approach_blind_mps", "0.2"}, {"srt_range_m", "5"}, {"altitude_m", "1.2"},
               {"speed_limit_mps", "0.8"}, {"explorer", "frontier"}, {"frontier_reach_m", "8"},
               {"frontier_relaxed_m", "0.3"}, {"frontier_coastal", "0"}, {"yaw_rate_limit_radps", "0.25"},
               {"look_across_s", "3"}, {"look_across_release_s", "1.5"}, {"clearance_m", "0.3"}});
  FlightOptions f;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, opt, f), "");
  EXPECT_FALSE(f.stack.explorer.approach.enabled);
  EXPECT_FLOAT_EQ(f.stack.explorer.approach.blind_speed_mps, 0.2f);
  EXPECT_FLOAT_EQ(f.stack.explorer.srt.perception_range_m, 5.0f);
  EXPECT_FLOAT_EQ(f.stack.mission.takeoff_altitude_m, 1.2f);
  EXPECT_FLOAT_EQ(f.stack.explorer.guidance.speed_limit_mps, 0.8f);
  EXPECT_EQ(f.stack.explorer_kind, exploration::ExplorerKind::kFrontier);
  EXPECT_FLOAT_EQ(f.stack.explorer.frontier.reach_m, 8.0f);
  EXPECT_FLOAT_EQ(f.stack.explorer.frontier.relaxed_lethal_m, 0.3f);
  EXPECT_FLOAT_EQ(f.stack.explorer.frontier.coastal_fraction, 0.0f);
  EXPECT_FLOAT_EQ(f.stack.explorer.guidance.yaw_rate_limit_radps, 0.25f);
  EXPECT_FLOAT_EQ(f.stack.explorer.look_across.after_s, 3.0f);
  EXPECT_FLOAT_EQ(f.stack.explorer.look_across.release_s, 1.5f);
  EXPECT_FLOAT_EQ(f.stack.clearance.min_clearance_m, 0.3f);
  EXPECT_EQ(f.stack.explorer.validate(), Status::kOk);
  for (const auto& [key, bad] : {std::pair<const char*, const char*>{"approach", "maybe"},
                                 {"approach_blind_mps", "-1"},
                                 {"speed_limit_mps", "0"},
                                 {"speed_limit_mps", "fast"},
                                 {"speed_limit_mps", "6"},
                                 {"yaw_rate_limit_radps", "0"},
                                 {"yaw_rate_limit_radps", "11"},
                                 {"look_across_s", "-1"},
                                 {"look_across_s", "soon"},
                                 {"look_across_release_s", "601"},
                                 {"srt_range_m", "0"},
                                 {"explorer", "grid"},
                                 {"frontier_reach_m", "0"},
                                 {"frontier_reach_m", "31"},
                                 {"frontier_relaxed_m", "-0.1"},
                                 {"frontier_coastal", "1.5"},
                                 {"altitude_m", "0.1"},
                                 {"altitude_m", "high"},
                                 {"clearance_m", "-0.1"},
                                 {"clearance_m", "4"}}) {
    const sim::MissionOptions b = options({{key, bad}});
    FlightOptions g;
    EXPECT_NE(parse_flight_options(mission::MissionKind::kExplore, b, g), "") << key << "=" << bad;
  }
  // The flight height is every flying mission's; the explorer's knobs are explore's only.
  FlightOptions h;
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kHover, options({{"altitude_m", "1.5"}}), h), "");
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, options({{"altitude_m", "1.5"}, {"approach", "on"}}), h),
            "");
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, options({{"speed_limit_mps", "0.8"}}), h), "");
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, options({{"clearance_m", "0.3"}}), h), "");
}

// The explorer's distances from laser returns (modules/exploration/EXPERIMENTS.md, Not done: the same physical margins
// when the laser sees walls' faces), each to its own parameter.
TEST(FlightOptions, ExplorerDistancesReachTheirParameters) {
  sim::MissionOptions margins{{{"wall_target_m", "0.95"}, {"wall_safe_m", "0.6"},
                               {"srt_clearance_m", "0.35"}, {"approach_stop_m", "0.3"}}};
  FlightOptions m;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, margins, m), "");
  EXPECT_FLOAT_EQ(m.stack.explorer.wall.target_range_m, 0.95f);
  EXPECT_FLOAT_EQ(m.stack.explorer.wall.safe_range_m, 0.6f);
  EXPECT_FLOAT_EQ(m.stack.explorer.srt.clearance_m, 0.35f);
  EXPECT_FLOAT_EQ(m.stack.explorer.approach.stop_distance_m, 0.3f);
  EXPECT_EQ(m.stack.explorer.validate(), Status::kOk);
  // Each value valid alone, the pair not (r_safe above r_t): refused when the stack starts.
  sim::MissionOptions crossed{{{"wall_target_m", "0.95"}, {"wall_safe_m", "1.2"}}};
  FlightOptions n;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, crossed, n), "");
  EXPECT_EQ(n.stack.explorer.validate(), Status::kInvalidArgument);
  for (const sim::MissionOptions& bad :
       {sim::MissionOptions{{{"srt_clearance_m", "0"}}}, sim::MissionOptions{{{"approach_stop_m", "-0.1"}}},
        sim::MissionOptions{{{"wall_target_m", "far"}}}, sim::MissionOptions{{{"wall_safe_m", "6"}}}}) {
    FlightOptions g;
    EXPECT_NE(parse_flight_options(mission::MissionKind::kExplore, bad, g), "") << bad.values.begin()->first;
  }
  // The SRT's memory of where the vehicle has flown.
  FlightOptions mem;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_memory", "on"}}}, mem), "");
  EXPECT_TRUE(mem.stack.explorer.srt.prefer_unvisited);
  EXPECT_NE(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_memory", "yes"}}}, mem),
            "");
  // A run-out retracing the path flown.
  FlightOptions retrace;
  EXPECT_EQ(retrace.stack.explorer.srt.retrace, exploration::RetraceMode::kGuarded);  // the default
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_retrace", "on"}}}, retrace),
            "");
  EXPECT_EQ(retrace.stack.explorer.srt.retrace, exploration::RetraceMode::kAlways);
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_retrace", "guarded"}}}, retrace),
      "");
  EXPECT_EQ(retrace.stack.explorer.srt.retrace, exploration::RetraceMode::kGuarded);
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_retrace", "off"}}}, retrace), "");
  EXPECT_EQ(retrace.stack.explorer.srt.retrace, exploration::RetraceMode::kOff);
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_retrace", "1"}}}, retrace),
            "srt_retrace: expected off, guarded or on, got '1'");
  // The flight home's shortcut where the scan shows the way clear.
  FlightOptions home;
  EXPECT_TRUE(home.stack.mission.return_shortcut);
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"return_shortcut", "off"}}}, home),
      "");
  EXPECT_FALSE(home.stack.mission.return_shortcut);
  EXPECT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"return_shortcut", "no"}}}, home),
      "return_shortcut: expected on or off, got 'no'");
  // Home re-localisation, on by default.
  FlightOptions fix;
  EXPECT_TRUE(fix.stack.home_fix.enabled);
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"home_fix", "off"}}}, fix), "");
  EXPECT_FALSE(fix.stack.home_fix.enabled);
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"home_fix", "1"}}}, fix),
            "home_fix: expected on or off, got '1'");
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"takeoff_survey_rad", "3"}}}, fix),
      "");
  EXPECT_EQ(fix.stack.home_fix.survey_rad, 3.0f);
  EXPECT_EQ(fix.stack.home_fix.frontier_survey_rad, 3.0f);
  EXPECT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"takeoff_survey_rad", "-1"}}}, fix),
      "takeoff_survey_rad: '-1' is not an angle in [0, 12.5] rad");
  EXPECT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"takeoff_survey_rad", "nan"}}}, fix),
      "takeoff_survey_rad: 'nan' is not an angle in [0, 12.5] rad");
  // What the retrace counts, and what ends it.
  FlightOptions target;
  EXPECT_EQ(target.stack.explorer.srt.retrace_target, exploration::RetraceTarget::kUnflown);
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore,
                                 sim::MissionOptions{{{"srt_retrace_target", "frontier"}}}, target),
            "");
  EXPECT_EQ(target.stack.explorer.srt.retrace_target, exploration::RetraceTarget::kFrontier);
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_retrace_target", "seen"}}},
                                 target),
            "srt_retrace_target: expected unflown or frontier, got 'seen'");
  // Frontiers kept beside walls.
  FlightOptions rescue;
  EXPECT_FALSE(rescue.stack.explorer.srt.rescue_frontiers);
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_rescue", "on"}}}, rescue),
            "");
  EXPECT_TRUE(rescue.stack.explorer.srt.rescue_frontiers);
  EXPECT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_rescue", "maybe"}}}, rescue),
      "srt_rescue: expected on or off, got 'maybe'");
  // Discontinuity frontiers from the beams' jumps (default) or, off, from the sectors' radii
  // alone as paper 002 has it.
  FlightOptions jumps;
  EXPECT_TRUE(jumps.stack.explorer.srt.discontinuity_needs_beam_jump);
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_beam_jumps", "off"}}}, jumps),
      "");
  EXPECT_FALSE(jumps.stack.explorer.srt.discontinuity_needs_beam_jump);
  // The scan matcher's key scan once per interval along a corridor: off by default, any mission.
  FlightOptions corridor;
  EXPECT_EQ(corridor.stack.matcher.degenerate_key_interval_s, 0.0f);
  ASSERT_EQ(
      parse_flight_options(mission::MissionKind::kHover, sim::MissionOptions{{{"corridor_keys_s", "1"}}}, corridor),
      "");
  EXPECT_EQ(corridor.stack.matcher.degenerate_key_interval_s, 1.0f);
  EXPECT_EQ(
      parse_flight_options(mission::MissionKind::kHover, sim::MissionOptions{{{"corridor_keys_s", "-1"}}}, corridor),
      "corridor_keys_s: '-1' is not a time in [0, 60] s");
  // Which draws are steered: after a restart by default, any of the four by name.
  FlightOptions steer;
  EXPECT_EQ(steer.stack.explorer.srt.steer, exploration::SteerUnflown::kAfterRestart);
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_steer", "root"}}}, steer),
            "");
  EXPECT_EQ(steer.stack.explorer.srt.steer, exploration::SteerUnflown::kFromRootOnly);
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_steer", "off"}}}, steer),
            "");
  EXPECT_EQ(steer.stack.explorer.srt.steer, exploration::SteerUnflown::kNever);
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kExplore, sim::MissionOptions{{{"srt_steer", "on"}}}, steer),
            "srt_steer: expected off, restarted, every or root, got 'on'");
  // Explore's only.
  FlightOptions h;
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, margins, h), "");
}

TEST(FlightOptions, AnEkfFileIsCheckedAndKeptToLoadOverTheLasersDefaults) {
  const std::string path = test::write_temp_file("flight_options_test.ekf", "pose_cov_scale = 2\n");
  FlightOptions ok;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kHover, options({{"ekf", path.c_str()}}), ok), "");
  EXPECT_EQ(ok.ekf_file, path);  // start() loads it over autonomy::vehicle_ekf_params(laser)
  EXPECT_TRUE(ok.ekf_for_laser);
  FlightOptions missing;
  EXPECT_NE(parse_flight_options(mission::MissionKind::kHover, options({{"ekf", "/no/such/file.ekf"}}), missing), "");
  std::remove(path.c_str());
}

// slam=on|off, or a parameter file that turns it on; unset, start() asks the laser
// (autonomy::vehicle_slam_enabled); a bad file is refused with its line.
TEST(FlightOptions, TheCompactSlamFollowsTheLaserUnlessAsked) {
  EXPECT_TRUE(autonomy::vehicle_slam_enabled(4000));
  EXPECT_FALSE(autonomy::vehicle_slam_enabled(30000));
  EXPECT_FALSE(autonomy::vehicle_slam_enabled(0));
  FlightOptions plain;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, options({}), plain), "");
  EXPECT_FALSE(plain.slam_on.has_value());
  FlightOptions on, off;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, options({{"slam", "on"}}), on), "");
  EXPECT_EQ(on.slam_on, std::optional<bool>(true));
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, options({{"slam", "off"}}), off), "");
  EXPECT_EQ(off.slam_on, std::optional<bool>(false));
  const std::string path = test::write_temp_file("flight_options_test.slam", "iterations = 50\nmin_gain_level = 9\n");
  FlightOptions file;
  ASSERT_EQ(parse_flight_options(mission::MissionKind::kExplore, options({{"slam", path.c_str()}}), file), "");
  EXPECT_EQ(file.slam_on, std::optional<bool>(true));
  EXPECT_EQ(file.stack.slam.iterations, 50.0f);
  EXPECT_EQ(file.stack.slam.min_gain_level, 9.0f);
  const std::string bad_path =
      test::write_temp_file("flight_options_test_bad.slam", "min_points = 900\nmax_points = 100\n");
  FlightOptions bad;
  EXPECT_EQ(parse_flight_options(mission::MissionKind::kExplore, options({{"slam", bad_path.c_str()}}), bad),
            bad_path + ": inconsistent SLAM parameters: need min_points <= max_points");
  EXPECT_EQ(bad.stack.slam.min_points, slam::SlamParams{}.min_points);  // nothing taken from it
  std::remove(bad_path.c_str());
  FlightOptions missing;
  EXPECT_NE(parse_flight_options(mission::MissionKind::kExplore, options({{"slam", "/no/such/file"}}), missing), "");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace kestrel::flight
