#pragma once
// kestrel-sim --trace-scans: one CSV row per scan the autonomy stack processed, with the
// match (flags, pose, covariance, score, ellipse), the filter after the update and the
// simulator's true pose, so that where and why an estimate drifts can be read off a file
// instead of a temporary print in the stack. Off by default; when off nothing is opened and
// the mission pays one null-pointer test per scan. With the compact SLAM, the same option
// writes its trace beside this one (slam_trace.hpp).
//
// Columns (header row first; angles in rad, lengths in m, time in s of simulated time):
//   t_s                the scan's stamp (its first beam)
//   flags              ScanMatch flags (scan_matcher.hpp match_flag), as an integer, and
//   rejected lost degenerate key_scan window_clamped map_restarted   the same bits as 0/1
//   x y theta          the match's pose (meaningless when rejected)
//   cov_xx cov_yy cov_xy cov_tt   its covariance (m^2, rad^2)
//   score overlap points axis_ratio major_axis_rad   its quality (ScanMatch fields)
//   nav_t_s nav_x nav_y nav_vx nav_vy nav_heading nav_std_x nav_std_y nav_std_heading
//                      the filter's state after the update (NavFilter::state())
//   true_x true_y true_yaw true_vx true_vy   the true state at the scan's stamp
//   match_err_m        |match position - true position at t_s| (nan when rejected)
//   match_err_theta    match heading - true heading, wrapped (nan when rejected)
//   nav_err_m          |filter position - true position at nav_t_s|
// A true state older than the simulator's truth history is written as nan.
#include <cstddef>
#include <string>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/flight/csv_trace.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"
#include "kestrel/sim/vehicle.hpp"

namespace kestrel::flight {

class ScanTrace {
 public:
  static const char* header();  // without the newline
  // One row (without the newline) into buf; the number of characters, as snprintf. truth_*
  // may be null (unknown: nan).
  static int format_row(char* buf, std::size_t size, const scan_matching::ScanMatch& match, const NavState& filter,
                        const sim::VehicleState* truth_at_scan, const sim::VehicleState* truth_at_nav);

  // Creates `path` and writes the header; the buffer is allocated here, so rows do not
  // allocate.
  Status open(const std::string& path) { return file_.open(path, header()); }
  bool is_open() const { return file_.is_open(); }
  void write(const scan_matching::ScanMatch& match, const NavState& filter, const sim::VehicleState* truth_at_scan,
             const sim::VehicleState* truth_at_nav) {
    file_.write([&](char* buf, std::size_t size) {
      return format_row(buf, size, match, filter, truth_at_scan, truth_at_nav);
    });
  }
  // Flushes; kIoError if any write failed.
  Status flush() const { return file_.flush(); }
  std::size_t rows() const { return file_.rows(); }  // rows written (a failed or truncated one is not)

 private:
  CsvTrace file_;
};

}  // namespace kestrel::flight
