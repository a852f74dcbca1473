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
// translations. Rotations are ranked by the bound of their whole window; each is searched
// depth-first over a quad-tree of translation blocks, best bound first, pruning any block whose
// bound is below the best exact score found so far. Ties are broken towards the smallest
// (theta, y, x) index in both modes, so both return the same pose.
#include <array>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/scan_matching/likelihood_map.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

inline constexpr int kMaxThetaSteps = 512;      // rotation half-window, steps
inline constexpr int kMaxExhaustiveWindow = 64; // translation half-window of the image addition

// A pose on the search grid: theta = centre + k * step, translation = centre + (tx, ty) cells.
struct GridPose {
  int32_t k = 0, tx = 0, ty = 0;
  int32_t score = -1;  // sum of the cells under the scan's points; -1: nothing found
};

class CorrelativeSearch {
 public:
  // Prepares a search of `pts` (sensor frame) around `centre` (world frame) on `map`:
  // translations within +-half_cells cells, rotations within +-half_steps steps of step_rad.
  // Returns kInvalidArgument when the window exceeds the static capacities.
  Status setup(const ScanPoints& pts, const Pose2& centre, const LikelihoodMap& map,
               int half_cells, int half_steps, float step_rad);

  GridPose exhaustive();
  // Seeds are poses of this window (e.g. the optima of small searches around each motion
  // hypothesis): their exact scores start the pruning, the result is still the exact optimum.
  GridPose branch_and_bound(const GridPose* seeds = nullptr, int seed_count = 0);
  // Best translation at one rotation, exact (no pruning against other rotations); the seed is
  // any translation inside the window, ideally near the answer.
  GridPose best_at(int k, int seed_tx = 0, int seed_ty = 0);
  // Score image at rotation k over translations (cx +- half, cy +- half), row-major,
  // (2 half + 1)^2 values, by image addition. half <= kMaxExhaustiveWindow.
  const uint16_t* slice(int k, int cx, int cy, int half);

  int32_t score(int k, int tx, int ty);  // one pose, for tests
  Pose2 pose_of(float k, float tx, float ty) const;
  int half_cells() const { return half_cells_; }
  int half_steps() const { return half_steps_; }
  uint64_t nodes_visited() const { return nodes_; }

 private:
  struct Node {
    int32_t tx, ty, bound;
    int8_t level;
  };
  void rotate(int k);
  int32_t bound(int level, int tx, int ty) const;
  void accumulate(int x0, int y0, int half);
  void dfs(int k, int32_t root_bound, GridPose& best);
  static bool better(const GridPose& a, const GridPose& b);

  const LikelihoodMap* map_ = nullptr;
  std::array<float, kMaxPoints> px_{}, py_{};  // points in cells, sensor frame
  std::array<int32_t, kMaxPoints> qx_{}, qy_{};  // fine cell of each point at the current rotation
  uint16_t n_ = 0;
  Pose2 centre_;
  float cx_cells_ = 0, cy_cells_ = 0;  // window centre in map cells
  float step_rad_ = 0;
  int half_cells_ = 0, half_steps_ = 0, top_level_ = 0;
  int rotated_k_ = 1 << 30;
  uint64_t nodes_ = 0;
  std::array<uint16_t, (2 * kMaxExhaustiveWindow + 1) * (2 * kMaxExhaustiveWindow + 1)> acc_{};
  std::array<Node, 4 * kMaxLevels + 8> stack_{};
  struct ThetaBound {
    int32_t bound;
    int32_t k;
  };
  std::array<ThetaBound, 2 * kMaxThetaSteps + 1> order_{};
};

}  // namespace kestrel::scan_matching
