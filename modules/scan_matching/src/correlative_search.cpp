#include "kestrel/scan_matching/correlative_search.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

Status CorrelativeSearch::setup(const ScanPoints& pts, const Pose2& centre, const LikelihoodMap& map,
                                int half_cells, int half_steps, float step_rad, int slice_half, float max_range_m,
                                const SeenDiscs* seen) {
  if (half_cells < 0 || half_cells > kMaxWindowCells || half_steps < 0 || half_steps > kMaxThetaSteps ||
      !(step_rad >= 0) || !centre.finite() || slice_half < 0 || slice_half > kMaxExhaustiveWindow) {
    return Status::kInvalidArgument;
  }
  const float inv = 1.0f / map.resolution_m();
  const float cx = (centre.x - map.origin_x_m()) * inv, cy = (centre.y - map.origin_y_m()) * inv;
  // The centre in Q8 cells must fit int32.
  if (!(std::fabs(cx) < 4.0e6f) || !(std::fabs(cy) < 4.0e6f)) return Status::kInvalidArgument;
  // Points as int16 in 1/2^F cell, F as fine as the sensor's range allows (Q3 for 29 m at
  // 7.5 mm cells, Q5 for the URG-04LX's 4 m). From the range, not the scan's farthest point:
  // the precision, and so the answer, must not change from scan to scan with what is in view.
  float reach = max_range_m > 0 ? max_range_m : 0.0f;
  for (uint16_t i = 0; i < pts.count; ++i) {
    if (!std::isfinite(pts.x[i]) || !std::isfinite(pts.y[i])) return Status::kInvalidArgument;
    reach = std::max({reach, std::fabs(pts.x[i]), std::fabs(pts.y[i])});
  }
  reach *= inv;
  if (!(reach < 32000.0f)) return Status::kInvalidArgument;  // beyond int16 cells even at F = 0
  int f = 8;
  while (f > 0 && reach * static_cast<float>(1 << f) >= 32000.0f) --f;
  map_ = &map;
  n_ = pts.count;
  const float scale = inv * static_cast<float>(1 << f);
  // Round half away from zero, inline (std::lround is a library call per coordinate); the
  // magnitudes are below 32,000, so the conversion cannot overflow.
  const auto round16 = [](float v) { return static_cast<int16_t>(v < 0 ? v - 0.5f : v + 0.5f); };
  for (uint16_t i = 0; i < n_; ++i) {
    pxy_[2 * i] = round16(pts.x[i] * scale);
    pxy_[2 * i + 1] = round16(pts.y[i] * scale);
  }
  centre_ = centre;
  disc_count_ = 0;
  if (seen != nullptr && seen->count > 0) {
    // Shrunk by the search's reach, so a point kept is inside for every translation.
    const float r = seen->radius_m * inv - static_cast<float>(half_cells + slice_half);
    disc_r2_ = r > 0 ? static_cast<int64_t>(r * r) : -1;
    disc_count_ = std::min(seen->count, kMaxSeenDiscs);
    for (std::size_t i = 0; i < disc_count_; ++i) {
      const float dx = (seen->x[i] - map.origin_x_m()) * inv, dy = (seen->y[i] - map.origin_y_m()) * inv;
      if (!(std::fabs(dx) < 1.0e6f) || !(std::fabs(dy) < 1.0e6f)) return Status::kInvalidArgument;
      disc_x_[i] = static_cast<int32_t>(std::lround(dx));
      disc_y_[i] = static_cast<int32_t>(std::lround(dy));
    }
  }
  // The centre in Q8 cells, split into whole cells and the fraction in Q(F + 15).
  const auto q8x = static_cast<int32_t>(std::lround(cx * 256.0f)), q8y = static_cast<int32_t>(std::lround(cy * 256.0f));
  rot_.cx = q8x >> 8;
  rot_.cy = q8y >> 8;
  rot_.fx = (q8x & 255) << (f + kTrigBits - 8);
  rot_.fy = (q8y & 255) << (f + kTrigBits - 8);
  rot_.shift = f + kTrigBits;
  step_rad_ = step_rad;
  half_cells_ = half_cells;
  slice_half_ = slice_half;
  half_steps_ = half_steps;
  top_level_ = 0;
  while ((1 << top_level_) < 2 * half_cells + 1) ++top_level_;
  rotated_k_ = 1 << 30;
  runs_level_ = 0;
  nodes_ = 0;
  return Status::kOk;
}

