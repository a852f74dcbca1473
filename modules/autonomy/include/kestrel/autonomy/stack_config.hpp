#pragma once
// Everything the autonomy stack is configured with, one struct per module (each with its
// defaults and units inline in its own header), plus what ties them together.
#include "kestrel/control/controller_params.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/exploration/explorer.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/mission/mission_controller.hpp"
#include "kestrel/scan_matching/params.hpp"

namespace kestrel::autonomy {

struct StackConfig {
  scan_matching::Params matcher;
  estimation::EkfParams ekf;
  control::ControllerParams controller = control::default_controller_params();
  exploration::Params explorer;
  exploration::ExplorerKind explorer_kind = exploration::ExplorerKind::kBlend;
  mission::MissionParams mission;
  mission::MissionKind mission_kind = mission::MissionKind::kHover;
  StaticVector<mission::Waypoint, mission::MissionController::kMaxWaypoints> waypoints;
  // Where the vehicle stands at power-up, in the world frame the mission is expressed in: the
  // scan matcher's first scan starts the map at this pose.
  Pose2 home;
  // Apply each scan-matcher pose at the time its scan was taken (the EKF's state history), or,
  // false, as if taken on arrival: the comparison of paper 000 Figure 3b.
  bool use_measurement_time = true;
};

}  // namespace kestrel::autonomy
