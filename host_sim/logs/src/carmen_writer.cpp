#include "kestrel/logs/carmen_writer.hpp"

#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace kestrel::logs {

namespace {

gzFile as_gz(void* f) { return static_cast<gzFile>(f); }

bool ends_with(const char* s, const char* suffix) {
  const std::size_t n = std::strlen(s), m = std::strlen(suffix);
  return n >= m && std::strcmp(s + n - m, suffix) == 0;
}

// Appends with snprintf semantics; `len` stops growing once the buffer is full, which
// emit() then reports.
template <class... Args>
void append(char* buf, std::size_t cap, std::size_t& len, const char* fmt, Args... args) {
  if (len >= cap) return;
  const int n = std::snprintf(buf + len, cap - len, fmt, args...);
  if (n < 0) {
    len = cap;
    return;
  }
  len += static_cast<std::size_t>(n);
}

// " m.mmm" for a range in millimetres, without printf: a 1081-beam scan is formatted 40 times a
// second of simulated flight, and the simulator runs 50 times faster than real time.
void append_mm(char* buf, std::size_t cap, std::size_t& len, uint16_t mm) {
  if (len + 8 > cap) {
    len = cap;
    return;
  }
  char* p = buf + len;
  *p++ = ' ';
  unsigned metres = mm / 1000u;
  const unsigned frac = mm % 1000u;
  char digits[2];
  int nd = 0;
  do {
    digits[nd++] = static_cast<char>('0' + metres % 10u);
    metres /= 10u;
  } while (metres > 0 && nd < 2);
  while (nd > 0) *p++ = digits[--nd];
  *p++ = '.';
  *p++ = static_cast<char>('0' + frac / 100u);
  *p++ = static_cast<char>('0' + frac / 10u % 10u);
  *p++ = static_cast<char>('0' + frac % 10u);
  len = static_cast<std::size_t>(p - buf);
}

}  // namespace

CarmenWriter::~CarmenWriter() { (void)close(); }

Status CarmenWriter::open(const char* path, const char* hostname) {
  (void)close();
  if (path == nullptr) return Status::kIoError;
  // "T": write without compression (transparent), so both cases share one code path. Level 1:
  // the simulator records at 50 times real time, and level 6 costs half as much again per scan
  // (logs/write_utm30_scan) for a slightly smaller file.
  gzFile f = gzopen(path, ends_with(path, ".gz") ? "wb1" : "wbT");
  if (f == nullptr) return Status::kIoError;
  file_ = f;
  failed_ = false;
  timing_written_ = false;
  lines_ = 0;
  // Host names are one field: no spaces.
  std::snprintf(host_, sizeof host_, "%s", hostname != nullptr && hostname[0] != '\0' ? hostname : "kestrel");
  for (char& c : host_) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = '_';
  }
  // The header also makes zlib allocate its buffers now rather than on the first scan.
  const char* header =
      "# CARMEN log written by kestrel\n"
      "# message formats defined: PARAM ROBOTLASER1 IMU\n"
      "# ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy remission_mode "
      "num_readings [range] num_remissions [remission] laser_pose_x laser_pose_y laser_pose_theta "
      "robot_pose_x robot_pose_y robot_pose_theta laser_tv laser_rv forward_safety_dist "
      "side_safety_dist turn_axis timestamp hostname logger_timestamp\n"
      "# IMU accelerationX accelerationY accelerationZ quaternion_q0 quaternion_q1 quaternion_q2 "
      "quaternion_q3 magneticfieldX magneticfieldY magneticfieldZ gyroX gyroY gyroZ timestamp "
      "hostname logger_timestamp\n";
  const std::size_t n = std::strlen(header);
  std::memcpy(line_.data(), header, n);
  const Status s = emit(n);
  lines_ = 0;
  if (!ok(s)) return s;
  if (gzflush(f, Z_SYNC_FLUSH) != Z_OK) {
    failed_ = true;
    return Status::kIoError;
  }
  return Status::kOk;
}

