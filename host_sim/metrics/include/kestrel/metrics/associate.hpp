#pragma once
// Pairs the samples of two time-stamped sequences (an estimate and a reference) by nearest
// stamp, as the TUM benchmark's associate step does, for when an estimator skipped some
// inputs. Stamps need not be sorted (real logs step back in time now and then).
#include <span>
#include <vector>

#include "kestrel/core/time.hpp"
#include "kestrel/metrics/relative_pose_error.hpp"

namespace kestrel::metrics {

// For every a[i], the b[j] with the nearest stamp, if it is within max_dt; each b[j] is used at
// most once (the earliest a claiming it wins). Pairs are (i, j), in the order of a.
std::vector<PosePair> associate_by_stamp(std::span<const TimeUs> a, std::span<const TimeUs> b, Duration max_dt);

}  // namespace kestrel::metrics
