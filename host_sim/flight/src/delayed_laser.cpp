#include "kestrel/flight/delayed_laser.hpp"

namespace kestrel::flight {

Status DelayedLaser::poll(LaserScan& out) {
  for (;;) {
    const Status s = inner_.poll(incoming_);
    if (s == Status::kNoData) break;
    if (s != Status::kOk) return s;
    if (!queue_.push({clock_.now() + delay_, incoming_})) {
      Pending oldest;
      (void)queue_.pop(oldest);
      ++dropped_;
      (void)queue_.push({clock_.now() + delay_, incoming_});
    }
  }
  const Pending* head = queue_.peek();
  if (head == nullptr || clock_.now() < head->release) return Status::kNoData;
  Pending p;
  (void)queue_.pop(p);
  out = p.scan;
  return Status::kOk;
}

}  // namespace kestrel::flight
