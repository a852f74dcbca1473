#pragma once
// Work units of SRT-Star's arrival step (sectors, erosion, tree update, waypoint choice), done in
// slices so that one guidance cycle stays inside its share of the loop budget on the Verdex
// (DESIGN.md: 5 ms of each 100 ms scan period at 400 MHz, about 2 M cycles, for guidance). A
// unit is about 100 instructions of the PXA270 (software floating point); the weights below
// come from `kestrel-budget insns` on the exploration benchmarks (README of this module).
#include <cstdint>

namespace kestrel::exploration::work {

inline constexpr uint32_t kUnbounded = 0xFFFFFFFFu;  // a budget that never runs out: one call
inline constexpr uint32_t kClassify = 200;           // SectorScan::begin, the integer pass over a scan
inline constexpr uint32_t kTableEntry = 12;          // one sine and one cosine (measured 1,170)
inline constexpr uint32_t kSkipBeams = 8;            // beams per unit that cannot shorten any ray
// The erosion, fitted to two scenes (a 6 x 4 m room: 481 eroding returns, 2,202 rays out at
// the first test, 649 at the side test, 3,155 to the square root, 5.14 M instructions; a 1.4 m
// corridor: 617, 5,463, 799, 10,614, 14.69 M): about 1,500 a return, 300 / 600 / 1,080 a ray.
inline constexpr uint32_t kErodeBeam = 15;  // a return that can shorten rays: arcsine, bounds
inline constexpr uint32_t kErodeRay = 3;    // one ray tested against it ...
inline constexpr uint32_t kErodeSide = 3;   // ... that passed the first test (side offset)
inline constexpr uint32_t kErodeRoot = 5;   // ... that needed the square root
inline constexpr uint32_t kFinish = 100;             // rounding the rays, finding the frontiers
inline constexpr uint32_t kRegionTest = 4;           // a point against a safe region's reach
inline constexpr uint32_t kRegionAngle = 40;         // ... and against its sector (atan2)
inline constexpr uint32_t kPathBeam = 10;            // one return against a straight path
                                                     // (a trail point against a retrace leg too)
inline constexpr uint32_t kTrailPoint = 4;           // a trail point's squared distance to a place:
                                                     // 265 instructions measured (1,024 points,
                                                     // exploration/trail_search/1024), charged 400
                                                     // as kRegionTest, whose arithmetic it is
inline constexpr uint32_t kKeepOutTest = 20;         // a segment against the keep-out boxes
inline constexpr uint32_t kFrontierScan = 16;        // frontiers per unit when picking one of a node
inline constexpr uint32_t kGridCells = 2;            // visited-grid cells per unit: UnflownBearings::count,
                                                     // charged 54.4 k for its 33 x 33; 49.0 k measured
                                                     // with every cell in reach unflown inside the
                                                     // extent (exploration/unflown_count_all_unflown;
                                                     // 37.4 k at exploration/unflown_count). Charged
                                                     // 36.3 k before session 42, the trail's count of a
                                                     // retrace took 1.74 M in one cycle
                                                     // (exploration/srt_retrace_cycles)
inline constexpr uint32_t kFrontierCells = 1;        // ... counting frontier cells (up to five lookups
                                                     // each): 83.6 k measured (exploration/
                                                     // frontier_count), 92.8 k at worst, nothing seen
                                                     // in reach (..._nothing_seen), charged 109 k
inline constexpr uint32_t kSeenStep = 7;             // one step along a beam, its cell marked seen (two
                                                     // divisions and floors in software): a URG-04LX
                                                     // slice in a 6 x 4 m room measured 280 k over the
                                                     // guidance step (exploration/guidance_step_
                                                     // frontier_marks), about 700 a step

}  // namespace kestrel::exploration::work
