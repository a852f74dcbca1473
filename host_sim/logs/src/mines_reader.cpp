#include "kestrel/logs/mines_reader.hpp"

#include <cstdio>
#include <cstring>

#include "kestrel/core/angle.hpp"

namespace kestrel::logs {

namespace {
constexpr int kStepsPerRevolution = 1024;
constexpr int kFrontStep = 384;
constexpr int kFirstStep = 44;
}  // namespace

Duration MinesReader::beam_interval() const {
  return Duration::from_us((options_.scan_period.us + kStepsPerRevolution / 2) / kStepsPerRevolution);
}

Status MinesReader::open(const char* path) {
  error_ = LogError{};
  stats_ = LogStats{};
  have_last_ = false;
  const Status s = lines_.open(path);
  if (!ok(s)) {
    std::snprintf(error_.reason, sizeof error_.reason, "%s", lines_.reason());
    return fail(s);
  }
  return Status::kOk;
}

Status MinesReader::fail(Status s) {
  error_.status = s;
  error_.line = lines_.line_number();
  return s;
}

Status MinesReader::next(LogRecord& out) {
  if (error_.status != Status::kOk) return error_.status;
  while (true) {
    std::string_view line;
    const Status s = lines_.next(line);
    if (s == Status::kNoData) return Status::kNoData;
    if (!ok(s)) {
      std::snprintf(error_.reason, sizeof error_.reason, "%s", lines_.reason());
      return fail(s);
    }
    ++stats_.lines;
    FieldCursor probe(line);
    std::string_view first;
    if (!probe.next(first) || first[0] == '#') {
      ++stats_.skipped_lines;
      continue;
    }
    const Status p = parse(line, out);
    if (!ok(p)) return fail(p);
    if (have_last_ && out.scan.stamp < last_) {
      if (options_.time_order == TimeOrder::kError) {
        std::snprintf(error_.reason, sizeof error_.reason,
                      "time stamp %lld us is older than the previous %lld us",
                      static_cast<long long>(out.scan.stamp.us), static_cast<long long>(last_.us));
        return fail(Status::kTimeJump);
      }
      ++stats_.backward_stamps;
      if (options_.time_order == TimeOrder::kDrop) continue;
    }
    have_last_ = true;
    last_ = out.scan.stamp;
    out.line = lines_.line_number();
    ++stats_.laser_records;
    return Status::kOk;
  }
}

Status MinesReader::parse(std::string_view line, LogRecord& out) {
  FieldCursor f(line);
  const std::size_t fields = f.remaining();
  if (fields != kFirstRangeField + kBeams && fields != kFirstRangeField + kBeams + 1) {
    std::snprintf(error_.reason, sizeof error_.reason, "%zu fields, expected %d or %d", fields,
                  kFirstRangeField + kBeams, kFirstRangeField + kBeams + 1);
    return Status::kMalformed;
  }
  long long stamp_us = 0;
  Status s = f.read_int(stamp_us, error_.reason, sizeof error_.reason);
  if (!ok(s)) return s;
  if (stamp_us > kMaxLogStampUs || stamp_us < -kMaxLogStampUs) {
    std::snprintf(error_.reason, sizeof error_.reason, "field 1: time stamp %lld us out of range", stamp_us);
    return Status::kOutOfRange;
  }
  for (int i = 1; i < kFirstRangeField; ++i) {
    s = f.skip(error_.reason, sizeof error_.reason);
    if (!ok(s)) return s;
  }
  LaserScan& scan = out.scan;
  for (int i = 0; i < kBeams; ++i) {
    long long mm = 0;
    s = f.read_int(mm, error_.reason, sizeof error_.reason);
    if (!ok(s)) return s;
    if (mm < 0 || mm > 65535) {
      // 1-based, as FieldCursor's own messages count (the header's layout counts from 0).
      std::snprintf(error_.reason, sizeof error_.reason, "field %zu: range %lld mm out of range",
                    f.field_index(), mm);
      return Status::kMalformed;
    }
    scan.range_mm[static_cast<std::size_t>(i)] =
        mm > options_.max_range_mm ? range_code::kNoReturn : static_cast<uint16_t>(mm);
  }
  std::memset(scan.range_mm.data() + kBeams, 0, (kMaxBeams - kBeams) * sizeof scan.range_mm[0]);
  const double step = 2.0 * kPi<double> / kStepsPerRevolution;
  out.kind = LogRecord::Kind::kLaser;
  out.has_pose = false;
  out.pose = Pose2d{};
  out.odom_pose = Pose2d{};
  out.timestamp_s = static_cast<double>(stamp_us) * 1e-6;
  scan.stamp = TimeUs::from_us(stamp_us);
  scan.scan_period = options_.scan_period;
  scan.beam_interval = beam_interval();
  scan.first_angle_rad = static_cast<float>((kFirstStep - kFrontStep) * step);
  scan.angle_step_rad = static_cast<float>(step);
  scan.max_range_mm = options_.max_range_mm;
  scan.beam_count = kBeams;
  return Status::kOk;
}

}  // namespace kestrel::logs
