#include "kestrel/logs/log_replay.hpp"

namespace kestrel::logs {

hal::LaserGeometry ReplayLaserScanner::geometry() const { return replay_.geometry(); }
Status ReplayLaserScanner::poll(LaserScan& out) { return replay_.poll_scan(out); }
Duration ReplayImu::sample_period() const { return replay_.imu_period(); }
Status ReplayImu::poll(ImuSample& out) { return replay_.poll_imu(out); }

LogReplay::LogReplay(LogSource& source, const TimeSource* clock, const ReplayOptions& options)
    : source_(source), clock_(clock), options_(options) {}

bool LogReplay::fill_lookahead() {
  if (has_lookahead_) return true;
  if (source_done_) return false;
  const Status s = source_.next(lookahead_);
  if (!ok(s)) {
    source_done_ = true;
    source_status_ = s == Status::kNoData ? Status::kOk : s;
    return false;
  }
  if (lookahead_.kind == LogRecord::Kind::kLaser) {
    lookahead_.scan.stamp = lookahead_.scan.stamp + offset_;
  } else {
    lookahead_.imu.stamp = lookahead_.imu.stamp + offset_;
  }
  has_lookahead_ = true;
  return true;
}

TimeUs LogReplay::lookahead_stamp() const {
  return lookahead_.kind == LogRecord::Kind::kLaser ? lookahead_.scan.stamp : lookahead_.imu.stamp;
}

Status LogReplay::prime() {
  if (primed_) return source_status_;
  primed_ = true;
  // The first record fixes the time offset; nothing has been shifted yet.
  if (fill_lookahead() && clock_ != nullptr && options_.align_start) {
    offset_ = clock_->now() - lookahead_stamp();
    if (lookahead_.kind == LogRecord::Kind::kLaser) {
      lookahead_.scan.stamp = lookahead_.scan.stamp + offset_;
    } else {
      lookahead_.imu.stamp = lookahead_.imu.stamp + offset_;
    }
  }
  // Read ahead to the first scan, so geometry() can answer before the first poll, but never
  // so far that IMU samples would be dropped (a log may hold no scans at all).
  while (scan_count_ == 0 && imu_queue_.size() < kImuQueue && fill_lookahead()) route_lookahead();
  if (scan_count_ > 0) {
    const LaserScan& s = scans_[scan_head_].scan;
    geometry_.beam_count = s.beam_count;
    geometry_.first_angle_rad = s.first_angle_rad;
    geometry_.angle_step_rad = s.angle_step_rad;
    geometry_.min_range_mm = options_.min_range_mm;
    geometry_.max_range_mm = s.max_range_mm;
    geometry_.scan_period = s.scan_period;
  }
  return source_status_;
}

void LogReplay::route_lookahead() {
  if (lookahead_.kind == LogRecord::Kind::kLaser) {
    if (scan_count_ == kScanQueue) {
      scan_head_ = (scan_head_ + 1) % kScanQueue;
      --scan_count_;
      ++dropped_scans_;
    }
    scans_[(scan_head_ + scan_count_) % kScanQueue] = lookahead_;
    ++scan_count_;
  } else {
    if (imu_queue_.size() == kImuQueue) {
      ImuSample oldest;
      (void)imu_queue_.pop(oldest);
      ++dropped_imu_;
    }
    (void)imu_queue_.push(lookahead_.imu);
  }
  has_lookahead_ = false;
}

void LogReplay::read_ahead(TimeUs now) {
  const TimeUs horizon = now + options_.reorder_window;
  while (fill_lookahead() && lookahead_stamp() <= horizon) route_lookahead();
}

Status LogReplay::end_status(int stream) {
  if (!stream_exhausted()) return Status::kNoData;
  if (source_status_ != Status::kOk && !error_reported_[stream]) {
    error_reported_[stream] = true;
    return source_status_;
  }
  return Status::kClosed;
}

Status LogReplay::poll_scan(LaserScan& out) {
  if (!primed_) (void)prime();
  if (clock_ != nullptr) {
    const TimeUs now = clock_->now();
    read_ahead(now);
    // Hand out the newest due scan; older due ones were never read in time.
    std::size_t due = 0;
    while (due < scan_count_ && scans_[(scan_head_ + due) % kScanQueue].scan.stamp <= now) ++due;
    if (due == 0) return scan_count_ > 0 ? Status::kNoData : end_status(0);
    dropped_scans_ += static_cast<uint32_t>(due - 1);
    scan_head_ = (scan_head_ + due - 1) % kScanQueue;
    scan_count_ -= due - 1;
  } else {
    while (scan_count_ == 0 && fill_lookahead()) route_lookahead();
    if (scan_count_ == 0) return end_status(0);
  }
  const LogRecord& rec = scans_[scan_head_];
  out = rec.scan;
  last_scan_ = rec;
  has_last_scan_ = true;
  scan_head_ = (scan_head_ + 1) % kScanQueue;
  --scan_count_;
  return Status::kOk;
}

Status LogReplay::poll_imu(ImuSample& out) {
  if (!primed_) (void)prime();
  if (clock_ != nullptr) {
    const TimeUs now = clock_->now();
    read_ahead(now);
    const ImuSample* oldest = imu_queue_.peek();
    if (oldest == nullptr) return end_status(1);
    if (oldest->stamp > now) return Status::kNoData;
  } else {
    while (imu_queue_.empty() && fill_lookahead()) route_lookahead();
  }
  if (imu_queue_.pop(out)) return Status::kOk;
  return end_status(1);
}

bool LogReplay::finished() const { return stream_exhausted() && scan_count_ == 0 && imu_queue_.empty(); }

}  // namespace kestrel::logs
