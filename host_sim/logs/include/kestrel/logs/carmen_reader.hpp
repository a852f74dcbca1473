#pragma once
// Streaming reader of CARMEN logs (plain or gzip), the format of the Radish datasets and of
// kestrel's own recordings. One line at a time into a fixed buffer; no allocation after
// open(). Lines read:
//
//   FLASER n r_1..r_n x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
//     Old-style front laser. Geometry as CARMEN guesses it (readlog's carmen_laser_guess_*):
//     first beam at -90 degrees; 180 and 181 beams are 1 degree apart, 360 and 361 beams
//     0.5 degree (so 180 and 360 beams end one step short of +90), 400 and 401 beams 0.25
//     degree over 100 degrees (first beam at -50); any other n is spread over 180 degrees,
//     pi / (n - 1) apart. `x y theta` is the reference pose, `odom_*` the odometry.
//   ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy remission_mode
//               n r_1..r_n m rem_1..rem_m laser_x laser_y laser_theta robot_x robot_y
//               robot_theta tv rv forward_safety side_safety turn_axis ipc_timestamp hostname
//               logger_timestamp
//     Any field of view; the laser pose is the reference pose.
//   IMU accX accY accZ q0 q1 q2 q3 magX magY magZ gyroX gyroY gyroZ ipc_timestamp hostname
//       logger_timestamp
//     CARMEN's IMU message (readlog's carmen_string_to_imu_message); kestrel reads the
//     accelerations (m/s^2, body frame) and rates (rad/s) and ignores the orientation and the
//     magnetometer.
//   PARAM name value ...
//     kestrel_laser_scan_period_us, kestrel_laser_beam_interval_us and kestrel_imu_period_us
//     (kestrel's writer records the scanner timing this way) set the timing copied into the
//     scans; other parameters are skipped.
// Every other message type (ODOM, NEFF, SYNC, TRUEPOS, ...) and '#' comments are skipped. A
// line that does not start with a message name is an error, so that a binary or garbage file
// is not read as an empty log.
//
// Ranges are converted from metres to mm; zero, and readings at or beyond the maximum range
// (80 m for FLASER, as CARMEN assumes for a SICK LMS; the line's own for ROBOTLASER1), become
// range_code::kNoReturn. Stamps: TimeUs of ipc_timestamp (rounded to the microsecond), which is
// also kept as double seconds.
#include <cstddef>

#include "kestrel/logs/field_cursor.hpp"
#include "kestrel/logs/line_reader.hpp"
#include "kestrel/logs/log_source.hpp"

namespace kestrel::logs {

struct CarmenReaderOptions {
  TimeOrder time_order = TimeOrder::kError;
  double flaser_max_range_m = 80.0;  // FLASER readings at or beyond this are no return
};

class CarmenReader final : public LogSource {
 public:
  explicit CarmenReader(const CarmenReaderOptions& options = {}) : options_(options) {}

  // kOk, or kIoError (error() says why) when the file cannot be opened.
  Status open(const char* path);

  Status next(LogRecord& out) override;
  const LogError& error() const override { return error_; }
  const LogStats& stats() const override { return stats_; }
  Duration scan_period() const override { return scan_period_; }
  Duration beam_interval() const override { return beam_interval_; }
  Duration imu_period() const override { return imu_period_; }

 private:
  enum class Parsed { kRecord, kSkip };
  Status parse_line(std::string_view line, LogRecord& out, Parsed& parsed);
  Status parse_flaser(FieldCursor& f, LogRecord& out);
  Status parse_robotlaser1(FieldCursor& f, LogRecord& out);
  Status parse_imu(FieldCursor& f, LogRecord& out);
  Status parse_param(FieldCursor& f);
  Status read_ranges(FieldCursor& f, std::size_t n, double max_range_m, LogRecord& out);
  Status read_timestamp(FieldCursor& f, LogRecord& out);
  // Applies the time-order policy; sets `drop` when the record must be skipped.
  Status check_order(LogRecord::Kind kind, TimeUs stamp, bool& drop);
  Status fail(Status s);
  Status fail(Status s, const char* reason);

  CarmenReaderOptions options_;
  LineReader lines_;
  LogError error_;
  LogStats stats_;
  bool have_last_[2] = {false, false};
  TimeUs last_[2];
  Duration scan_period_;
  Duration beam_interval_;
  Duration imu_period_;
};

}  // namespace kestrel::logs
