#include "kestrel/exploration/params.hpp"

#include <cmath>

#include "kestrel/core/mode_names.hpp"
#include "kestrel/exploration/beam_geometry.hpp"

namespace kestrel::exploration {
namespace {
bool positive(float v) {
  return std::isfinite(v) && v > 0.0f;
}
bool non_negative(float v) {
  return std::isfinite(v) && v >= 0.0f;
}
}  // namespace

const char* to_string(SteerUnflown s) {
  switch (s) {
    case SteerUnflown::kNever:
      return "off";
    case SteerUnflown::kAfterRestart:
      return "restarted";
    case SteerUnflown::kEveryNode:
      return "every";
    case SteerUnflown::kFromRootOnly:
      return "root";
  }
  return "unknown";
}

Result<SteerUnflown> parse_steer_unflown(const char* name) {
  return parse_by_name(name, kSteerUnflownModes);
}

const char* to_string(RetraceMode m) {
  switch (m) {
    case RetraceMode::kOff:
      return "off";
    case RetraceMode::kGuarded:
      return "guarded";
    case RetraceMode::kAlways:
      return "on";
  }
  return "unknown";
}

Result<RetraceMode> parse_retrace_mode(const char* name) {
  return parse_by_name(name, kRetraceModes);
}

const char* to_string(RetraceTarget t) {
  switch (t) {
    case RetraceTarget::kUnflown:
      return "unflown";
    case RetraceTarget::kFrontier:
      return "frontier";
  }
  return "unknown";
}

Result<RetraceTarget> parse_retrace_target(const char* name) {
  return parse_by_name(name, kRetraceTargets);
}

Status Params::validate() const {
  // Ranges are held in millimetres of 16 bits, and the field's sums in 32 (wall_follow_field.cpp):
  // every range below the 65 m a scan can carry.
  const bool wall_ok = positive(wall.target_range_m) && wall.target_range_m < 65.0f && positive(wall.safe_range_m) &&
                       wall.safe_range_m < wall.target_range_m && non_negative(wall.gain_wf) &&
                       non_negative(wall.gain_safe) && positive(wall.max_range_m) && wall.max_range_m < 65.0f;
  const bool srt_ok = srt.sector_count >= 2 && srt.sector_count <= kMaxSectors && positive(srt.perception_range_m) &&
                      srt.perception_range_m < 65.0f && positive(srt.discontinuity_m) &&
                      positive(srt.step_min_fraction) && srt.step_min_fraction <= srt.step_max_fraction &&
                      srt.step_max_fraction <= 1.0f && non_negative(srt.clearance_m) &&
                      non_negative(srt.coverage_margin_m) && srt.max_attempts_per_frontier >= 1 &&
                      listed(srt.steer, kSteerUnflownModes) && listed(srt.retrace, kRetraceModes) &&
                      listed(srt.retrace_target, kRetraceTargets);
  // A drift allowance beyond 10 m would hide a building's whole wall: no margin, a lost estimate.
  bool keep_out_ok = srt.keep_out_count <= kMaxKeepOuts && non_negative(srt.keep_out_drift_margin_m) &&
                     srt.keep_out_drift_margin_m <= 10.0f;
  for (std::size_t i = 0; keep_out_ok && i < srt.keep_out_count; ++i) keep_out_ok = srt.keep_out[i].valid();
  // A waypoint is at least twice d from its node, in millimetres of 16 bits: d up to 10 m.
  const bool guidance_ok = positive(guidance.arrival_distance_m) && guidance.arrival_distance_m <= 10.0f &&
                           non_negative(guidance.gain_fr) &&
                           positive(guidance.speed_limit_mps) && positive(guidance.yaw_rate_limit_radps) &&
                           positive(guidance.waypoint_time_limit_s) && positive(guidance.blocked_arrival_distance_m) &&
                           positive(guidance.blocked_time_s) && std::isfinite(guidance.altitude_m) &&
                           non_negative(guidance.cruise_speed_mps) && non_negative(guidance.wall_hold_gain);
  // A waypoint is drawn clearance_m from the returns: the limiter must let the vehicle get there.
  const bool approach_ok = approach.validate() == Status::kOk &&
                           (!approach.enabled || approach.stop_distance_m <= srt.clearance_m);
  return wall_ok && srt_ok && keep_out_ok && guidance_ok && approach_ok && frontier.validate() == Status::kOk &&
                 look_across.validate() == Status::kOk
             ? Status::kOk
             : Status::kInvalidArgument;
}

Status LookAcrossParams::validate() const {
  auto in_range = [](float s) { return std::isfinite(s) && s >= 0.0f && s <= 600.0f; };
  return in_range(after_s) && in_range(release_s) ? Status::kOk : Status::kInvalidArgument;
}

Status FrontierParams::validate() const {
  // Every distance within the 60 m the rays may reach at most: they become cell counts and
  // squared cell distances of 16 and 32 bits (frontier_clusters.hpp, frontier_explorer.cpp).
  const auto within_reach = [](float v) { return non_negative(v) && v <= 60.0f; };
  const bool distances_ok = within_reach(min_frontier_m) && within_reach(blacklist_radius_m) &&
                            within_reach(goal_match_m) && within_reach(look_distance_m) &&
                            within_reach(progress_m) && within_reach(stuck_radius_m) && within_reach(switch_margin_m);
  const bool ok = distances_ok && cell_m >= 0.02f && cell_m <= 1.0f && positive(reach_m) && reach_m <= 60.0f &&
                  positive(lethal_m) && non_negative(relaxed_lethal_m) && relaxed_lethal_m <= lethal_m &&
                  soft_m >= lethal_m && soft_m <= 10.0f && soft_penalty <= 60 && non_negative(coastal_fraction) &&
                  coastal_fraction <= 1.0f && soft_penalty + coastal_penalty <= 60 && non_negative(goal_inset_m) &&
                  goal_inset_m <= 5.0f && positive(lookahead_m) && lookahead_m <= 10.0f && non_negative(field_weight) &&
                  field_weight <= 10.0f && non_negative(draw_period_s) && draw_period_s <= 2.0f &&
                  positive(replan_period_s) && replan_period_s <= 2.5f && positive(progress_m) &&
                  positive(patience_s) && positive(goal_time_limit_s) && looks_to_give_up >= 1 &&
                  positive(stuck_radius_m) && positive(stuck_time_s) && empty_plans_to_finish >= 1;
  // Distances become chamfer units of a third of a cell, at most 255.
  return ok && soft_m / cell_m * 3.0f < 255.0f ? Status::kOk : Status::kInvalidArgument;
}

Status ApproachParams::validate() const {
  const bool ok = positive(stop_distance_m) && stop_distance_m <= 2.0f && positive(gain) && gain <= 10.0f &&
                  non_negative(blind_speed_mps) && blind_speed_mps <= 10.0f;
  return ok ? Status::kOk : Status::kInvalidArgument;
}

Status BeamGeometry::validate() const {
  // The per-beam tables (sectors, clearance erosion) index beams by angle: a step finer than
  // kMinAngleStepRad would overflow those indices.
  return fan_well_formed(beam_count, first_angle_rad, angle_step_rad, max_range_mm) ? Status::kOk
                                                                                     : Status::kInvalidArgument;
}

bool BeamGeometry::matches(const LaserScan& scan) const {
  const float tol = 1e-3f * std::fabs(angle_step_rad);
  return scan.beam_count == beam_count && std::fabs(scan.first_angle_rad - first_angle_rad) <= tol &&
         std::fabs(scan.angle_step_rad - angle_step_rad) <= tol * 1e-2f + 1e-9f;
}

}  // namespace kestrel::exploration