Status CarmenWriter::close() {
  if (file_ == nullptr) return Status::kOk;
  const int rc = gzclose(as_gz(file_));
  file_ = nullptr;
  return rc == Z_OK && !failed_ ? Status::kOk : Status::kIoError;
}

Status CarmenWriter::emit(std::size_t len) {
  if (file_ == nullptr) return Status::kClosed;
  if (len >= line_.size()) {
    failed_ = true;
    return Status::kCapacityExceeded;
  }
  if (gzwrite(as_gz(file_), line_.data(), static_cast<unsigned>(len)) != static_cast<int>(len)) {
    failed_ = true;
    return Status::kIoError;
  }
  ++lines_;
  return Status::kOk;
}

Status CarmenWriter::write_param(const char* name, long long value, TimeUs stamp) {
  if (file_ == nullptr) return Status::kClosed;
  std::size_t len = 0;
  append(line_.data(), line_.size(), len, "PARAM %s %lld %.6f %s %.6f\n", name, value, stamp.seconds(), host_,
         stamp.seconds());
  return emit(len);
}

Status CarmenWriter::write_scan(const LaserScan& scan, const Pose2d& true_pose) {
  if (file_ == nullptr) return Status::kClosed;
  if (scan.beam_count == 0 || scan.beam_count > kMaxBeams || !true_pose.finite() ||
      !std::isfinite(scan.first_angle_rad) || !std::isfinite(scan.angle_step_rad) || scan.max_range_mm == 0) {
    return Status::kInvalidArgument;
  }
  if (!timing_written_) {
    Status s = write_param("kestrel_laser_scan_period_us", scan.scan_period.us, scan.stamp);
    if (ok(s)) s = write_param("kestrel_laser_beam_interval_us", scan.beam_interval.us, scan.stamp);
    if (!ok(s)) return s;
    timing_written_ = true;
  }
  const double t = scan.stamp.seconds();
  const double max_m = scan.max_range_mm * 1e-3;
  const double fov = static_cast<double>(scan.angle_step_rad) * (scan.beam_count - 1);
  char* buf = line_.data();
  const std::size_t cap = line_.size();
  std::size_t len = 0;
  // laser_type 99: CARMEN's "unknown proximity sensor"; accuracy: the 1 mm of the ranges.
  // Angles as %.9g so that the float geometry survives the round trip bit for bit.
  append(buf, cap, len, "ROBOTLASER1 99 %.9g %.9g %.9g %.3f 0.001 0 %u", static_cast<double>(scan.first_angle_rad),
         fov, static_cast<double>(scan.angle_step_rad), max_m, static_cast<unsigned>(scan.beam_count));
  for (std::size_t i = 0; i < scan.beam_count; ++i) {
    const uint16_t r = scan.range_mm[i];
    if (r == range_code::kNoReturn || r >= scan.max_range_mm) {
      append_mm(buf, cap, len, scan.max_range_mm);
    } else {
      append_mm(buf, cap, len, r);
    }
  }
  append(buf, cap, len, " 0 %.6f %.6f %.9g %.6f %.6f %.9g 0 0 0 0 0 %.6f %s %.6f\n", true_pose.x, true_pose.y,
         true_pose.theta, true_pose.x, true_pose.y, true_pose.theta, t, host_, t);
  return emit(len);
}

Status CarmenWriter::write_imu(const ImuSample& imu) {
  if (file_ == nullptr) return Status::kClosed;
  if (!imu.accel_mps2.allFinite() || !imu.gyro_radps.allFinite()) return Status::kInvalidArgument;
  const double t = imu.stamp.seconds();
  std::size_t len = 0;
  append(line_.data(), line_.size(), len, "IMU %.9g %.9g %.9g 1 0 0 0 0 0 0 %.9g %.9g %.9g %.6f %s %.6f\n",
         static_cast<double>(imu.accel_mps2.x()), static_cast<double>(imu.accel_mps2.y()),
         static_cast<double>(imu.accel_mps2.z()), static_cast<double>(imu.gyro_radps.x()),
         static_cast<double>(imu.gyro_radps.y()), static_cast<double>(imu.gyro_radps.z()), t, host_, t);
  return emit(len);
}

}  // namespace kestrel::logs