Pose2 CorrelativeSearch::pose_of(float k, float tx, float ty) const {
  const float res = map_->resolution_m();
  return {centre_.x + tx * res, centre_.y + ty * res, wrap_angle(centre_.theta + k * step_rad_)};
}

// The scan is transformed once per rotation: every translation is an integer cell offset.
// The transform is fixed point (rotate_points.hpp: 16-bit points and Q15 cos and sin, 32-bit
// products, floor by arithmetic shift): the Verdex has no FPU, so the per-point work is
// integer, and SIMD targets do four points per instruction.
// Only the points that stay inside the map under every translation the search and its
// slices evaluate (the window plus the slice reach) are scored. A point that is inside for
// some translations and outside (scoring zero) for others would bias the search: along a
// corridor whose walls run past the map's edge, shifting the pose back towards the key scans
// brings more wall points into the map than it takes out at the far edge, and the optimum is
// dragged back (measured: up to 5 m over iarc-arena's 26 m hallway with a 0.3 m window). With
// one fixed set per rotation, every translation is judged on the same points.
void CorrelativeSearch::rotate(int k) {
  if (k == rotated_k_) return;
  rotated_k_ = k;
  runs_level_ = 0;
  const double th = static_cast<double>(centre_.theta) + static_cast<double>(k) * step_rad_;
  rot_.c = trig_q15(std::cos(th));
  rot_.s = trig_q15(std::sin(th));
  rotate_points(pxy_.data(), n_, rot_, qx_.data(), qy_.data());
  const int32_t reach = half_cells_ + slice_half_;
  const int32_t inner = map_->dim() - 2 * reach;  // cells x with x - reach and x + reach inside
  const auto span = static_cast<uint32_t>(std::max(inner, 0));
  // Compaction in place: the kept point i moves to slot m <= i.
  uint16_t m = 0;
  for (uint16_t i = 0; i < n_; ++i) {
    const int32_t x = qx_[i], y = qy_[i];
    qx_[m] = x;
    qy_[m] = y;
    m = static_cast<uint16_t>(m + (static_cast<uint32_t>(x - reach) < span && static_cast<uint32_t>(y - reach) < span &&
                                   seen_by_a_key_scan(x, y)));
  }
  nq_ = m;
}

// The same argument for the key scans' reach: a key scan drew its walls out to the laser's
// reach and no farther, and a scan from elsewhere sees its own out to the same reach. Its
// points beyond every key scan's reach score zero here and more of them land within reach as
// the pose shifts back towards the key scans: along a corridor whose ends are out of reach,
// every match was dragged back by its whole window (a URG-04LX flight along gt-building's
// corridor: 0.8 m/s flown, 0.2 m/s estimated).
bool CorrelativeSearch::seen_by_a_key_scan(int32_t x, int32_t y) const {
  if (disc_count_ == 0) return true;
  for (std::size_t i = 0; i < disc_count_; ++i) {
    const int64_t dx = x - disc_x_[i], dy = y - disc_y_[i];
    if (dx * dx + dy * dy <= disc_r2_) return true;
  }
  return false;
}

