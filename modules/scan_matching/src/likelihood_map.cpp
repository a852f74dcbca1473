#include "kestrel/scan_matching/likelihood_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kestrel::scan_matching {

SegmentGeometry::SegmentGeometry(const MapSegment& s)
    : ax(s.ax), ay(s.ay), bx(s.bx), by(s.by), tx(1 << 14), ty(0), len_q(0) {
  const int32_t dx = bx - ax, dy = by - ay;
  if (dx != 0 || dy != 0) {
    const float len = std::sqrt(static_cast<float>(dx) * dx + static_cast<float>(dy) * dy);
    tx = static_cast<int32_t>(std::lround(static_cast<float>(dx) / len * 16384.0f));
    ty = static_cast<int32_t>(std::lround(static_cast<float>(dy) / len * 16384.0f));
    len_q = tx * dx + ty * dy;
  }
}

int64_t SegmentGeometry::distance2(int32_t px, int32_t py) const {
  const int32_t ex = px - ax, ey = py - ay;
  const int32_t u = tx * ex + ty * ey;  // along the segment, Q14 sub-cells
  if (u <= 0) return static_cast<int64_t>(ex) * ex + static_cast<int64_t>(ey) * ey;
  if (u >= len_q) {
    const int64_t fx = px - bx, fy = py - by;
    return fx * fx + fy * fy;
  }
  const int64_t across = static_cast<int64_t>(-ty) * ex + static_cast<int64_t>(tx) * ey;  // Q14
  return (across * across) >> 28;
}

void LikelihoodKernel::configure(float radius_cells) {
  radius_sub_ = std::max<int32_t>(1, static_cast<int32_t>(std::ceil(radius_cells * kSub)));
  const int64_t r2 = static_cast<int64_t>(radius_sub_) * radius_sub_;
  shift_ = 0;
  while ((r2 >> shift_) >= kTable) ++shift_;
  for (int i = 0; i < kTable; ++i) {
    // The log-likelihood -d/sigma is linear in d: the cell value falls linearly to zero at
    // the kernel radius, evaluated at the middle of the table bin.
    const double d2 = (static_cast<double>(i) + 0.5) * static_cast<double>(int64_t{1} << shift_);
    const double v = kCellMax * (1.0 - std::sqrt(d2) / radius_sub_);
    table_[static_cast<std::size_t>(i)] =
        static_cast<uint8_t>(std::clamp(std::lround(v), 0L, static_cast<long>(kCellMax)));
  }
}

LikelihoodMap::LikelihoodMap(uint8_t* cells, int dim, uint8_t* pyramid, MapSegment* segments,
                             std::size_t max_segments)
    : cells_(cells), dim_(dim), pyramid_(pyramid), segments_(segments), max_segments_(max_segments) {
  std::size_t off = 0;
  for (int l = 1; l <= kMaxLevels; ++l) {
    level_offset_[static_cast<std::size_t>(l)] = off;
    off += static_cast<std::size_t>(level_dim(dim, l)) * level_dim(dim, l);
  }
}

Status LikelihoodMap::configure(const Params& p) {
  if (!(p.resolution_m > 1e-4f) || !(p.sigma_m > 0) || !(p.kernel_sigmas > 0) ||
      !(p.kernel_sigmas * p.sigma_m / p.resolution_m < 64.0f)) {
    return Status::kInvalidArgument;
  }
  resolution_m_ = p.resolution_m;
  kernel_.configure(p.kernel_sigmas * p.sigma_m / p.resolution_m);
  std::memset(cells_, 0, static_cast<std::size_t>(dim_) * dim_);
  std::memset(pyramid_, 0, pyramid_size(dim_));
  segment_count_ = 0;
  dirty_x1_ = dirty_y1_ = -1;
  return Status::kOk;
}

// Visits every cell that a segment's kernel can reach: along the major axis, one strip of
// cells across the segment per step, as wide as the kernel divided by cos(slope) (the cap
// columns beyond the end points use the same strip, which also covers the round end caps).
template <class F>
void LikelihoodMap::for_each_covered(const MapSegment& s, F&& f) {
  const int32_t r = kernel_.radius_sub();
  const bool x_major = std::abs(s.bx - s.ax) >= std::abs(s.by - s.ay);
  // Work in (major, minor) coordinates so one loop serves both orientations.
  const int32_t a_maj = x_major ? s.ax : s.ay, a_min = x_major ? s.ay : s.ax;
  const int32_t b_maj = x_major ? s.bx : s.by, b_min = x_major ? s.by : s.bx;
  const int32_t d_maj = b_maj - a_maj, d_min = b_min - a_min;
  const int32_t lo = std::min(a_maj, b_maj), hi = std::max(a_maj, b_maj);
  // Half-width of the strip: r (1 + |slope|) >= r / cos(slope), in sub-cells.
  const int32_t half =
      d_maj == 0 ? r
                 : r + static_cast<int32_t>((static_cast<int64_t>(r) * std::abs(d_min) + std::abs(d_maj) - 1) /
                                            std::abs(d_maj));
  const int c0 = std::max(0, (lo - r) / kSub - 1), c1 = std::min(dim_ - 1, (hi + r) / kSub + 1);
  for (int c = c0; c <= c1; ++c) {
    const int32_t centre = std::clamp(c * kSub + kSub / 2, lo, hi);
    const int32_t m =
        d_maj == 0 ? a_min : a_min + static_cast<int32_t>(static_cast<int64_t>(centre - a_maj) * d_min / d_maj);
    const int r0 = std::max(0, (m - half) / kSub - 1), r1 = std::min(dim_ - 1, (m + half) / kSub + 1);
    if (x_major) {
      for (int row = r0; row <= r1; ++row) f(c, row);
    } else {
      for (int row = r0; row <= r1; ++row) f(row, c);
    }
  }
}

