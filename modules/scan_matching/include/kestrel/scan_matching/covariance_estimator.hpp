#pragma once
// Covariance of a correlative match, paper 000 section 5.1.3. Translation and rotation are
// treated separately. Translation: the 2D slice of the pose likelihood at the best rotation is
// thresholded at its 95th percentile and an ellipse is fitted to the binary image by its second
// moments; the ellipse's size and orientation give the covariance (a corridor gives a long thin
// ellipse along the corridor, flagged as degenerate). Rotation: the best score per rotation
// forms a bell-shaped curve whose width (full width at half height above its floor) gives the
// variance. Parabolic interpolation through the peak and its neighbours gives a sub-cell and
// sub-step refinement of the grid optimum.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "kestrel/scan_matching/correlative_search.hpp"

namespace kestrel::scan_matching {

struct CovarianceEstimate {
  Eigen::Matrix2f translation_cells = Eigen::Matrix2f::Identity();  // cells^2
  float rotation_steps2 = 1.0f;                                     // steps^2
  float major_axis_rad = 0;    // orientation of the ellipse's long axis, map frame
  float axis_ratio = 1.0f;     // major / minor eigenvalue
  bool degenerate = false;
  bool truncated = false;      // the likely region reached the slice's edge
  float dx = 0, dy = 0, dk = 0;  // sub-cell / sub-step refinement of the grid optimum
};

// Variance given to the unobservable axis of a degenerate match (a corridor): 100 cells of
// standard deviation, e.g. 1 m with 1 cm cells, so the filter ignores the match along it.
inline constexpr double kUnboundedVarianceCells2 = 1e4;

class CovarianceEstimator {
 public:
  // slice: (2 half + 1)^2 scores centred on the optimum. curve: best score per rotation,
  // `count` entries, the optimum at index `peak`; the width is taken at half height above
  // `floor`, outward from the peak to the first entry below it or the curve's end.
  CovarianceEstimate estimate(const uint16_t* slice, int half, const int32_t* curve, int count,
                              int peak, int32_t floor, float degenerate_ratio);

 private:
  std::array<uint16_t, (2 * kMaxExhaustiveWindow + 1) * (2 * kMaxExhaustiveWindow + 1)> scratch_{};
};

}  // namespace kestrel::scan_matching
