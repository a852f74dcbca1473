#pragma once
// What the explorer is told of the newest scan match (exploration::LookAcross): whether it
// could measure the position along every axis and, if not, along which it could not, in the
// navigation filter's frame, where the explorer commands its heading.
#include "kestrel/core/se2.hpp"
#include "kestrel/exploration/look_across.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"

namespace kestrel::autonomy {

// The match's flat axis is drawn in the scan matcher's frame; after SLAM corrections the
// filter's frame is the matcher's turned by frame_correction.theta (world = correction *
// matcher), and so is the axis. A lost match measured nothing: not usable.
exploration::MatchConstraint match_constraint_in_nav_frame(const scan_matching::ScanMatch& match, TimeUs stamp,
                                                           const Pose2& frame_correction);

}  // namespace kestrel::autonomy
