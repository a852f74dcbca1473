#include "kestrel/scan_matching/local_map.hpp"

#include "kestrel/scan_matching/contour_drawing.hpp"

#include <algorithm>

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
  m.begin_centred(newest.pose.x, newest.pose.y);
  Status result = Status::kOk;
  for (std::size_t j = 0; j < count_; ++j) {
    const Stored& s = keys_[(head_ + j) % k];
    if (!ok(draw_contours(m, s.pose, s.points, s.contours))) result = Status::kCapacityExceeded;
  }
  m.finish();
  return result;
}

}  // namespace kestrel::scan_matching
