#pragma once
// Scan-to-map alignment, paper 000 section 5.1.2: the best rigid transform (x, y, theta) of a
// scan against a likelihood map, over a grid of poses centred on a prediction.
//
// Exhaustive mode follows the paper: for each rotation the scan is transformed once, and since
// the likelihoods of one point under every translation form the square window of the map
// around it, the windows of all points are added into one integer score image (image
// addition), whose maximum is the best translation at that rotation.
//
// Multi-resolution mode follows Olson (ICRA 2009): a coarse map whose cells are the max of the
// fine cells they can reach gives an upper bound on the score of a whole block of
// translations. Rotations are taken outward from the best pose known at the start; each is searched
// depth-first over a quad-tree of translation blocks, best bound first, pruning any block whose
// bound is below the best exact score found so far; small blocks at the bottom are scored
// whole by image addition (kLeafLevel). Both modes break ties by one total order (nearest
// the prediction first), so both return the same pose.
//
// Every block searched at level L starts at -half + m * 2^L cells, so a point's level-L cell
// is its own fixed base cell plus the block index m: the points of one rotation are reduced
// once per level to runs of consecutive points sharing a base cell, and a coarse bound sums
// count * cell over the runs. Along a wall many points share a coarse cell, so the loose,
// frequently evaluated coarse bounds get cheap; the sums, and so the search, are unchanged.
#include <array>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/scan_matching/likelihood_map.hpp"
#include "kestrel/scan_matching/rotate_points.hpp"
#include "kestrel/scan_matching/row_add.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

inline constexpr int kMaxThetaSteps = 512;      // rotation half-window, steps
inline constexpr int kMaxExhaustiveWindow = 64; // translation half-window of the image addition
// Branch and bound stops descending at blocks of 2^kLeafLevel translations and scores all of
// them by image addition where the target has SIMD lanes (one lane group per row); without,
// it descends to single poses.
inline constexpr int kLeafLevel = kRowLanes == 8 ? 3 : 0;

// Where the map's key scans could see: discs of the laser's reach around their poses (world
// frame). A point outside all of them scores zero whatever is there.
inline constexpr std::size_t kMaxSeenDiscs = 8;
struct SeenDiscs {
  std::array<float, kMaxSeenDiscs> x{}, y{};
  std::size_t count = 0;
  float radius_m = 0;
};

// A pose on the search grid: theta = centre + k * step, translation = centre + (tx, ty) cells.
struct GridPose {
  int32_t k = 0, tx = 0, ty = 0;
  int32_t score = -1;  // sum of the cells under the scan's points; -1: nothing found
};

class CorrelativeSearch {
 public:
  // Prepares a search of `pts` (sensor frame) around `centre` (world frame) on `map`:
  // translations within +-half_cells cells, rotations within +-half_steps steps of step_rad.
  // Each rotation scores only the points that stay inside the map for every translation
  // within +-(half_cells + slice_half): slices reaching up to slice_half cells beyond the
  // window (the covariance's) are judged on the same points as the search.
  // Returns kInvalidArgument when the window exceeds the static capacities, a point is not
  // finite, or it (or max_range_m) is more than 32,000 cells from the sensor (int16 cells;
  // 240 m at 7.5 mm).
  // max_range_m (optional) fixes the points' precision for every scan of that sensor.
  // seen (optional): a rotation also scores only the points that stay inside one of these
  // discs under every translation (see rotate()).
  Status setup(const ScanPoints& pts, const Pose2& centre, const LikelihoodMap& map,
               int half_cells, int half_steps, float step_rad, int slice_half = 0, float max_range_m = 0,
               const SeenDiscs* seen = nullptr);

  GridPose exhaustive();
  // Seeds are poses of this window (e.g. the optima of small searches around each motion
  // hypothesis): their exact scores start the pruning, the result is still the exact optimum.
  GridPose branch_and_bound(const GridPose* seeds = nullptr, int seed_count = 0);
  // Best translation at one rotation, exact (no pruning against other rotations); the seed is
  // any translation inside the window, ideally near the answer.
  GridPose best_at(int k, int seed_tx = 0, int seed_ty = 0);
  // Best translation at rotation k farther than `radius` cells from (cx, cy), exact (the max
  // of the slice over the window outside that disc), by branch and bound: blocks that lie
  // inside the disc or cannot beat the best found are skipped. score -1 when every
  // translation of the window is inside the disc. Ties: any of the best.
  GridPose best_outside(int k, int cx, int cy, int radius);
  // Score image at rotation k over translations (cx +- half, cy +- half), row-major,
  // (2 half + 1)^2 values, by image addition. half <= kMaxExhaustiveWindow.
  const uint16_t* slice(int k, int cx, int cy, int half);

