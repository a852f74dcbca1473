#pragma once
// A scan's contours drawn into a likelihood map at a world pose: its segments as segments, its
// one-point contours as dots. Shared by the local map (the last k key scans) and the
// relocaliser (the take-off turn's reference scans), so both maps hold the same picture of a
// scan.
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/scan_matching/contour_extractor.hpp"
#include "kestrel/scan_matching/likelihood_map.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

// Between the map's begin() and finish(). A segment or dot with an end outside the map (or not
// finite) is left out: the map is a window on the world. kCapacityExceeded when the map's
// segment list filled up (what fitted is drawn), otherwise kOk.
Status draw_contours(LikelihoodMap& map, const Pose2& pose, const ScanPoints& pts, const Contours& contours);

}  // namespace kestrel::scan_matching
