#include "kestrel/scan_matching/correlative_search.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

Status CorrelativeSearch::setup(const ScanPoints& pts, const Pose2& centre, const LikelihoodMap& map,
                                int half_cells, int half_steps, float step_rad) {
  if (half_cells < 0 || half_cells > kMaxWindowCells || half_steps < 0 || half_steps > kMaxThetaSteps ||
      !(step_rad >= 0) || !centre.finite()) {
    return Status::kInvalidArgument;
  }
  map_ = &map;
  n_ = pts.count;
  const float inv = 1.0f / map.resolution_m();
  for (uint16_t i = 0; i < n_; ++i) {
    px_[i] = pts.x[i] * inv;
    py_[i] = pts.y[i] * inv;
  }
  centre_ = centre;
  cx_cells_ = (centre.x - map.origin_x_m()) * inv;
  cy_cells_ = (centre.y - map.origin_y_m()) * inv;
  step_rad_ = step_rad;
  half_cells_ = half_cells;
  half_steps_ = half_steps;
  top_level_ = 0;
  while ((1 << top_level_) < 2 * half_cells + 1) ++top_level_;
  rotated_k_ = 1 << 30;
  nodes_ = 0;
  return Status::kOk;
}

Pose2 CorrelativeSearch::pose_of(float k, float tx, float ty) const {
  const float res = map_->resolution_m();
  return {centre_.x + tx * res, centre_.y + ty * res, wrap_angle(centre_.theta + k * step_rad_)};
}

// The scan is transformed once per rotation: every translation is an integer cell offset.
void CorrelativeSearch::rotate(int k) {
  if (k == rotated_k_) return;
  rotated_k_ = k;
  const float th = centre_.theta + static_cast<float>(k) * step_rad_;
  const float c = std::cos(th), s = std::sin(th);
  // floor() without a library call: truncate, then step down for negative fractions.
  const auto floor_i = [](float v) {
    const auto t = static_cast<int32_t>(v);
    return t - static_cast<int32_t>(v < static_cast<float>(t));
  };
  for (uint16_t i = 0; i < n_; ++i) {
    qx_[i] = floor_i(c * px_[i] - s * py_[i] + cx_cells_);
    qy_[i] = floor_i(s * px_[i] + c * py_[i] + cy_cells_);
  }
}

int32_t CorrelativeSearch::bound(int level, int tx, int ty) const {
  int32_t sum = 0;
  if (level == 0) {
    const unsigned d = static_cast<unsigned>(map_->dim());
    const uint8_t* cells = map_->cells();
    for (uint16_t i = 0; i < n_; ++i) {
      const unsigned x = static_cast<unsigned>(qx_[i] + tx), y = static_cast<unsigned>(qy_[i] + ty);
      if (x < d && y < d) sum += cells[y * d + x];
    }
    return sum;
  }
  const int s = 1 << level;
  const unsigned d = static_cast<unsigned>(level_dim(map_->dim(), level));
  const uint8_t* cells = map_->level(level);
  for (uint16_t i = 0; i < n_; ++i) {
    // Arithmetic shift floors; a negative index means every reachable fine cell is outside.
    const unsigned x = static_cast<unsigned>((qx_[i] + tx + s) >> level);
    const unsigned y = static_cast<unsigned>((qy_[i] + ty + s) >> level);
    if (x < d && y < d) sum += cells[y * d + x];
  }
  return sum;
}

int32_t CorrelativeSearch::score(int k, int tx, int ty) {
  rotate(k);
  return bound(0, tx, ty);
}

bool CorrelativeSearch::better(const GridPose& a, const GridPose& b) {
  if (a.score != b.score) return a.score > b.score;
  // Equal scores: the one nearest the prediction. Along a corridor the score is flat over the
  // whole window, and a tie broken towards one corner (lowest k, ty, tx) drags every match
  // that way: measured in closed loop, an estimate 0.1 m/s slower than the vehicle.
  const int ak = std::abs(a.k), bk = std::abs(b.k);
  if (ak != bk) return ak < bk;
  const int ad = a.tx * a.tx + a.ty * a.ty, bd = b.tx * b.tx + b.ty * b.ty;
  if (ad != bd) return ad < bd;
  if (a.k != b.k) return a.k < b.k;
  if (a.ty != b.ty) return a.ty < b.ty;
  return a.tx < b.tx;
}

// Image addition: adds each point's map window to the score image, one row at a time.
void CorrelativeSearch::accumulate(int x0, int y0, int half) {
  const int w = 2 * half + 1;
  const int d = map_->dim();
  const uint8_t* cells = map_->cells();
  std::fill(acc_.begin(), acc_.begin() + w * w, uint16_t{0});
  for (uint16_t i = 0; i < n_; ++i) {
    const int bx = qx_[i] + x0, by = qy_[i] + y0;  // map cell of window entry (0, 0)
    const int ux0 = std::max(0, -bx), ux1 = std::min(w, d - bx);
    const int uy0 = std::max(0, -by), uy1 = std::min(w, d - by);
    if (ux0 >= ux1) continue;
    for (int uy = uy0; uy < uy1; ++uy) {
      const uint8_t* src = cells + static_cast<std::size_t>(by + uy) * d + bx;
      uint16_t* dst = acc_.data() + uy * w;
      for (int ux = ux0; ux < ux1; ++ux) dst[ux] = static_cast<uint16_t>(dst[ux] + src[ux]);
    }
  }
}

