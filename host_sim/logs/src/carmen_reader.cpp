#include "kestrel/logs/carmen_reader.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "kestrel/core/angle.hpp"
#include "kestrel/logs/range_conversion.hpp"

namespace kestrel::logs {

namespace {

bool is_message_name(std::string_view w) {
  if (w.empty() || w[0] < 'A' || w[0] > 'Z') return false;
  for (char c : w) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

// CARMEN's guess of a FLASER's geometry from its beam count (see the header).
void flaser_geometry(std::size_t n, double& first, double& step) {
  const double pi = kPi<double>;
  first = -pi / 2;
  if (n == 180 || n == 181) {
    step = pi / 180.0;
  } else if (n == 360 || n == 361) {
    step = pi / 360.0;
  } else if (n == 400 || n == 401) {
    step = pi / 720.0;
    first = -deg_to_rad(50.0);
  } else {
    step = n > 1 ? pi / static_cast<double>(n - 1) : 0.0;
  }
}

}  // namespace

Status CarmenReader::open(const char* path) {
  error_ = LogError{};
  stats_ = LogStats{};
  have_last_[0] = have_last_[1] = false;
  scan_period_ = beam_interval_ = imu_period_ = Duration{};
  const Status s = lines_.open(path);
  if (!ok(s)) {
    error_.line = 0;
    return fail(s, lines_.reason());
  }
  return Status::kOk;
}

Status CarmenReader::fail(Status s) {
  error_.status = s;
  error_.line = lines_.line_number();
  return s;
}

Status CarmenReader::fail(Status s, const char* reason) {
  std::snprintf(error_.reason, sizeof error_.reason, "%s", reason);
  return fail(s);
}

Status CarmenReader::next(LogRecord& out) {
  if (error_.status != Status::kOk) return error_.status;
  while (true) {
    std::string_view line;
    const Status s = lines_.next(line);
    if (s == Status::kNoData) return Status::kNoData;
    if (!ok(s)) return fail(s, lines_.reason());
    ++stats_.lines;
    Parsed parsed = Parsed::kSkip;
    const Status p = parse_line(line, out, parsed);
    if (!ok(p)) return fail(p);
    if (parsed == Parsed::kSkip) continue;
    bool drop = false;
    const TimeUs stamp = out.kind == LogRecord::Kind::kLaser ? out.scan.stamp : out.imu.stamp;
    const Status t = check_order(out.kind, stamp, drop);
    if (!ok(t)) return fail(t);
    if (drop) continue;
    out.line = lines_.line_number();
    if (out.kind == LogRecord::Kind::kLaser) {
      ++stats_.laser_records;
    } else {
      ++stats_.imu_records;
    }
    return Status::kOk;
  }
}

Status CarmenReader::check_order(LogRecord::Kind kind, TimeUs stamp, bool& drop) {
  const int k = kind == LogRecord::Kind::kLaser ? 0 : 1;
  drop = false;
  if (have_last_[k] && stamp < last_[k]) {
    switch (options_.time_order) {
      case TimeOrder::kError:
        std::snprintf(error_.reason, sizeof error_.reason,
                      "time stamp %.6f s is older than the previous %s stamp %.6f s",
                      stamp.seconds(), k == 0 ? "laser" : "IMU", last_[k].seconds());
        return Status::kTimeJump;
      case TimeOrder::kAccept:
        ++stats_.backward_stamps;
        break;
      case TimeOrder::kDrop:
        ++stats_.backward_stamps;
        drop = true;
        return Status::kOk;
    }
  }
  have_last_[k] = true;
  last_[k] = stamp;
  return Status::kOk;
}

Status CarmenReader::parse_line(std::string_view line, LogRecord& out, Parsed& parsed) {
  FieldCursor f(line);
  std::string_view name;
  parsed = Parsed::kSkip;
  if (!f.next(name) || name[0] == '#') {
    ++stats_.skipped_lines;
    return Status::kOk;
  }
  if (!is_message_name(name)) {
    const int shown = static_cast<int>(name.size() < 24 ? name.size() : 24);
    std::snprintf(error_.reason, sizeof error_.reason, "not a CARMEN message line (starts with '%.*s')",
                  shown, name.data());
    return Status::kMalformed;
  }
  Status s = Status::kOk;
  if (name == "FLASER") {
    s = parse_flaser(f, out);
  } else if (name == "ROBOTLASER1") {
    s = parse_robotlaser1(f, out);
  } else if (name == "IMU") {
    s = parse_imu(f, out);
  } else {
    if (name == "PARAM") s = parse_param(f);
    ++stats_.skipped_lines;
    return s;
  }
  if (ok(s)) parsed = Parsed::kRecord;
  return s;
}

Status CarmenReader::read_ranges(FieldCursor& f, std::size_t n, double max_range_m, LogRecord& out) {
  LaserScan& scan = out.scan;
  for (std::size_t i = 0; i < n; ++i) {
    double r = 0;
    const Status s = f.read_double(r, error_.reason, sizeof error_.reason);
    if (!ok(s)) return s;
    if (!ok(metres_to_range_mm(r, max_range_m, scan.range_mm[i]))) {
      std::snprintf(error_.reason, sizeof error_.reason, "field %zu: negative range %g", f.field_index(), r);
      return Status::kMalformed;
    }
  }
  std::memset(scan.range_mm.data() + n, 0, (kMaxBeams - n) * sizeof scan.range_mm[0]);
  scan.beam_count = static_cast<uint16_t>(n);
  scan.scan_period = scan_period_;
  scan.beam_interval = beam_interval_;
  return Status::kOk;
}

Status CarmenReader::read_timestamp(FieldCursor& f, LogRecord& out) {
  double t = 0;
  Status s = f.read_double(t, error_.reason, sizeof error_.reason);
  if (!ok(s)) return s;
  // TimeUs counts microseconds in an int64: keep well inside it (log_record.hpp).
  if (!(std::fabs(t) * 1e6 <= static_cast<double>(kMaxLogStampUs))) {
    std::snprintf(error_.reason, sizeof error_.reason, "field %zu: time stamp %g s out of range",
                  f.field_index(), t);
    return Status::kOutOfRange;
  }
  out.timestamp_s = t;
  s = f.skip(error_.reason, sizeof error_.reason);  // hostname
  if (!ok(s)) return s;
  double logger_t = 0;
  s = f.read_double(logger_t, error_.reason, sizeof error_.reason);
  if (!ok(s)) return s;
  if (f.remaining() != 0) {
    std::snprintf(error_.reason, sizeof error_.reason, "%zu unexpected fields after the logger time stamp",
                  f.remaining());
    return Status::kMalformed;
  }
  return Status::kOk;
}

namespace {

Status read_count(FieldCursor& f, const char* what, long long& n, LogError& e) {
  const Status s = f.read_int(n, e.reason, sizeof e.reason);
  if (!ok(s)) return s;
  if (n < 0) {
    std::snprintf(e.reason, sizeof e.reason, "field %zu: negative %s %lld", f.field_index(), what, n);
    return Status::kMalformed;
  }
  return Status::kOk;
}

// A field the record carries as a float: finite as a double is not enough ("1e40" would be an
// IMU sample or a scan angle of inf).
Status read_float(FieldCursor& f, float& out, LogError& e) {
  double v = 0;
  const Status s = f.read_double(v, e.reason, sizeof e.reason);
  if (!ok(s)) return s;
  if (std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max())) {
    std::snprintf(e.reason, sizeof e.reason, "field %zu: %g is beyond a float's range", f.field_index(), v);
    return Status::kNotFinite;
  }
  out = static_cast<float>(v);
  return Status::kOk;
}

Status read_pose(FieldCursor& f, Pose2d& p, LogError& e) {
  Status s = f.read_double(p.x, e.reason, sizeof e.reason);
  if (ok(s)) s = f.read_double(p.y, e.reason, sizeof e.reason);
  double theta = 0;
  if (ok(s)) s = f.read_double(theta, e.reason, sizeof e.reason);
  p.theta = wrap_angle(theta);
  return s;
}

}  // namespace

Status CarmenReader::parse_flaser(FieldCursor& f, LogRecord& out) {
  long long n = 0;
  Status s = read_count(f, "beam count", n, error_);
  if (!ok(s)) return s;
  if (n == 0) {
    std::snprintf(error_.reason, sizeof error_.reason, "FLASER with no beams");
    return Status::kMalformed;
  }
  if (n > static_cast<long long>(kMaxBeams)) {
    std::snprintf(error_.reason, sizeof error_.reason, "%lld beams, more than kMaxBeams (%zu)", n, kMaxBeams);
    return Status::kCapacityExceeded;
  }
  const std::size_t expected = static_cast<std::size_t>(n) + 9;
  if (f.remaining() != expected) {
    std::snprintf(error_.reason, sizeof error_.reason,
                  "FLASER with %lld beams needs %zu fields after the count, found %zu", n, expected,
                  f.remaining());
    return Status::kMalformed;
  }
  out.kind = LogRecord::Kind::kLaser;
  s = read_ranges(f, static_cast<std::size_t>(n), options_.flaser_max_range_m, out);
  if (ok(s)) s = read_pose(f, out.pose, error_);
  if (ok(s)) s = read_pose(f, out.odom_pose, error_);
  if (ok(s)) s = read_timestamp(f, out);
  if (!ok(s)) return s;
  double first = 0, step = 0;
  flaser_geometry(static_cast<std::size_t>(n), first, step);
  out.scan.first_angle_rad = static_cast<float>(first);
  out.scan.angle_step_rad = static_cast<float>(step);
  out.scan.max_range_mm = max_range_to_mm(options_.flaser_max_range_m);
  out.scan.stamp = TimeUs::from_s(out.timestamp_s);
  out.has_pose = true;
  return Status::kOk;
}

Status CarmenReader::parse_robotlaser1(FieldCursor& f, LogRecord& out) {
  long long laser_type = 0, remission_mode = 0, n = 0, m = 0;
  double fov = 0, max_range = 0, accuracy = 0;
  float start = 0, res = 0;
  Status s = f.read_int(laser_type, error_.reason, sizeof error_.reason);
  if (ok(s)) s = read_float(f, start, error_);
  if (ok(s)) s = f.read_double(fov, error_.reason, sizeof error_.reason);
  if (ok(s)) s = read_float(f, res, error_);
  if (ok(s)) s = f.read_double(max_range, error_.reason, sizeof error_.reason);
  if (ok(s)) s = f.read_double(accuracy, error_.reason, sizeof error_.reason);
  if (ok(s)) s = f.read_int(remission_mode, error_.reason, sizeof error_.reason);
  if (ok(s)) s = read_count(f, "beam count", n, error_);
  if (!ok(s)) return s;
  if (!(max_range > 0)) {
    std::snprintf(error_.reason, sizeof error_.reason, "maximum range %g must be positive", max_range);
    return Status::kMalformed;
  }
  if (n == 0) {
    std::snprintf(error_.reason, sizeof error_.reason, "ROBOTLASER1 with no beams");
    return Status::kMalformed;
  }
  if (n > static_cast<long long>(kMaxBeams)) {
    std::snprintf(error_.reason, sizeof error_.reason, "%lld beams, more than kMaxBeams (%zu)", n, kMaxBeams);
    return Status::kCapacityExceeded;
  }
  if (n > 1 && res == 0) {  // also a resolution too fine for a float, e.g. 1e-300
    std::snprintf(error_.reason, sizeof error_.reason, "angular resolution is zero");
    return Status::kMalformed;
  }
  // n ranges, the remission count, then at least the 14 fields after the remissions.
  if (f.remaining() < static_cast<std::size_t>(n) + 15) {
    std::snprintf(error_.reason, sizeof error_.reason,
                  "ROBOTLASER1 with %lld beams needs at least %lld more fields, found %zu", n, n + 15,
                  f.remaining());
    return Status::kMalformed;
  }
  out.kind = LogRecord::Kind::kLaser;
  s = read_ranges(f, static_cast<std::size_t>(n), max_range, out);
  if (ok(s)) s = read_count(f, "remission count", m, error_);
  if (!ok(s)) return s;
  // At least 14 fields are left (checked above), so this cannot wrap, whatever m says.
  if (f.remaining() - 14 != static_cast<unsigned long long>(m)) {
    std::snprintf(error_.reason, sizeof error_.reason,
                  "remission count %lld, but %zu remission fields follow", m, f.remaining() - 14);
    return Status::kMalformed;
  }
  for (long long i = 0; i < m && ok(s); ++i) {
    double rem = 0;
    s = f.read_double(rem, error_.reason, sizeof error_.reason);
  }
  if (ok(s)) s = read_pose(f, out.pose, error_);
  if (ok(s)) s = read_pose(f, out.odom_pose, error_);
  for (int i = 0; i < 5 && ok(s); ++i) {  // tv rv forward_safety side_safety turn_axis
    double v = 0;
    s = f.read_double(v, error_.reason, sizeof error_.reason);
  }
  if (ok(s)) s = read_timestamp(f, out);
  if (!ok(s)) return s;
  out.scan.first_angle_rad = start;
  out.scan.angle_step_rad = res;
  out.scan.max_range_mm = max_range_to_mm(max_range);
  out.scan.stamp = TimeUs::from_s(out.timestamp_s);
  out.has_pose = true;
  return Status::kOk;
}

Status CarmenReader::parse_imu(FieldCursor& f, LogRecord& out) {
  if (f.remaining() != 16) {
    std::snprintf(error_.reason, sizeof error_.reason, "IMU needs 16 fields after the name, found %zu",
                  f.remaining());
    return Status::kMalformed;
  }
  // accX accY accZ, q0..q3 magX..magZ (not kept: any finite double), gyroX gyroY gyroZ.
  float v[13] = {};
  for (int i = 0; i < 13; ++i) {
    double ignored = 0;
    const bool kept = i < 3 || i >= 10;
    const Status s = kept ? read_float(f, v[i], error_) : f.read_double(ignored, error_.reason, sizeof error_.reason);
    if (!ok(s)) return s;
  }
  const Status s = read_timestamp(f, out);
  if (!ok(s)) return s;
  out.kind = LogRecord::Kind::kImu;
  out.has_pose = false;
  out.imu.stamp = TimeUs::from_s(out.timestamp_s);
  out.imu.accel_mps2 = Eigen::Vector3f(v[0], v[1], v[2]);
  out.imu.gyro_radps = Eigen::Vector3f(v[10], v[11], v[12]);
  return Status::kOk;
}

Status CarmenReader::parse_param(FieldCursor& f) {
  std::string_view name;
  if (!f.next(name)) return Status::kOk;  // a bare PARAM says nothing: skip it like CARMEN does
  Duration* target = nullptr;
  if (name == "kestrel_laser_scan_period_us") target = &scan_period_;
  if (name == "kestrel_laser_beam_interval_us") target = &beam_interval_;
  if (name == "kestrel_imu_period_us") target = &imu_period_;
  if (target == nullptr) return Status::kOk;
  long long us = 0;
  const Status s = f.read_int(us, error_.reason, sizeof error_.reason);
  if (!ok(s)) return s;
  if (us < 0 || us > 60'000'000) {
    std::snprintf(error_.reason, sizeof error_.reason, "PARAM %.*s: %lld us out of range",
                  static_cast<int>(name.size()), name.data(), us);
    return Status::kOutOfRange;
  }
  *target = Duration::from_us(us);
  return Status::kOk;
}

}  // namespace kestrel::logs
