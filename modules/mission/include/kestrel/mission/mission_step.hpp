#pragma once
// The time one mission step may account for. The ramps integrate the time between steps and
// the held-descent wait adds it up; after a long gap (a stalled loop) a set-point must not
// leap, nor a second's wait pass in two steps, so a step counts for at most this.
namespace kestrel::mission {

inline constexpr float kMaxStepS = 0.1f;

}  // namespace kestrel::mission
