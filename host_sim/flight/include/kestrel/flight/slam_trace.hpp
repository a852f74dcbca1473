#pragma once
// kestrel-sim --trace-scans, when the compact SLAM runs (the URG-04LX's default, or slam=on):
// slam_trace.csv, one row per scan the SLAM processed, with its outcome, the filter's pose it
// started from, its best fit and the simulator's true pose, so that whether the SLAM's map
// could have set a drifting estimate right, or had followed it, can be read off a file.
//
// Columns (header row first; angles in rad, lengths in m, time in s of simulated time):
//   t_s                the scan's stamp
//   flags              SlamResult flags (compact_slam.hpp slam_flag), as an integer, and
//   started drawn matched corrected warming_up too_few_points not_finite no_fit no_gain
//   too_far unpinned   every one of those bits as 0/1
//   points level prior_level   returns used; the best fit's and the prior's mean map value
//                      (0 wall .. 255 free; 0 when nothing was searched)
//   prior_x prior_y prior_theta   the filter's pose at the stamp
//   fit_x fit_y fit_theta         the search's best pose after supported_move (the prior when
//                      nothing was searched), both in the filter's frame
//   fit_move_m         |fit - prior|: what a correction would move
//   true_x true_y true_yaw   the true pose at the stamp
//   prior_err_m fit_err_m    |prior - truth| and |fit - truth|: a fit nearer the truth than
//                      the prior is one the map could correct by
//   true_level         the scan's mean map value at the true pose, as level: below the
//                      fit's, the map holds the true place better than where the search
//                      ended (a wider search would have found it); nan when the scan was
//                      drawn (its own returns would flatter every pose near the fit) or
//                      not searched
// A true state older than the simulator's truth history is written as nan.
#include <cstddef>
#include <string>

#include "kestrel/autonomy/autonomy_stack.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/flight/csv_trace.hpp"
#include "kestrel/sim/vehicle.hpp"

namespace kestrel::flight {

class SlamTrace {
 public:
  static const char* header();  // without the newline
  // One row (without the newline) into buf; the number of characters, as snprintf. `truth`
  // may be null (unknown: nan).
  // `true_level` is mean_level() at the true pose, in map units (0 .. 255), or nan.
  static int format_row(char* buf, std::size_t size, const autonomy::SlamStep& step, const sim::VehicleState* truth,
                        double true_level);

  Status open(const std::string& path) { return file_.open(path, header()); }
  bool is_open() const { return file_.is_open(); }
  void write(const autonomy::SlamStep& step, const sim::VehicleState* truth, double true_level) {
    file_.write([&](char* buf, std::size_t size) { return format_row(buf, size, step, truth, true_level); });
  }
  Status flush() const { return file_.flush(); }
  std::size_t rows() const { return file_.rows(); }

 private:
  CsvTrace file_;
};

}  // namespace kestrel::flight
