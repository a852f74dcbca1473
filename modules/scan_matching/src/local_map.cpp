#include "kestrel/scan_matching/local_map.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

LocalMap::LocalMap(const Params& p, LikelihoodMap& a, LikelihoodMap& b)
    : params_(p), maps_{&a, &b}, extractor_(p) {
  (void)configure(p);
}

Status LocalMap::configure(const Params& p) {
  if (p.keyframes < 1 || p.keyframes > kMaxKeyframes) return Status::kInvalidArgument;
  params_ = p;
  extractor_.set_params(p);
  for (LikelihoodMap* m : maps_) {
    const Status s = m->configure(p);
    if (!ok(s)) return s;
  }
  active_.store(-1);
  reader_.store(-1);
  count_ = head_ = 0;
  pending_ = false;
  while (queue_.pop(incoming_)) {
  }
  return Status::kOk;
}

const LikelihoodMap* LocalMap::acquire() {
  // Mark first, then confirm: a rebuild that loaded the index before the mark sees the mark,
  // one that swapped in between is caught by the second load.
  int idx = active_.load();
  for (;;) {
    reader_.store(idx);
    const int again = active_.load();
    if (again == idx) break;
    idx = again;
  }
  return idx < 0 ? nullptr : maps_[static_cast<std::size_t>(idx)];
}

Status LocalMap::rebuild() {
  while (queue_.pop(incoming_)) {
    const KeyScan& in = incoming_;
    const std::size_t k = params_.keyframes;
    if (in.restart) count_ = head_ = 0;
    const std::size_t slot = count_ < k ? (head_ + count_) % k : head_;
    if (count_ < k) {
      ++count_;
    } else {
      head_ = (head_ + 1) % k;
    }
    Stored& s = keys_[slot];
    s.pose = in.pose;
    s.points = in.points;
    extractor_.extract(s.points, s.contours);
    pending_ = true;
  }
  if (!pending_) return Status::kNoData;
  const int active = active_.load();
  const int target = active < 0 ? 0 : 1 - active;
  if (reader_.load() == target) return Status::kTimeout;
  const Status st = draw_into(*maps_[static_cast<std::size_t>(target)]);
  active_.store(target);
  generation_.fetch_add(1);
  pending_ = false;
  return st;
}

Status LocalMap::draw_into(LikelihoodMap& m) {
  const std::size_t k = params_.keyframes;
  const Stored& newest = keys_[(head_ + count_ - 1) % k];
  const float res = m.resolution_m();
  // Centre the window on the newest key scan, on a grid of whole cells.
  const float half = 0.5f * static_cast<float>(m.dim()) * res;
  m.begin(std::floor((newest.pose.x - half) / res) * res, std::floor((newest.pose.y - half) / res) * res);
  const float inv = static_cast<float>(kSub) / res;
  const float lim = static_cast<float>(m.dim() * kSub - 1);
  Status result = Status::kOk;
  for (std::size_t j = 0; j < count_; ++j) {
    const Stored& s = keys_[(head_ + j) % k];
    const float c = std::cos(s.pose.theta), sn = std::sin(s.pose.theta);
    const auto to_map = [&](uint16_t i, int16_t& mx, int16_t& my) {
      const float wx = s.pose.x + c * s.points.x[i] - sn * s.points.y[i];
      const float wy = s.pose.y + sn * s.points.x[i] + c * s.points.y[i];
      const float fx = (wx - m.origin_x_m()) * inv, fy = (wy - m.origin_y_m()) * inv;
      if (!(fx >= 0 && fx <= lim && fy >= 0 && fy <= lim)) return false;
      mx = static_cast<int16_t>(fx);
      my = static_cast<int16_t>(fy);
      return true;
    };
    MapSegment seg;
    for (uint16_t i = 0; i < s.contours.segment_count; ++i) {
      if (to_map(s.contours.seg_a[i], seg.ax, seg.ay) && to_map(s.contours.seg_b[i], seg.bx, seg.by)) {
        if (!ok(m.draw(seg))) result = Status::kCapacityExceeded;
      }
    }
    for (uint16_t i = 0; i < s.contours.point_count; ++i) {
      if (s.contours.degree[i] != 0) continue;
      if (to_map(i, seg.ax, seg.ay)) {
        seg.bx = seg.ax;
        seg.by = seg.ay;
        if (!ok(m.draw(seg))) result = Status::kCapacityExceeded;
      }
    }
  }
  m.finish();
  return result;
}

}  // namespace kestrel::scan_matching
