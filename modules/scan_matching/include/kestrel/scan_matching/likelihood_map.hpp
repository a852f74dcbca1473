#pragma once
// The likelihood map of paper 000, section 5.1.1, with the max-pooled pyramid of Olson's
// multi-resolution correlative matcher (ICRA 2009) on top.
//
// Cells hold a scaled log-likelihood of a return there: log P(d) = -d / sigma for a return at
// distance d from the nearest contour, clipped at kernel_sigmas * sigma (beyond which a return
// is no more likely than clutter) and mapped linearly onto [0, kCellMax]. Most cells are zero,
// so the map is drawn, not computed: each contour segment is walked along its major axis with
// a one-cell-wide kernel across it, the kernel widened by 1/cos of the slope, taking the max
// with what is there. Drawing and clearing cost is proportional to the non-zero cells: a
// rebuild clears only the segments it drew last time.
//
// Coarse level L (cell step s = 2^L) bounds the fine map from above: cell I of level L holds
// the max of fine cells [(I-1)s, (I-1)s + 2s - 1) in each axis, so for a point in fine cell q
// the level-L cell (q + s) >> L bounds every fine cell q..q+s-1 that a block of s translations
// can put it in. Each level is a 3x3, stride-2 max of the level below.
//
// The cells live in storage owned by the caller (LikelihoodMapStorage<Dim>), so the size is a
// compile-time choice of whoever allocates it once at start-up.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/status.hpp"
#include "kestrel/scan_matching/params.hpp"

namespace kestrel::scan_matching {

inline constexpr int32_t kSub = 16;          // sub-cell units per cell for contour geometry
inline constexpr int kMaxLevels = 9;         // coarsest step 512 cells
inline constexpr int kMaxWindowCells = 255;  // translation half-window, so 2W+1 <= 2^kMaxLevels

// A contour segment in the map frame, in 1/kSub cell units.
struct MapSegment {
  int16_t ax = 0, ay = 0, bx = 0, by = 0;
};

// Integer geometry of one segment: squared distance from a point, in (1/kSub cell)^2.
struct SegmentGeometry {
  explicit SegmentGeometry(const MapSegment& s);
  int64_t distance2(int32_t px, int32_t py) const;
  int32_t ax, ay, bx, by, tx, ty, len_q;
};

// Maps a squared distance to a cell value; one table per map configuration.
class LikelihoodKernel {
 public:
  static constexpr int kTable = 1024;
  void configure(float radius_cells);
  uint8_t value(int64_t d2) const {
    const int64_t i = d2 >> shift_;
    return i < kTable ? table_[static_cast<std::size_t>(i)] : 0;
  }
  int32_t radius_sub() const { return radius_sub_; }

 private:
  std::array<uint8_t, kTable> table_{};
  int shift_ = 0;
  int32_t radius_sub_ = 0;
};

constexpr int level_dim(int dim, int level) { return (dim - 1) / (1 << level) + 2; }
constexpr std::size_t pyramid_size(int dim) {
  std::size_t n = 0;
  for (int l = 1; l <= kMaxLevels; ++l) n += static_cast<std::size_t>(level_dim(dim, l)) * level_dim(dim, l);
  return n;
}

class LikelihoodMap {
 public:
  LikelihoodMap(const LikelihoodMap&) = delete;
  LikelihoodMap& operator=(const LikelihoodMap&) = delete;

  // Sets resolution and kernel; clears everything. Not for the real-time path.
  Status configure(const Params& p);

  // Starts a rebuild with a new origin (world position of the corner of cell (0,0), m):
  // clears the segments drawn last time and the coarse levels they touched.
  void begin(float origin_x_m, float origin_y_m);
  // begin() with the window centred on a world point, its origin on the grid of whole cells.
  void begin_centred(float x_m, float y_m);
  // Draws one segment (map frame, 1/kSub cells). kCapacityExceeded when the list is full.
  Status draw(const MapSegment& s);
  // Builds the coarse levels over the drawn area. The map is ready to search afterwards.
  void finish();

  int dim() const { return dim_; }
  float resolution_m() const { return resolution_m_; }
  float origin_x_m() const { return origin_x_; }
  float origin_y_m() const { return origin_y_; }
  uint8_t at(int x, int y) const {
    return (static_cast<unsigned>(x) < static_cast<unsigned>(dim_) &&
            static_cast<unsigned>(y) < static_cast<unsigned>(dim_))
               ? cells_[static_cast<std::size_t>(y) * dim_ + x] : 0;
  }
  const uint8_t* cells() const { return cells_; }
  // Level 1..kMaxLevels of the pyramid, level_dim(dim(), level) cells square.
  const uint8_t* level(int l) const { return pyramid_ + level_offset_[static_cast<std::size_t>(l)]; }
  const LikelihoodKernel& kernel() const { return kernel_; }
  std::size_t segment_count() const { return segment_count_; }
  std::size_t nonzero_cells() const;  // for tests and diagnostics (scans the whole map)

 protected:
  LikelihoodMap(uint8_t* cells, int dim, uint8_t* pyramid, MapSegment* segments, std::size_t max_segments);

 private:
  template <class F>
  void for_each_covered(const MapSegment& s, F&& f);
  void build_level(int l);

  uint8_t* cells_;
  int dim_;
  uint8_t* pyramid_;
  MapSegment* segments_;
  std::size_t max_segments_;
  std::size_t segment_count_ = 0;
  std::array<std::size_t, kMaxLevels + 1> level_offset_{};
  int dirty_x0_ = 0, dirty_y0_ = 0, dirty_x1_ = -1, dirty_y1_ = -1;  // fine cells drawn
  float resolution_m_ = 0.0075f;
  float origin_x_ = 0, origin_y_ = 0;
  LikelihoodKernel kernel_;
};

namespace detail {
template <int Dim, std::size_t MaxSegments>
struct MapArrays {
  std::array<uint8_t, static_cast<std::size_t>(Dim) * Dim> cells_{};
  std::array<uint8_t, pyramid_size(Dim)> pyramid_{};
  std::array<MapSegment, MaxSegments> segments_{};
};
}  // namespace detail

// The storage: one fine grid, its pyramid and the list of drawn segments. The arrays are a
// base so they exist before the map that points into them.
template <int Dim, std::size_t MaxSegments>
class LikelihoodMapStorage final : private detail::MapArrays<Dim, MaxSegments>, public LikelihoodMap {
  static_assert(Dim >= 16 && Dim * kSub < 32768, "segment coordinates are int16 sub-cells");
  using A = detail::MapArrays<Dim, MaxSegments>;

 public:
  LikelihoodMapStorage()
      : LikelihoodMap(A::cells_.data(), Dim, A::pyramid_.data(), A::segments_.data(), MaxSegments) {}
};

}  // namespace kestrel::scan_matching