// The lowest level the search asks for (kLeafLevel, where it stops descending) straight from
// the points, each further level from the one below: with c the level-L base cell of a
// point, floor((c + 1) / 2) is its level-(L+1) base cell.
void CorrelativeSearch::build_runs(int level) {
  if (runs_level_ >= level && runs_first_ <= level) return;
  const auto merge_into = [](std::array<Run, kMaxPoints + 1>& out, auto&& source, int n) {
    // Branch-free merge (a branch on "same cell" mispredicts along ragged contours): the
    // cell is compared as one 32-bit key, the count kept by masking, and the current run
    // stored every step. Runs start at slot 1; slot 0 takes the sentinel, which matches no
    // cell (see below).
    const auto key = [](const Run& r) {
      return static_cast<uint32_t>(static_cast<uint16_t>(r.x)) |
             (static_cast<uint32_t>(static_cast<uint16_t>(r.y)) << 16);
    };
    uint32_t prev = key(Run{INT16_MIN, INT16_MIN, 0}), count = 0;
    int m = 0;  // slot of the current run
    for (int i = 0; i < n; ++i) {
      const Run r = source(i);
      const uint32_t k = key(r);
      const uint32_t same = k == prev;
      count = (count & (0u - same)) + r.count;
      m += static_cast<int>(1u - same);
      prev = k;
      out[static_cast<std::size_t>(m)] = Run{r.x, r.y, static_cast<uint16_t>(count)};
    }
    return static_cast<uint16_t>(m);
  };
  if (runs_level_ == 0 || level < runs_first_) {
    const int first = std::max(1, std::min(level, kLeafLevel));
    // No clamping needed: rotate() kept only points at least half_cells inside the map, of at
    // most 2047 cells (LikelihoodMapStorage: Dim * kSub < 32768), so every cell here lies in
    // [0, Dim / 2 + 1], far from the sentinel and from int16's limits.
    const int32_t off = (1 << first) - half_cells_;
    run_count_[static_cast<std::size_t>(first - 1)] = merge_into(
        runs_[static_cast<std::size_t>(first - 1)],
        [&](int i) {
          return Run{static_cast<int16_t>((qx_[i] + off) >> first), static_cast<int16_t>((qy_[i] + off) >> first), 1};
        },
        nq_);
    runs_first_ = runs_level_ = first;
  }
  for (int l = runs_level_ + 1; l <= level; ++l) {
    const auto& in = runs_[static_cast<std::size_t>(l - 2)];
    run_count_[static_cast<std::size_t>(l - 1)] = merge_into(
        runs_[static_cast<std::size_t>(l - 1)],
        [&](int i) {
          const Run& r = in[static_cast<std::size_t>(i + 1)];
          return Run{static_cast<int16_t>((r.x + 1) >> 1), static_cast<int16_t>((r.y + 1) >> 1), r.count};
        },
        run_count_[static_cast<std::size_t>(l - 2)]);
  }
  runs_level_ = std::max(runs_level_, level);
}

int32_t CorrelativeSearch::bound(int level, int tx, int ty) {
  if (level == 0) return exact(tx, ty);
  build_runs(level);
  // The block index along each axis; nodes at this level start at -half_cells + m * 2^level.
  const int mx = (tx + half_cells_) >> level, my = (ty + half_cells_) >> level;
  const unsigned d = static_cast<unsigned>(level_dim(map_->dim(), level));
  const uint8_t* cells = map_->level(level);
  const auto& runs = runs_[static_cast<std::size_t>(level - 1)];
  const uint16_t nr = run_count_[static_cast<std::size_t>(level - 1)];
  int32_t sum = 0;
  for (uint16_t i = 1; i <= nr; ++i) {
    // Outside this level's image: every reachable fine cell is outside the map.
    const unsigned x = static_cast<unsigned>(runs[i].x + mx), y = static_cast<unsigned>(runs[i].y + my);
    if (x < d && y < d) sum += runs[i].count * cells[y * d + x];
  }
  return sum;
}

// The four children of a block in one pass over the runs (or the points, at level 0): they
// share each run's load and address, and the four cells are neighbours in the level's image.
// Same sums as four bound() calls.
void CorrelativeSearch::child_bounds(int level, int tx, int ty, std::array<int32_t, 4>& out) {
  int32_t s00 = 0, s10 = 0, s01 = 0, s11 = 0;
  const auto add = [&](int32_t x, int32_t y, int32_t count, const uint8_t* cells, int32_t d) {
    const bool x0 = static_cast<uint32_t>(x) < static_cast<uint32_t>(d),
               x1 = static_cast<uint32_t>(x + 1) < static_cast<uint32_t>(d);
    if (static_cast<uint32_t>(y) < static_cast<uint32_t>(d)) {
      const uint8_t* row = cells + static_cast<std::ptrdiff_t>(y) * d;
      if (x0) s00 += count * row[x];
      if (x1) s10 += count * row[x + 1];
    }
    if (static_cast<uint32_t>(y + 1) < static_cast<uint32_t>(d)) {
      const uint8_t* row = cells + static_cast<std::ptrdiff_t>(y + 1) * d;
      if (x0) s01 += count * row[x];
      if (x1) s11 += count * row[x + 1];
    }
  };
  if (level == 0) {
    const int32_t d = map_->dim();
    for (uint16_t i = 0; i < nq_; ++i) add(qx_[i] + tx, qy_[i] + ty, 1, map_->cells(), d);
  } else {
    build_runs(level);
    const int mx = (tx + half_cells_) >> level, my = (ty + half_cells_) >> level;
    const int32_t d = level_dim(map_->dim(), level);
    const uint8_t* cells = map_->level(level);
    const auto& runs = runs_[static_cast<std::size_t>(level - 1)];
    const uint16_t nr = run_count_[static_cast<std::size_t>(level - 1)];
    for (uint16_t i = 1; i <= nr; ++i) add(runs[i].x + mx, runs[i].y + my, runs[i].count, cells, d);
  }
  out = {s00, s10, s01, s11};
}

