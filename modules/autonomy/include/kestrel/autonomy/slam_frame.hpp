#pragma once
// Where the compact SLAM's map lies in the filter's frame. The home re-localisation moves the
// filter's frame (NavFilter::apply_correction shifts the trajectory from the fix on) and leaves
// the SLAM's map where it was drawn, so the two frames part: filter pose = frame * SLAM pose.
// Priors go into the SLAM through to_slam(), its corrections come back through to_filter()
// with the frame they were offered under.
#include "kestrel/core/se2.hpp"

namespace kestrel::autonomy {

class SlamFrame {
 public:
  Pose2 to_slam(const Pose2& filter_pose) const { return frame_.inverse().compose(filter_pose); }
  Pose2 to_filter(const Pose2& slam_pose) const { return frame_.compose(slam_pose); }

  // The filter's frame correction went from `before` to `after` (NavFilter::frame_correction()
  // around a correction the SLAM did not make): the filter's trajectory moved by
  // after * before^-1 in the world, the SLAM's did not.
  void filter_moved(const Pose2& before, const Pose2& after) {
    frame_ = after.compose(before.inverse()).compose(frame_);
  }

 private:
  Pose2 frame_;
};

}  // namespace kestrel::autonomy
