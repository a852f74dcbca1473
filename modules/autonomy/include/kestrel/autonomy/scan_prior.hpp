#pragma once
// The scan matcher's prior, from the navigation filter's state: where the filter puts the
// vehicle at the scan's stamp, how sure it is, and how it was moving during the sweep.
#include "kestrel/core/messages.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"

namespace kestrel::autonomy {

// The farthest the filter's state is carried back (or forward) to a scan's stamp. A scan
// stamped further from the filter than this came from a clock that jumped or from a laser that
// stalled; a prior extrapolated over it would centre the search on a guess, so there is none
// and the matcher falls back on its own constant-velocity prediction.
inline constexpr float kMaxPriorExtrapolationS = 0.5f;

// True with `prior` filled when the filter is valid, its state finite and the scan within
// kMaxPriorExtrapolationS of it; false (prior untouched) otherwise.
bool scan_prior_from_nav(const NavState& nav, TimeUs scan_stamp, scan_matching::PosePrior& prior);

// The same prior in the scan matcher's frame. The filter's frame is the matcher's moved by the
// SLAM's corrections (NavFilter::frame_correction(), world = correction * matcher), and the
// matcher's map stays where it was drawn.
scan_matching::PosePrior prior_in_matcher_frame(const scan_matching::PosePrior& world, const Pose2& frame_correction);

}  // namespace kestrel::autonomy
