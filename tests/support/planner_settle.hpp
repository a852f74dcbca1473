#pragma once
// Drives an SRT-Star planner through an arrival step sliced over calls, as the guidance task
// does: the vehicle waits where it is, the same pose, scan and stamp each call, until the
// planner is no longer busy.
#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::test {

// Calls an arrival step may be sliced over before a driver gives up: a hang's guard only.
inline constexpr int kSettleCallGuard = 1000000;

// One update of `planner`, then more while it is busy. `each(status)` sees every call, so a test
// can check each one and read the planner's work after it.
template <typename Planner, typename Each>
void update_until_settled(Planner& planner, const Pose2& pose, const LaserScan& scan, TimeUs now, bool& fresh,
                          Each&& each) {
  each(planner.update(pose, scan, now, fresh));
  for (int call = 0; call < kSettleCallGuard && planner.busy(); ++call) each(planner.update(pose, scan, now, fresh));
}

}  // namespace kestrel::test
