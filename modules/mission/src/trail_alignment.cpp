#include "kestrel/mission/trail_alignment.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace kestrel::mission {
namespace {
// Shorter than this, a stretch has no direction to speak of.
constexpr float kMinStretchM = 0.2f;
// Offsets at most this far along the stretch's way (a quarter of a turn's worth of drift).
constexpr float kMaxAlongM = 0.3f;

// Each breadcrumb's cell, once: the offsets are whole cells, so a candidate is integer look-ups.
struct Scorer {
  const ScanFreeSpace& free_space;
  std::span<const Point2> breadcrumbs;
  std::span<const ScanFreeSpace::Cell> cells;
  std::span<const KeepOut> keep_out;
  float grow;

  // The breadcrumbs free in a row from the next one, then those of them free by the wide
  // clearance: the trail was flown in one piece from where the vehicle is, so a stretch moved
  // into the corridor behind it, free but cut from the way ahead, scores nothing past the cut.
  // The keep-out boxes (float geometry) are asked only by `with_keep_out`: they can only lower
  // a score, so a candidate that cannot win without them is never asked.
  int operator()(int i, int j, bool with_keep_out) const {
    int in_row = 0, wide = 0;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const ScanFreeSpace::Clearance c = free_space.at({cells[k].x + i, cells[k].y + j});
      if (c == ScanFreeSpace::Clearance::kNotFree) break;
      if (with_keep_out && kept_out({breadcrumbs[k].x + static_cast<float>(i) * ScanFreeSpace::kCellM,
                                     breadcrumbs[k].y + static_cast<float>(j) * ScanFreeSpace::kCellM}))
        break;
      ++in_row;
      if (c == ScanFreeSpace::Clearance::kWide) ++wide;
    }
    return in_row * kWideWeight + wide;
  }
  bool kept_out(Point2 p) const {
    for (const KeepOut& k : keep_out)
      if (k.crossed_by(p, p, grow)) return true;
    return false;
  }
  static constexpr int kWideWeight = 64;  // above any count of wide ones
  static constexpr std::size_t kMaxBreadcrumbs = 32;
};
}  // namespace

bool find_trail_offset(const ScanFreeSpace& free_space, std::span<const Point2> breadcrumbs, float max_offset_m,
                       std::span<const KeepOut> keep_out, float keep_out_grow_m, Point2& offset) {
  if (breadcrumbs.empty() || breadcrumbs.size() > Scorer::kMaxBreadcrumbs || !(max_offset_m > 0.0f)) return false;
  std::array<ScanFreeSpace::Cell, Scorer::kMaxBreadcrumbs> cells;
  for (std::size_t k = 0; k < breadcrumbs.size(); ++k) cells[k] = free_space.cell_of(breadcrumbs[k]);
  const Scorer score{free_space, breadcrumbs, {cells.data(), breadcrumbs.size()}, keep_out, keep_out_grow_m};
  const bool boxes = !keep_out.empty();
  const int steps = static_cast<int>(std::min(max_offset_m, 1.0f) / ScanFreeSpace::kCellM + 1e-3f);
  // The way the stretch leads: an offset mostly along it would slide the stretch back towards
  // the vehicle (free, behind it), not onto where it was flown beside it.
  const Point2 first = breadcrumbs.front(), last = breadcrumbs.back();
  const float length = std::hypot(last.x - first.x, last.y - first.y);
  const float along_x = length > kMinStretchM ? (last.x - first.x) / length : 0.0f;
  const float along_y = length > kMinStretchM ? (last.y - first.y) / length : 0.0f;
  const float max_along_cells = kMaxAlongM / ScanFreeSpace::kCellM + 1e-3f;
  // A stretch (two breadcrumbs, where there are two) must come free in a row: one alone, moved
  // into whatever is free nearest, says nothing.
  const int needed = std::min<int>(2, static_cast<int>(breadcrumbs.size())) * Scorer::kWideWeight;
  int best = std::max(score(0, 0, boxes), needed - 1), best_d2 = 0, best_i = 0, best_j = 0;
  for (int j = -steps; j <= steps; ++j) {
    for (int i = -steps; i <= steps; ++i) {
      const int d2 = i * i + j * j;
      if (d2 == 0 || d2 > steps * steps) continue;
      if (std::fabs(static_cast<float>(i) * along_x + static_cast<float>(j) * along_y) > max_along_cells) continue;
      const auto better = [&](int n) { return n > best || (n == best && best_d2 > 0 && d2 < best_d2); };
      if (!better(score(i, j, false))) continue;
      const int n = boxes ? score(i, j, true) : score(i, j, false);
      if (!better(n)) continue;
      best = n;
      best_d2 = d2;
      best_i = i;
      best_j = j;
    }
  }
  if (best_d2 == 0) return false;  // nothing beat the trail as it lies (and a stretch's worth)
  offset = {static_cast<float>(best_i) * ScanFreeSpace::kCellM, static_cast<float>(best_j) * ScanFreeSpace::kCellM};
  return true;
}

}  // namespace kestrel::mission
