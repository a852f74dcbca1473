#pragma once
// The breadcrumb trail laid back onto what the laser sees, when the flight home stalls. The trail
// was drawn in the estimate's frame as it stood then; the estimate drifts along a corridor and
// its late corrections do not reach all of what was drawn before, so a stretch of trail can
// lie half a metre off where the vehicle flew (gt-building, URG-04LX: beside a door, the trail
// through the door's jamb, the vehicle held off the wall until the stall landed it 17 m from
// home). Every stretch of trail was flown, so where it truly lies is free space: the offset
// that puts most of the next breadcrumbs where the newest scan shows free space is where that
// stretch lies now.
#include <span>

#include "kestrel/core/keep_out.hpp"
#include "kestrel/core/scan_free_space.hpp"
#include "kestrel/core/se2.hpp"

namespace kestrel::mission {

// Offsets on a grid of ScanFreeSpace::kCellM within `max_offset_m` of none (at most 1 m), each
// scored by how many breadcrumbs, from the first (the next one home) on, land free in a row
// (clear of returns by the near clearance, and outside every operator's keep-out box grown by
// `keep_out_grow_m`: glass, which the laser shows free), then by how many of those are free by
// the wide clearance too, so the middle of a door scores above its edge. The best score wins,
// the smallest offset among equals; `offset` is set and true returned only when it beats the
// trail as it lies (offset zero) and brings two breadcrumbs in a row (one, if there is one)
// free. Offsets more than 0.3 m along the stretch's way (first to last breadcrumb) are not
// tried: they slide the stretch back into the free space the vehicle stands in. At most 317
// offsets, each an integer look-up per breadcrumb; at most 32 breadcrumbs.
bool find_trail_offset(const ScanFreeSpace& free_space, std::span<const Point2> breadcrumbs, float max_offset_m,
                       std::span<const KeepOut> keep_out, float keep_out_grow_m, Point2& offset);

}  // namespace kestrel::mission