  int32_t score(int k, int tx, int ty);  // one pose, for tests
  // The upper bound branch and bound uses for the block of 2^level translations at (tx, ty),
  // which must lie on the search's block grid (tx + half_cells a multiple of 2^level); tests.
  int32_t block_bound(int k, int level, int tx, int ty) {
    rotate(k);
    return bound(level, tx, ty);
  }
  // The four block_bound()s of level `level` at (tx, ty) + {0, 2^level}^2 in one pass, as the
  // search takes them; tests.
  std::array<int32_t, 4> child_block_bounds(int k, int level, int tx, int ty) {
    rotate(k);
    std::array<int32_t, 4> b{};
    child_bounds(level, tx, ty, b);
    return b;
  }
  // Of the points rotation k scores (see setup()) that fall inside the map at (k, tx, ty),
  // how many (`fit`) land on cells of at least `threshold`: whether the scan is already in
  // the map.
  void overlap(int k, int tx, int ty, uint8_t threshold, int& inside, int& fit);
  // Calls visit(x, y) with the map cell of each point rotation k scores (see setup()) at
  // (k, tx, ty) that lies inside the map: the cells the search itself judged the pose on.
  template <typename Visit>
  void for_each_cell(int k, int tx, int ty, Visit visit) {
    rotate(k);
    const auto d = static_cast<unsigned>(map_->dim());
    for (uint16_t i = 0; i < nq_; ++i) {
      const auto x = static_cast<unsigned>(qx_[i] + tx), y = static_cast<unsigned>(qy_[i] + ty);
      if (x < d && y < d) visit(static_cast<int>(x), static_cast<int>(y));
    }
  }
  Pose2 pose_of(float k, float tx, float ty) const;
  int half_cells() const { return half_cells_; }
  // How many points rotation k scores (see setup()).
  int scored_points(int k) {
    rotate(k);
    return nq_;
  }
  int half_steps() const { return half_steps_; }
  uint64_t nodes_visited() const { return nodes_; }

 private:
  struct Node {
    int32_t tx, ty, bound;
    int8_t level;
  };
  // Consecutive points of the scan whose cell at one level is the same.
  struct Run {
    int16_t x, y;  // base cell: the cell under the block at -half_cells in both axes
    uint16_t count;
  };
  void rotate(int k);
  void build_runs(int level);
  int32_t bound(int level, int tx, int ty);
  // bound() of the four blocks of 2^level at (tx, ty) + {0, 2^level}^2, in (x, y) order.
  void child_bounds(int level, int tx, int ty, std::array<int32_t, 4>& out);
  int32_t exact(int tx, int ty) const;  // score of a translation at the current rotation
  void accumulate(int x0, int y0, int w);
  void dfs(int k, int32_t root_bound, GridPose& best);
  // Pushes the children of block n (level n.level - 1) that hold translations of the window
  // and have a bound of at least min_bound, the one to explore first on top.
  void push_children(const Node& n, int32_t min_bound, std::size_t& top);
  // Orders up to four children so that the one to explore first is last (best bound; equal
  // bounds in (y, x) order), ready to push.
  static void order_best_last(Node* kids, int n);
  bool seen_by_a_key_scan(int32_t x, int32_t y) const;
  static bool better(const GridPose& a, const GridPose& b);

  const LikelihoodMap* map_ = nullptr;
  std::array<int16_t, 2 * kMaxPoints> pxy_{};  // points (x, y) in 1/2^point_bits_ cells, sensor frame
  std::array<int32_t, kMaxPoints> qx_{}, qy_{};  // fine cell of each point at the current rotation
  std::array<int32_t, kMaxPoints> offsets_{};   // image addition: window corner of each point
  std::array<uint16_t, kMaxPoints> clipped_{};  // image addition: points whose window crosses the map's edge
  uint16_t n_ = 0;   // points of the scan
  uint16_t nq_ = 0;  // of them, those the current rotation keeps (qx_, qy_)
  std::array<int32_t, kMaxSeenDiscs> disc_x_{}, disc_y_{};  // SeenDiscs in map cells
  std::size_t disc_count_ = 0;                               // 0: no disc test
  int64_t disc_r2_ = 0;  // squared radius less the search's reach, cells^2 (< 0: nothing seen)
  Pose2 centre_;
  RotationQ rot_;  // window centre in map cells; cos and sin of the current rotation
  float step_rad_ = 0;
  int half_cells_ = 0, slice_half_ = 0, half_steps_ = 0, top_level_ = 0;
  int rotated_k_ = 1 << 30;
  int runs_first_ = 0, runs_level_ = 0;  // levels first..level hold runs of this rotation
  std::array<std::array<Run, kMaxPoints + 1>, kMaxLevels> runs_{};  // [level - 1], from slot 1
  std::array<uint16_t, kMaxLevels> run_count_{};
  uint64_t nodes_ = 0;
  static constexpr int kAccStride = (2 * kMaxExhaustiveWindow + 1 + kRowLanes - 1) / kRowLanes * kRowLanes;
  std::array<uint16_t, (2 * kMaxExhaustiveWindow + 1) * kAccStride> acc_{};
  std::array<Node, 4 * kMaxLevels + 8> stack_{};
};

}  // namespace kestrel::scan_matching
