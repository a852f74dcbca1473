#include "kestrel/autonomy/home_fix.hpp"

#include <cmath>

namespace kestrel::autonomy {

Status validate(const HomeFixConfig& c) {
  if (scan_matching::validate(c.search) != Status::kOk) return Status::kInvalidArgument;
  const auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };  // false for NaN
  if (!in(c.survey_rad, 0.0f, 12.5f) || !in(c.home_survey_rad, 0.0f, 12.5f) || !in(c.reference_window_s, 0.0f, 600.0f) || !in(c.reference_spacing_m, 0.1f, 20.0f) ||
      !in(c.reference_turn_rad, 0.05f, 3.2f) || !in(c.radius_m, 0.0f, 12.0f) || !in(c.period_s, 0.05f, 60.0f) ||
      !in(c.agree_m, 0.01f, 2.0f) || !in(c.agree_rad, 0.001f, 1.0f) || !in(c.view_change_m, 0.0f, 10.0f) ||
      !in(c.view_change_rad, 0.0f, 3.2f))
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
  in_full_.store(false);
  out_ready_.store(false);
  counters_ = {};
  configured_ = c.enabled;
  return Status::kOk;
}

bool HomeFix::hand_over(const scan_matching::ScanPoints& points, const LaserScan& scan, const Pose2& pose, bool reference) {
  if (in_full_.load(std::memory_order_acquire)) return false;
  in_.points = points;
  in_.scan = scan;
  in_.pose = pose;
  in_.stamp = scan.stamp;
  in_.reference = reference;
  in_full_.store(true, std::memory_order_release);
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
    const bool moved = std::hypot(pose.x - last_reference_.x, pose.y - last_reference_.y) >= config_.reference_spacing_m ||
                       std::fabs(wrap_angle(pose.theta - last_reference_.theta)) >= config_.reference_turn_rad;
    if (moved && may_reference && hand_over(points, scan, pose, true)) {
      last_reference_ = pose;
      ++references_offered_;
    }
    return;
  }
  if (!flying_home || std::hypot(pose.x - home_.x, pose.y - home_.y) > config_.radius_m) return;
  if (searched_ && (stamp - last_search_).seconds() < static_cast<double>(config_.period_s)) return;
  if (out_ready_.load(std::memory_order_acquire)) return;  // a fix not yet taken: the guess would be stale
  if (hand_over(points, scan, pose, false)) {
    last_search_ = stamp;
    searched_ = true;
  }
}

bool HomeFix::take(PoseMeasurement2& fix) {
  if (!out_ready_.load(std::memory_order_acquire)) return false;
  fix = out_;
  out_ready_.store(false, std::memory_order_release);
  return true;
}

void HomeFix::background_step() {
  if (!in_full_.load(std::memory_order_acquire) || out_ready_.load(std::memory_order_acquire)) return;
  if (in_.reference) {
    if (relocaliser_.add_reference(in_.points, in_.pose) == Status::kOk) ++counters_.references;
  } else {
    ++counters_.searches;
    const scan_matching::Relocalisation r = relocaliser_.locate(in_.points, in_.pose, &in_.scan);
    if (!r.fixed()) {
      have_pending_ = false;
      switch (r.outcome) {
        case scan_matching::RelocaliseOutcome::kNoGain: ++counters_.no_gain; break;
        case scan_matching::RelocaliseOutcome::kAmbiguous: ++counters_.ambiguous; break;
        case scan_matching::RelocaliseOutcome::kSeesThrough: ++counters_.sees_through; break;
        default: ++counters_.no_fit; break;
      }
    } else {
      ++counters_.found;
      const Pose2 correction = r.pose.compose(in_.pose.inverse());
      const Pose2 diff = correction.compose(pending_.inverse());
      const bool agrees = have_pending_ && std::hypot(diff.x, diff.y) <= config_.agree_m && std::fabs(diff.theta) <= config_.agree_rad;
      const bool new_view = std::hypot(in_.pose.x - pending_view_.x, in_.pose.y - pending_view_.y) >= config_.view_change_m ||
                            std::fabs(wrap_angle(in_.pose.theta - pending_view_.theta)) >= config_.view_change_rad;
      if (agrees && new_view) {
        out_ = {};
        out_.stamp = in_.stamp;
        out_.pose = r.pose;
        have_pending_ = false;
        ++counters_.confirmed;
        out_ready_.store(true, std::memory_order_release);
      } else if (!agrees) {
        pending_ = correction;
        pending_view_ = in_.pose;
        have_pending_ = true;
      }  // the same fix from the same view: still waiting for another view
    }
  }
  in_full_.store(false, std::memory_order_release);
}

}  // namespace kestrel::autonomy
