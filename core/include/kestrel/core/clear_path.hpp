#pragma once
// Whether a scan vouches for a straight way: the flight home's shortcut (mission_controller.hpp)
// leaves the breadcrumb trail only where the laser sees the way clear.
#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"

namespace kestrel {

// True when the straight path from the laser, at `laser` (world frame: beam i points along
// laser.theta + scan.angle_of(i)), to `target` keeps `clearance_m` from every return of `scan`.
// False where the scan cannot say: the target is farther than max_range_mm less the clearance
// (a beam with no return then proves nothing that far), or the path's corridor is not wholly
// inside the field of view (its edge directions included), or a beam between those edge
// directions said nothing (deflected, dropped out or too near: kNoReturn is open space), or an
// input is not finite or not positive. A return whose nearest point of the path is its start
// is one the vehicle leaves behind, and does not block it; one the start is already within the
// clearance of (a vehicle held off a wall) blocks it only if the path closes in on it by more
// than 5 cm. Outside those edge directions, range codes block nothing (the returns on either
// side of a dropout beside the start still show what is there).
// Float, one pass over the beams, the beam directions by rotation (four trigonometric calls in
// all).
bool straight_path_clear(const LaserScan& scan, const Pose2& laser, Point2 target, float clearance_m);

}  // namespace kestrel
