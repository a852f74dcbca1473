#include "kestrel/autonomy/match_constraint.hpp"

#include "kestrel/core/angle.hpp"

namespace kestrel::autonomy {

exploration::MatchConstraint match_constraint_in_nav_frame(const scan_matching::ScanMatch& match, TimeUs stamp,
                                                           const Pose2& frame_correction) {
  namespace mf = scan_matching::match_flag;
  exploration::MatchConstraint c;
  c.stamp = stamp;
  c.degenerate = (match.measurement.flags & mf::kDegenerate) != 0;
  c.flat_axis_rad = wrap_angle(match.major_axis_rad + frame_correction.theta);
  c.usable = (match.measurement.flags & mf::kLost) == 0;
  return c;
}

}  // namespace kestrel::autonomy
