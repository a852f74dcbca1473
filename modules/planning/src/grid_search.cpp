#include "kestrel/planning/grid_search.hpp"

#include <algorithm>

namespace kestrel::planning {
namespace {

constexpr uint16_t kNil = 0xFFFF;
static_assert(GridSearch::kMaxOpen < kNil, "entry links are 16-bit");
static_assert(GridSearch::kBuckets > 14 + (14 * SearchCosts::kMaxPenalty) / 10, "a step must not wrap the bucket ring");

struct Step {
  int dx, dy;
  uint16_t base;
};
constexpr Step kSteps[8] = {{1, 0, 10}, {-1, 0, 10}, {0, 1, 10},  {0, -1, 10},
                            {1, 1, 14}, {1, -1, 14}, {-1, 1, 14}, {-1, -1, 14}};

}  // namespace

Status SearchCosts::validate() const {
  const bool far_ok = far_penalty == 0 || far > soft;
  return soft >= lethal && soft_penalty <= kMaxPenalty && far_penalty <= kMaxPenalty - soft_penalty && far_ok
             ? Status::kOk
             : Status::kInvalidArgument;
}

bool GridSearch::push(uint32_t cell, uint16_t c) {
  if (free_head_ == kNil) return false;
  const uint16_t e = free_head_;
  free_head_ = entry_next_[e];
  entry_cell_[e] = cell;
  const std::size_t b = c % kBuckets;
  entry_next_[e] = bucket_head_[b];
  bucket_head_[b] = e;
  ++open_;
  peak_open_ = std::max(peak_open_, open_);
  return true;
}

Status GridSearch::run(const OccupancyGrid& grid, const ObstacleDistance& distance, const CellBox& box, Cell start,
                       const SearchCosts& costs) {
  box_ = {};
  peak_open_ = 0;
  if (costs.validate() != Status::kOk) return Status::kInvalidArgument;
  const CellBox b{std::max(0, box.x0), std::max(0, box.y0), std::min(kGridSide - 1, box.x1),
                  std::min(kGridSide - 1, box.y1)};
  if (b.empty() || !b.contains(start.x, start.y)) return Status::kOutOfRange;
  box_ = b;
  start_ = start;
  for (int y = b.y0; y <= b.y1; ++y) std::fill_n(&cost_[cell_index(b.x0, y)], b.x1 - b.x0 + 1, kUnreached);
  for (std::size_t e = 0; e < kMaxOpen; ++e) entry_next_[e] = static_cast<uint16_t>(e + 1 < kMaxOpen ? e + 1 : kNil);
  free_head_ = 0;
  bucket_head_.fill(kNil);
  open_ = 0;

  // The penalty of entering a cell, per straight step, by its obstacle distance.
  std::array<uint16_t, 256> penalty{};
  if (costs.soft > costs.lethal) {
    for (int d = costs.lethal; d < costs.soft; ++d)
      penalty[static_cast<std::size_t>(d)] =
          static_cast<uint16_t>(costs.soft_penalty * (costs.soft - d) / (costs.soft - costs.lethal));
  }
  if (costs.far_penalty > 0)
    for (std::size_t d = costs.far; d < penalty.size(); ++d) penalty[d] = costs.far_penalty;

  const std::size_t s = cell_index(start.x, start.y);
  cost_[s] = 0;
  (void)push(static_cast<uint32_t>(s), 0);
  uint32_t current = 0;  // the cost whose bucket is being emptied
  while (open_ > 0) {
    const std::size_t bucket = current % kBuckets;
    const uint16_t e = bucket_head_[bucket];
    if (e == kNil) {
      ++current;
      continue;
    }
    bucket_head_[bucket] = entry_next_[e];
    const uint32_t cell = entry_cell_[e];
    entry_next_[e] = free_head_;
    free_head_ = e;
    --open_;
    if (cost_[cell] != current) continue;  // improved since it was queued
    const int cx = static_cast<int>(cell % kGridSide), cy = static_cast<int>(cell / kGridSide);
    const uint8_t here = distance.at(cx, cy);
    for (const Step& st : kSteps) {
      const int nx = cx + st.dx, ny = cy + st.dy;
      if (!b.contains(nx, ny)) continue;
      const std::size_t n = cell_index(nx, ny);
      if (!occupancy::is_free(grid.at(nx, ny))) continue;
      const uint8_t d = distance.at(nx, ny);
      if (d < costs.lethal && !(here < costs.lethal && d >= here)) continue;
      const uint32_t c = current + st.base + penalty[d] * st.base / 10;
      if (c >= kUnreached || c >= cost_[n]) continue;
      cost_[n] = static_cast<uint16_t>(c);
      if (!push(static_cast<uint32_t>(n), static_cast<uint16_t>(c))) {
        box_ = {};
        return Status::kCapacityExceeded;
      }
    }
  }
  return Status::kOk;
}

Status GridSearch::path_to(Cell goal, PathCells& out) const {
  out.clear();
  if (!reached(goal)) return Status::kNotFound;
  // Goal to start, reversed at the end. Each step strictly lowers the cost (the cell's
  // predecessor is cheaper), so the walk ends at the start, the only cell of cost 0.
  Cell c = goal;
  for (;;) {
    if (!out.push_back(c)) {
      std::reverse(out.begin(), out.end());
      return Status::kCapacityExceeded;
    }
    const uint16_t here = cost(c);
    if (here == 0) break;
    Cell best = c;
    uint16_t best_cost = here;
    for (const Step& st : kSteps) {
      const Cell n{static_cast<int16_t>(c.x + st.dx), static_cast<int16_t>(c.y + st.dy)};
      const uint16_t k = cost(n);
      if (k < best_cost) {
        best_cost = k;
        best = n;
      }
    }
    if (best == c) break;  // cannot happen on a finished search; stops a corrupted one
    c = best;
  }
  std::reverse(out.begin(), out.end());
  return Status::kOk;
}

}  // namespace kestrel::planning
