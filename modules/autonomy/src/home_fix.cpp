#include "kestrel/autonomy/home_fix.hpp"

#include <cmath>

namespace kestrel::autonomy {

Status validate(const HomeFixConfig& c) {
  if (scan_matching::validate(c.search) != Status::kOk) return Status::kInvalidArgument;
  const auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };  // false for NaN
  if (!in(c.survey_rad, 0.0f, 12.5f) || !in(c.frontier_survey_rad, 0.0f, 12.5f) ||
      !in(c.home_survey_rad, 0.0f, 12.5f) || !in(c.reference_window_s, 0.0f, 600.0f) ||
      !in(c.reference_spacing_m, 0.1f, 20.0f) || !in(c.reference_turn_rad, 0.05f, 3.2f) ||
      !in(c.radius_m, 0.0f, 12.0f) || !in(c.explore_radius_m, 0.0f, 12.0f) ||
      !in(c.period_s, 0.05f, 60.0f) || !in(c.agree_m, 0.01f, 2.0f) || !in(c.agree_rad, 0.001f, 1.0f) ||
      !in(c.view_change_m, 0.0f, 10.0f) || !in(c.view_change_rad, 0.0f, 3.2f))
    return Status::kInvalidArgument;
  return Status::kOk;
}

Status HomeFix::configure(const HomeFixConfig& c, const scan_matching::Params& matcher) {
  configured_ = false;
  if (validate(c) != Status::kOk) return Status::kInvalidArgument;
  if (c.enabled && relocaliser_.configure(c.search, matcher) != Status::kOk) return Status::kInvalidArgument;
  config_ = c;
  started_ = searched_ = have_pending_ = false;
  references_offered_ = 0;
  in_.clear();
  out_.clear();
  counters_ = {};
  configured_ = c.enabled;
  return Status::kOk;
}

bool HomeFix::hand_over(const scan_matching::ScanPoints& points, const LaserScan& scan, const Pose2& pose,
                        bool reference) {
  Input* in = in_.writable();
  // A fix not yet taken would leave a search's guess stale. Read after the input slot is found
  // free: level 3 posts a fix before it frees the slot, so a free slot shows it.
  if (in == nullptr || (!reference && out_.full())) return false;
  in->points = points;
  in->scan = scan;
  in->pose = pose;
  in->stamp = scan.stamp;
  in->reference = reference;
  in_.post();
  return true;
}

void HomeFix::offer(const scan_matching::ScanPoints& points, const LaserScan& scan, const Pose2& pose, bool flying_home,
                    bool may_reference) {
  if (!configured_ || !pose.finite()) return;
  const TimeUs stamp = scan.stamp;
  if (!started_) {
    if (!may_reference || !hand_over(points, scan, pose, true)) return;
    started_ = true;
    first_stamp_ = stamp;
    home_ = last_reference_ = pose;
    references_offered_ = 1;
    return;
  }
  const bool collecting = references_offered_ < scan_matching::kMaxReferenceScans &&
                          (stamp - first_stamp_).seconds() <= static_cast<double>(config_.reference_window_s);
  if (collecting) {
    const bool moved =
        std::hypot(pose.x - last_reference_.x, pose.y - last_reference_.y) >= config_.reference_spacing_m ||
        std::fabs(wrap_angle(pose.theta - last_reference_.theta)) >= config_.reference_turn_rad;
    if (moved && may_reference && hand_over(points, scan, pose, true)) {
      last_reference_ = pose;
      ++references_offered_;
    }
    return;
  }
  const float from_home = std::hypot(pose.x - home_.x, pose.y - home_.y);
  // Not flying home, only while exploring at altitude (may_reference): landed, or coming down
  // in a failsafe, the laser sees what the vehicle flies over.
  const bool near = flying_home ? from_home <= config_.radius_m
                                : may_reference && config_.explore_radius_m > 0.0f &&
                                      from_home <= config_.explore_radius_m;
  if (!near) return;
  if (searched_ && (stamp - last_search_).seconds() < static_cast<double>(config_.period_s)) return;
  if (hand_over(points, scan, pose, false)) {
    last_search_ = stamp;
    searched_ = true;
  }
}

bool HomeFix::take(PoseMeasurement2& fix) {
  const PoseMeasurement2* out = out_.readable();
  if (out == nullptr) return false;
  fix = *out;
  out_.done();
  return true;
}

void HomeFix::background_step() {
  // The output slot is this side's while it is empty: a fix found now has somewhere to go.
  if (out_.full()) return;
  const Input* in = in_.readable();
  if (in == nullptr) return;
  if (in->reference) {
    if (relocaliser_.add_reference(in->points, in->pose, &in->scan) == Status::kOk) ++counters_.references;
  } else {
    ++counters_.searches;
    const scan_matching::Relocalisation r = relocaliser_.locate(in->points, in->pose, &in->scan);
    if (!r.fixed()) {
      have_pending_ = false;
      switch (r.outcome) {
        case scan_matching::RelocaliseOutcome::kNoGain: ++counters_.no_gain; break;
        case scan_matching::RelocaliseOutcome::kAmbiguous: ++counters_.ambiguous; break;
        case scan_matching::RelocaliseOutcome::kSeesThrough: ++counters_.sees_through; break;
        case scan_matching::RelocaliseOutcome::kReturnsInFree: ++counters_.returns_in_free; break;
        default: ++counters_.no_fit; break;
      }
    } else {
      ++counters_.found;
      const Pose2 correction = r.pose.compose(in->pose.inverse());
      // Judged where the vehicle is, not at the frame's origin: the earlier correction carried
      // to this guess against this fix. Compared as transforms, a heading 0.02 rad apart is
      // 0.16 m apart at a home 8 m from the origin, though both fixes put the vehicle within a
      // centimetre of the same pose.
      const Pose2 predicted = pending_.compose(in->pose);
      const bool agrees = have_pending_ &&
                          std::hypot(predicted.x - r.pose.x, predicted.y - r.pose.y) <= config_.agree_m &&
                          std::fabs(wrap_angle(predicted.theta - r.pose.theta)) <= config_.agree_rad;
      const bool new_view =
          std::hypot(in->pose.x - pending_view_.x, in->pose.y - pending_view_.y) >= config_.view_change_m ||
          std::fabs(wrap_angle(in->pose.theta - pending_view_.theta)) >= config_.view_change_rad;
      if (agrees && new_view) {
        PoseMeasurement2* out = out_.writable();
        *out = {};
        out->stamp = in->stamp;
        out->pose = r.pose;
        have_pending_ = false;
        ++counters_.confirmed;
        out_.post();
      } else if (!agrees) {
        pending_ = correction;
        pending_view_ = in->pose;
        have_pending_ = true;
      }  // the same fix from the same view: still waiting for another view
    }
  }
  in_.done();
}

}  // namespace kestrel::autonomy