int32_t CorrelativeSearch::exact(int tx, int ty) const {
  int32_t sum = 0;
  const unsigned d = static_cast<unsigned>(map_->dim());
  const uint8_t* cells = map_->cells();
  for (uint16_t i = 0; i < nq_; ++i) {
    const unsigned x = static_cast<unsigned>(qx_[i] + tx), y = static_cast<unsigned>(qy_[i] + ty);
    if (x < d && y < d) sum += cells[y * d + x];
  }
  return sum;
}

int32_t CorrelativeSearch::score(int k, int tx, int ty) {
  rotate(k);
  return bound(0, tx, ty);
}

// Over the points the search scores, like the score: new territory in the band at the map's
// edge is judged once the vehicle's motion brings it inside (0.4 m on the vehicle). Counting
// every point inside the map instead was tried: the 1 m/s hallway drift was 0.22 / 0.29 /
// 0.26 m on seeds 1-3 against 0.17 / 0.23 / 0.20 m.
void CorrelativeSearch::overlap(int k, int tx, int ty, uint8_t threshold, int& inside, int& fit) {
  inside = fit = 0;
  const uint8_t* cells = map_->cells();
  const auto d = static_cast<std::size_t>(map_->dim());
  for_each_cell(k, tx, ty, [&](int x, int y) {
    ++inside;
    fit += cells[static_cast<std::size_t>(y) * d + static_cast<std::size_t>(x)] >= threshold;
  });
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

// Image addition: adds each point's w x w map window to the score image. Rows are padded to whole
// lane groups; the padding lanes sum cells right of the window and are dropped when the image
// is packed to (2 half + 1)^2 at the end. Points whose padded window lies inside the map (all
// but a few at the map's edge) go through the SIMD kernels: one score row from all points at
// a time with the row in registers when it is at most kMaxRegisterGroups groups wide, else
// point by point; the rest are clipped, one cell at a time.
void CorrelativeSearch::accumulate(int x0, int y0, int w) {
  const int stride = (w + kRowLanes - 1) / kRowLanes * kRowLanes;
  const int d = map_->dim();
  const uint8_t* cells = map_->cells();
  std::fill(acc_.begin(), acc_.begin() + w * stride, uint16_t{0});
  // Branch-free split into the points whose padded window is inside the map (their offsets)
  // and the rest (their indices); a branch here mispredicts wherever the scan crosses the
  // map's edge.
  int inside = 0, clipped = 0;
  if (d >= stride && d >= w) {
    const auto xmax = static_cast<unsigned>(d - stride), ymax = static_cast<unsigned>(d - w);
    for (uint16_t i = 0; i < nq_; ++i) {
      const int bx = qx_[i] + x0, by = qy_[i] + y0;  // map cell of window entry (0, 0)
      const bool in = static_cast<unsigned>(bx) <= xmax && static_cast<unsigned>(by) <= ymax;
      offsets_[static_cast<std::size_t>(inside)] = by * d + bx;
      clipped_[static_cast<std::size_t>(clipped)] = i;
      inside += in;
      clipped += !in;
    }
  } else {
    for (uint16_t i = 0; i < nq_; ++i) clipped_[static_cast<std::size_t>(clipped++)] = i;
  }
  for (int j = 0; j < clipped; ++j) {
    const uint16_t i = clipped_[static_cast<std::size_t>(j)];
    const int bx = qx_[i] + x0, by = qy_[i] + y0;
    const int ux0 = std::max(0, -bx), ux1 = std::min(w, d - bx);
    const int uy0 = std::max(0, -by), uy1 = std::min(w, d - by);
    if (ux0 >= ux1 || uy0 >= uy1) continue;
    for (int uy = uy0; uy < uy1; ++uy) {
      add_row_scalar(acc_.data() + uy * stride + ux0, cells + static_cast<std::size_t>(by + uy) * d + bx + ux0,
                     ux1 - ux0);
    }
  }
  const int groups = kRowLanes == 8 ? stride / 8 : 0;
  if (groups == 1) {
#if defined(__ARM_NEON) || defined(__SSE2__)
    // One lane group: the rows of the whole block stay in registers.
    const auto block = [&]<int R>() { sum_block_lanes<R>(acc_.data(), stride, cells, d, offsets_.data(), inside); };
    switch (w) {
      case 1: block.template operator()<1>(); break;
      case 2: block.template operator()<2>(); break;
      case 3: block.template operator()<3>(); break;
      case 4: block.template operator()<4>(); break;
      case 5: block.template operator()<5>(); break;
      case 6: block.template operator()<6>(); break;
      case 7: block.template operator()<7>(); break;
      default: block.template operator()<8>(); break;
    }
#endif
  } else if (groups >= 2 && groups <= kMaxRegisterGroups) {
    for (int uy = 0; uy < w; ++uy) {
      uint16_t* dst = acc_.data() + uy * stride;
      const uint8_t* rows = cells + static_cast<std::size_t>(uy) * d;
      switch (groups) {
        case 2: sum_rows_lanes<2>(dst, rows, offsets_.data(), inside); break;
        case 3: sum_rows_lanes<3>(dst, rows, offsets_.data(), inside); break;
        default: sum_rows_lanes<4>(dst, rows, offsets_.data(), inside); break;
      }
    }
  } else {
    for (int i = 0; i < inside; ++i) {
      const uint8_t* src = cells + offsets_[static_cast<std::size_t>(i)];
      uint16_t* dst = acc_.data();
      for (int uy = 0; uy < w; ++uy, src += d, dst += stride) add_row_lanes(dst, src, stride);
    }
  }
  if (stride != w) {
    for (int uy = 1; uy < w; ++uy) std::copy_n(acc_.data() + uy * stride, w, acc_.data() + uy * w);
  }
}

GridPose CorrelativeSearch::exhaustive() {
  GridPose best;
  const int h = std::min(half_cells_, kMaxExhaustiveWindow);
  const int w = 2 * h + 1;
  for (int k = -half_steps_; k <= half_steps_; ++k) {
    rotate(k);
    accumulate(-h, -h, w);
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
  accumulate(cx - half, cy - half, 2 * half + 1);
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
    if (n.level <= kLeafLevel) {
      // Every pose of the block at once by image addition: on SIMD targets this costs about
      // what two or three exact scores do, where descending would cost up to 84 bounds.
      const int bs = 1 << n.level;
      accumulate(n.tx, n.ty, bs);
      for (int uy = 0; uy < bs && n.ty + uy <= half_cells_; ++uy) {
        for (int ux = 0; ux < bs && n.tx + ux <= half_cells_; ++ux) {
          const GridPose cand{k, n.tx + ux, n.ty + uy, acc_[static_cast<std::size_t>(uy * bs + ux)]};
          if (better(cand, best)) best = cand;
        }
      }
      nodes_ += static_cast<uint64_t>(bs * bs - 1);
      continue;
    }
    push_children(n, best.score, top);
  }
}

// A child whose bound only ties the best is still pushed by dfs (min_bound = the best score):
// it may win on the tie-break. best_outside wants any of the best and passes one above.
void CorrelativeSearch::push_children(const Node& n, int32_t min_bound, std::size_t& top) {
  const int level = n.level - 1;
  const int half = 1 << level;
  std::array<int32_t, 4> bounds{};
  child_bounds(level, n.tx, n.ty, bounds);
  Node kids[4];
  int nk = 0;
  for (int c = 0; c < 4; ++c) {
    const int tx = n.tx + ((c & 1) ? half : 0), ty = n.ty + ((c & 2) ? half : 0);
    const int32_t b = bounds[static_cast<std::size_t>(c)];
    // A block that starts beyond the window's far edge holds no translation of it.
    if (tx > half_cells_ || ty > half_cells_ || b < min_bound) continue;
    kids[nk++] = {tx, ty, b, static_cast<int8_t>(level)};
  }
  order_best_last(kids, nk);
  for (int c = 0; c < nk; ++c) stack_[top++] = kids[c];
}

// Insertion sort: at most four children (and std::sort on a 4-array trips GCC 12's
// array-bounds analysis under the sanitizers).
void CorrelativeSearch::order_best_last(Node* kids, int n) {
  const auto before = [](const Node& a, const Node& b) {
    if (a.bound != b.bound) return a.bound < b.bound;
    if (a.ty != b.ty) return a.ty > b.ty;
    return a.tx > b.tx;
  };
  for (int i = 1; i < n; ++i) {
    const Node key = kids[i];
    int j = i - 1;
    while (j >= 0 && before(key, kids[j])) {
      kids[j + 1] = kids[j];
      --j;
    }
    kids[j + 1] = key;
  }
}

// The relocaliser's question (is there a rival peak away from the best?) asked of the image
// addition cost a full slice of the window, 49 M of a search's 108 M instructions on the
// Verdex. Rivals are few: most blocks' bounds fall below the best rival found early.
GridPose CorrelativeSearch::best_outside(int k, int cx, int cy, int radius) {
  rotate(k);
  GridPose best{k, 0, 0, -1};
  const int64_t r2 = static_cast<int64_t>(radius) * radius;
  // Whether every translation of the block (within the window) is inside the disc: the
  // block's farthest corner from the centre is.
  const auto inside_disc = [&](int tx, int ty, int size) {
    const int64_t dx = std::max(std::abs(tx - cx), std::abs(std::min(tx + size - 1, half_cells_) - cx));
    const int64_t dy = std::max(std::abs(ty - cy), std::abs(std::min(ty + size - 1, half_cells_) - cy));
    return dx * dx + dy * dy <= r2;
  };
  std::size_t top = 0;
  stack_[top++] = {-half_cells_, -half_cells_, bound(top_level_, -half_cells_, -half_cells_),
                   static_cast<int8_t>(top_level_)};
  while (top > 0) {
    const Node n = stack_[--top];
    ++nodes_;
    if (n.bound <= best.score || inside_disc(n.tx, n.ty, 1 << n.level)) continue;
    if (n.level == 0) {  // an exact score above the best, outside the disc
      best = {k, n.tx, n.ty, n.bound};
      continue;
    }
    push_children(n, best.score + 1, top);  // at most 255 a point: far from overflow
  }
  return best;
}

GridPose CorrelativeSearch::branch_and_bound(const GridPose* seeds, int seed_count) {
  // The prediction itself is a real candidate: starting from its exact score prunes early.
  rotate(0);
  GridPose best{0, 0, 0, bound(0, 0, 0)};
  for (int i = 0; i < seed_count; ++i) {
    const GridPose& sd = seeds[i];
    if (std::abs(sd.k) > half_steps_ || std::abs(sd.tx) > half_cells_ || std::abs(sd.ty) > half_cells_) continue;
    rotate(sd.k);
    const GridPose cand{sd.k, sd.tx, sd.ty, bound(0, sd.tx, sd.ty)};
    if (better(cand, best)) best = cand;
  }
  // Rotations outward from the best so far: the optimum is usually near it, and finding it
  // first is what lets the bounds of the other rotations prune them whole. (Ranking the
  // rotations by the bound of their whole window instead costs a second transform of the
  // scan per rotation and, the window's bound being loose, prunes no better.)
  const int centre = best.k;
  for (int dk = 0; dk <= 2 * half_steps_; ++dk) {
    for (const int k : {centre - dk, centre + dk}) {
      if (k < -half_steps_ || k > half_steps_ || (dk == 0 && k != centre - dk)) continue;
      rotate(k);
      const int32_t top = bound(top_level_, -half_cells_, -half_cells_);
      if (top >= best.score) dfs(k, top, best);
    }
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