void LikelihoodMap::begin_centred(float x_m, float y_m) {
  const float half = 0.5f * static_cast<float>(dim_) * resolution_m_;
  begin(std::floor((x_m - half) / resolution_m_) * resolution_m_,
        std::floor((y_m - half) / resolution_m_) * resolution_m_);
}

void LikelihoodMap::begin(float origin_x_m, float origin_y_m) {
  for (std::size_t i = 0; i < segment_count_; ++i) {
    for_each_covered(segments_[i], [&](int x, int y) { cells_[static_cast<std::size_t>(y) * dim_ + x] = 0; });
  }
  segment_count_ = 0;
  if (dirty_x1_ >= 0) {
    for (int l = 1; l <= kMaxLevels; ++l) {
      const int s = 1 << l, d = level_dim(dim_, l);
      const int x0 = dirty_x0_ / s, x1 = std::min(d - 1, (dirty_x1_ + s) / s + 1);
      const int y0 = dirty_y0_ / s, y1 = std::min(d - 1, (dirty_y1_ + s) / s + 1);
      uint8_t* lv = pyramid_ + level_offset_[static_cast<std::size_t>(l)];
      for (int y = y0; y <= y1; ++y)
        std::memset(lv + static_cast<std::size_t>(y) * d + x0, 0, static_cast<std::size_t>(x1 - x0 + 1));
    }
  }
  dirty_x0_ = dirty_y0_ = 0;
  dirty_x1_ = dirty_y1_ = -1;
  origin_x_ = origin_x_m;
  origin_y_ = origin_y_m;
}

Status LikelihoodMap::draw(const MapSegment& s) {
  if (segment_count_ >= max_segments_) return Status::kCapacityExceeded;
  segments_[segment_count_++] = s;
  const SegmentGeometry g(s);
  bool any = false;
  int x0 = dim_, y0 = dim_, x1 = -1, y1 = -1;
  for_each_covered(s, [&](int x, int y) {
    const uint8_t v = kernel_.value(g.distance2(x * kSub + kSub / 2, y * kSub + kSub / 2));
    if (v == 0) return;
    uint8_t& cell = cells_[static_cast<std::size_t>(y) * dim_ + x];
    if (v > cell) cell = v;
    any = true;
    x0 = std::min(x0, x); x1 = std::max(x1, x);
    y0 = std::min(y0, y); y1 = std::max(y1, y);
  });
  if (any) {
    if (dirty_x1_ < 0) {
      dirty_x0_ = x0; dirty_y0_ = y0; dirty_x1_ = x1; dirty_y1_ = y1;
    } else {
      dirty_x0_ = std::min(dirty_x0_, x0); dirty_y0_ = std::min(dirty_y0_, y0);
      dirty_x1_ = std::max(dirty_x1_, x1); dirty_y1_ = std::max(dirty_y1_, y1);
    }
  }
  return Status::kOk;
}

void LikelihoodMap::build_level(int l) {
  const int s = 1 << l, d = level_dim(dim_, l);
  uint8_t* out = pyramid_ + level_offset_[static_cast<std::size_t>(l)];
  // Source: the fine map for level 1 (cells 2I-2..2I), else the level below (2I-1..2I+1).
  const uint8_t* src = l == 1 ? cells_ : pyramid_ + level_offset_[static_cast<std::size_t>(l - 1)];
  const int sd = l == 1 ? dim_ : level_dim(dim_, l - 1);
  const int shift = l == 1 ? -2 : -1;
  // Only the cells whose coverage meets the drawn area can be non-zero.
  const int x0 = std::max(0, dirty_x0_ / s), x1 = std::min(d - 1, (dirty_x1_ + s) / s + 1);
  const int y0 = std::max(0, dirty_y0_ / s), y1 = std::min(d - 1, (dirty_y1_ + s) / s + 1);
  for (int y = y0; y <= y1; ++y) {
    const int sy0 = std::max(0, 2 * y + shift), sy1 = std::min(sd - 1, 2 * y + shift + 2);
    for (int x = x0; x <= x1; ++x) {
      const int sx0 = std::max(0, 2 * x + shift), sx1 = std::min(sd - 1, 2 * x + shift + 2);
      uint8_t m = 0;
      for (int yy = sy0; yy <= sy1; ++yy) {
        const uint8_t* row = src + static_cast<std::size_t>(yy) * sd;
        for (int xx = sx0; xx <= sx1; ++xx) m = std::max(m, row[xx]);
      }
      out[static_cast<std::size_t>(y) * d + x] = m;
    }
  }
}

void LikelihoodMap::finish() {
  if (dirty_x1_ < 0) return;
  for (int l = 1; l <= kMaxLevels; ++l) build_level(l);
}

std::size_t LikelihoodMap::nonzero_cells() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(dim_) * dim_; ++i) n += cells_[i] != 0;
  return n;
}

}  // namespace kestrel::scan_matching
