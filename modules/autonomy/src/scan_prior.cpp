#include "kestrel/autonomy/scan_prior.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::autonomy {

bool scan_prior_from_nav(const NavState& nav, TimeUs scan_stamp, scan_matching::PosePrior& prior) {
  if (!nav.valid) return false;
  const float back = static_cast<float>((nav.stamp - scan_stamp).seconds());
  if (!(std::fabs(back) <= kMaxPriorExtrapolationS)) return false;
  const float vx = nav.velocity_mps.x(), vy = nav.velocity_mps.y(), w = nav.yaw_rate_radps;
  const Pose2 pose{nav.position_m.x() - vx * back, nav.position_m.y() - vy * back,
                   wrap_angle(nav.heading_rad - w * back)};
  // A non-finite filter state would centre the search nowhere; the matcher's own
  // prediction is better than that.
  if (!pose.finite() || !std::isfinite(vx) || !std::isfinite(vy) || !std::isfinite(w)) return false;
  prior.pose = pose;
  // The better-known horizontal axis sets the translation window: along a corridor the
  // filter's variance grows without bound (the match cannot see along it), yet there the score
  // is flat and a wider window would buy nothing but time; when matches stop altogether both
  // axes grow and the window with them, up to its maximum.
  prior.position_std_m = std::min(nav.position_std_m.x(), nav.position_std_m.y());
  prior.heading_std_rad = nav.heading_std_rad;
  // Held over the laser's sweep to deskew the scan (ScanMatcher::deskew).
  prior.vx_mps = vx;
  prior.vy_mps = vy;
  prior.yaw_rate_radps = w;
  return true;
}

scan_matching::PosePrior prior_in_matcher_frame(const scan_matching::PosePrior& world, const Pose2& frame_correction) {
  const Pose2 back = frame_correction.inverse();
  scan_matching::PosePrior m = world;
  m.pose = back.compose(world.pose);
  const float c = std::cos(back.theta), s = std::sin(back.theta);
  m.vx_mps = c * world.vx_mps - s * world.vy_mps;
  m.vy_mps = s * world.vx_mps + c * world.vy_mps;
  return m;
}

}  // namespace kestrel::autonomy
