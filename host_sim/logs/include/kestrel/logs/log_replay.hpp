#pragma once
// Plays a recorded log through the HAL: one LogSource demultiplexed into a LaserScanner and an
// Imu, so the same stack that flies on the real drivers or the simulator runs on a log.
//
// Paced by a clock (the simulator's lockstep clock, a ManualTimeSource, a real clock), a
// record is released once the clock reaches its stamp; with align_start the log's first stamp
// is mapped onto the clock's time at prime(), and the stamps handed out are shifted by the
// same offset, so they live on the vehicle's timeline. Each stream is released by its own
// stamps: the reader reads ahead up to `reorder_window` past the clock into one queue per
// stream, because a recorder writes a scan when its sweep ends, after IMU samples younger than
// the scan's stamp. Without a clock, records are released as fast as they are polled: each
// poll of the scanner reads up to the next scan (IMU samples met on the way are queued), each
// poll of the IMU reads up to the next sample (scans met on the way are queued).
//
// As the HAL asks, the scanner hands out the newest due scan not yet read (older due ones are
// dropped and counted; without a clock every scan is handed out in order) and the IMU the
// oldest sample. A full queue drops its oldest entry and counts it. When the log ends each
// driver returns kClosed; when the log is bad, each driver returns the reader's error Status
// once, then kClosed. No allocation after construction.
#include <array>

#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/hal/imu.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/logs/log_source.hpp"

namespace kestrel::logs {

class LogReplay;

class ReplayLaserScanner final : public hal::LaserScanner {
 public:
  explicit ReplayLaserScanner(LogReplay& replay) : replay_(replay) {}
  hal::LaserGeometry geometry() const override;
  Status poll(LaserScan& out) override;

 private:
  LogReplay& replay_;
};

class ReplayImu final : public hal::Imu {
 public:
  explicit ReplayImu(LogReplay& replay) : replay_(replay) {}
  Duration sample_period() const override;
  Status poll(ImuSample& out) override;

 private:
  LogReplay& replay_;
};

struct ReplayOptions {
  bool align_start = true;                              // with a clock: first stamp -> clock.now()
  Duration reorder_window = Duration::from_ms(250);     // read-ahead past the clock
  uint16_t min_range_mm = 20;                           // reported in the geometry (logs lack it)
};

class LogReplay {
 public:
  static constexpr std::size_t kImuQueue = 256;   // 250 ms at 1 kHz
  static constexpr std::size_t kScanQueue = 16;   // 250 ms at 40 Hz, with room

  // `source` must be open; `clock` may be null (as fast as polled). Both must outlive this.
  LogReplay(LogSource& source, const TimeSource* clock = nullptr, const ReplayOptions& options = {});
  LogReplay(const LogReplay&) = delete;
  LogReplay& operator=(const LogReplay&) = delete;

  // Reads ahead to the first scan so geometry() can answer, and fixes the time offset.
  // kOk (also for a log without scans), or the reader's error.
  Status prime();

  hal::LaserScanner& laser() { return laser_; }
  hal::Imu& imu() { return imu_; }

  // The record of the scan last handed out by laser().poll(): its reference pose, its line.
  const LogRecord& last_scan_record() const { return last_scan_; }
  bool has_last_scan() const { return has_last_scan_; }
  // Added to every log stamp to put it on the clock's timeline.
  Duration time_offset() const { return offset_; }
  // True when the log is exhausted (or failed) and everything read has been handed out.
  bool finished() const;
  const LogSource& source() const { return source_; }
  uint32_t dropped_scans() const { return dropped_scans_; }
  uint32_t dropped_imu() const { return dropped_imu_; }

 private:
  friend class ReplayLaserScanner;
  friend class ReplayImu;

  hal::LaserGeometry geometry() const { return geometry_; }
  Duration imu_period() const { return source_.imu_period(); }
  Status poll_scan(LaserScan& out);
  Status poll_imu(ImuSample& out);
  // Reads one record into the look-ahead slot: false at the end of the log or on an error.
  bool fill_lookahead();
  TimeUs lookahead_stamp() const;
  // Moves the look-ahead record into its stream's queue, dropping that queue's oldest entry
  // when it is full.
  void route_lookahead();
  // With a clock: reads ahead until the next record is beyond now + reorder_window.
  void read_ahead(TimeUs now);
  Status end_status(int stream);
  bool stream_exhausted() const { return source_done_ && !has_lookahead_; }

  LogSource& source_;
  const TimeSource* clock_;
  ReplayOptions options_;
  ReplayLaserScanner laser_{*this};
  ReplayImu imu_{*this};

  bool primed_ = false;
  Duration offset_;
  hal::LaserGeometry geometry_;
  LogRecord lookahead_;
  bool has_lookahead_ = false;
  bool source_done_ = false;  // the source said kNoData or failed
  Status source_status_ = Status::kOk;
  bool error_reported_[2] = {false, false};
  std::array<LogRecord, kScanQueue> scans_;  // circular: oldest at scan_head_
  std::size_t scan_head_ = 0;
  std::size_t scan_count_ = 0;
  LogRecord last_scan_;
  bool has_last_scan_ = false;
  RingBuffer<ImuSample, kImuQueue> imu_queue_;
  uint32_t dropped_scans_ = 0;
  uint32_t dropped_imu_ = 0;
};

}  // namespace kestrel::logs