GridPose CorrelativeSearch::exhaustive() {
  GridPose best;
  const int h = std::min(half_cells_, kMaxExhaustiveWindow);
  const int w = 2 * h + 1;
  for (int k = -half_steps_; k <= half_steps_; ++k) {
    rotate(k);
    accumulate(-h, -h, h);
    for (int uy = 0; uy < w; ++uy) {
      for (int ux = 0; ux < w; ++ux) {
        const int32_t v = acc_[static_cast<std::size_t>(uy * w + ux)];
        const GridPose cand{k, ux - h, uy - h, v};
        if (better(cand, best)) best = cand;
      }
    }
    nodes_ += static_cast<uint64_t>(w) * w;
  }
  return best;
}

const uint16_t* CorrelativeSearch::slice(int k, int cx, int cy, int half) {
  half = std::clamp(half, 0, kMaxExhaustiveWindow);
  rotate(k);
  accumulate(cx - half, cy - half, half);
  return acc_.data();
}

void CorrelativeSearch::dfs(int k, int32_t root_bound, GridPose& best) {
  std::size_t top = 0;
  stack_[top++] = {-half_cells_, -half_cells_, root_bound, static_cast<int8_t>(top_level_)};
  while (top > 0) {
    const Node n = stack_[--top];
    ++nodes_;
    if (n.bound < best.score) continue;  // pruned: nothing in this block can win
    if (n.level == 0) {
      const GridPose cand{k, n.tx, n.ty, n.bound};
      if (better(cand, best)) best = cand;
      continue;
    }
    const int level = n.level - 1;
    const int half = 1 << level;
    Node kids[4];
    int nk = 0;
    for (int c = 0; c < 4; ++c) {
      const int tx = n.tx + ((c & 1) ? half : 0), ty = n.ty + ((c & 2) ? half : 0);
      if (tx > half_cells_ || ty > half_cells_) continue;  // block entirely outside the window
      const int32_t b = bound(level, tx, ty);
      if (b < best.score) continue;
      kids[nk++] = {tx, ty, b, static_cast<int8_t>(level)};
    }
    // Push the best bound last so it is explored first; equal bounds keep (y, x) order.
    // Insertion sort: at most four children (and std::sort on a 4-array trips GCC 12's
    // array-bounds analysis under the sanitizers).
    const auto before = [](const Node& a, const Node& b) {
      if (a.bound != b.bound) return a.bound < b.bound;
      if (a.ty != b.ty) return a.ty > b.ty;
      return a.tx > b.tx;
    };
    for (int i = 1; i < nk; ++i) {
      const Node key = kids[i];
      int j = i - 1;
      while (j >= 0 && before(key, kids[j])) {
        kids[j + 1] = kids[j];
        --j;
      }
      kids[j + 1] = key;
    }
    for (int c = 0; c < nk; ++c) stack_[top++] = kids[c];
  }
}

GridPose CorrelativeSearch::branch_and_bound(const GridPose* seeds, int seed_count) {
  const int nt = 2 * half_steps_ + 1;
  for (int k = -half_steps_; k <= half_steps_; ++k) {
    rotate(k);
    order_[static_cast<std::size_t>(k + half_steps_)] = {bound(top_level_, -half_cells_, -half_cells_), k};
  }
  std::sort(order_.begin(), order_.begin() + nt, [](const ThetaBound& a, const ThetaBound& b) {
    return a.bound != b.bound ? a.bound > b.bound : a.k < b.k;
  });
  // The prediction itself is a real candidate: starting from its exact score prunes early.
  GridPose best;
  if (half_steps_ >= 0) {
    rotate(0);
    best = {0, 0, 0, bound(0, 0, 0)};
  }
  for (int i = 0; i < seed_count; ++i) {
    const GridPose& sd = seeds[i];
    if (std::abs(sd.k) > half_steps_ || std::abs(sd.tx) > half_cells_ || std::abs(sd.ty) > half_cells_) continue;
    rotate(sd.k);
    const GridPose cand{sd.k, sd.tx, sd.ty, bound(0, sd.tx, sd.ty)};
    if (better(cand, best)) best = cand;
  }
  for (int i = 0; i < nt; ++i) {
    const ThetaBound& t = order_[static_cast<std::size_t>(i)];
    if (t.bound < best.score) break;  // sorted: no later rotation can win either
    rotate(t.k);
    dfs(t.k, t.bound, best);
  }
  return best;
}

GridPose CorrelativeSearch::best_at(int k, int seed_tx, int seed_ty) {
  rotate(k);
  // A real pose of this rotation seeds the search: exact, and it prunes from the start.
  GridPose best{k, seed_tx, seed_ty, bound(0, seed_tx, seed_ty)};
  dfs(k, bound(top_level_, -half_cells_, -half_cells_), best);
  return best;
}

}  // namespace kestrel::scan_matching
