#pragma once
// A fixed-capacity FIFO of set-points, each held until its due time: the transport and
// processing delay between the companion computer and the autopilot. Paper 000 (Figure 3b)
// shows how a 0.2 s delay degrades hover; the simulator makes the delay a parameter.
#include <array>
#include <cstddef>

#include "kestrel/core/messages.hpp"

namespace kestrel::sim {

template <std::size_t N>
class CommandDelayLine {
 public:
  // False when full (the set-point is dropped) or when `due` precedes the last one queued
  // (due times must not go backwards).
  bool push(TimeUs due, const AttitudeSetpoint& sp) {
    if (size_ == N) return false;
    if (size_ > 0 && due < slots_[(head_ + size_ - 1) % N].due) return false;
    slots_[(head_ + size_) % N] = {due, sp};
    ++size_;
    return true;
  }
  // Moves every set-point due at or before `now` into `active` (the newest wins). Returns
  // true if `active` changed.
  bool release(TimeUs now, AttitudeSetpoint& active) {
    bool changed = false;
    while (size_ > 0 && slots_[head_].due <= now) {
      active = slots_[head_].sp;
      head_ = (head_ + 1) % N;
      --size_;
      changed = true;
    }
    return changed;
  }
  std::size_t size() const { return size_; }
  void clear() { size_ = 0; }

 private:
  struct Slot {
    TimeUs due;
    AttitudeSetpoint sp;
  };
  std::array<Slot, N> slots_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace kestrel::sim
