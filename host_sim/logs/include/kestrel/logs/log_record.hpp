#pragma once
// What a log reader hands out: one laser scan (with the reference pose the log carries, if
// any) or one IMU sample, plus the facts needed to report a bad line. Fixed size, so a
// reader fills the caller's record in place and never allocates per line.
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::logs {

struct LogRecord {
  enum class Kind : uint8_t { kLaser, kImu };

  Kind kind = Kind::kLaser;
  uint32_t line = 0;             // 1-based line (CARMEN, Mines) the record came from
  double timestamp_s = 0;        // the log's own time stamp (CARMEN ipc_timestamp), seconds

  // kLaser: ranges in mm, no-return and error codes below kMinValidRangeMm (see messages.hpp).
  LaserScan scan;
  bool has_pose = false;         // true when the line carries a reference pose
  Pose2d pose;                   // reference pose of the laser: FLASER `x y theta`,
                                 // ROBOTLASER1 laser pose (m, m, rad)
  Pose2d odom_pose;              // FLASER `odom_*`, ROBOTLASER1 robot pose (m, m, rad)

  // kImu
  ImuSample imu;
};

// The largest time stamp, either sign, a reader accepts: 10^12 s (31,700 years; a Unix stamp is
// 1.7e9). Any two stamps then differ by at most 2e18 us, so their difference, and a replay's
// offset onto a clock added to one, stay within TimeUs's int64; at the int64 limit itself a
// stamp of -9e12 s and one of +9e12 s made the clock-paced replay's sum wrap.
inline constexpr int64_t kMaxLogStampUs = 1'000'000'000'000'000'000;

// Why reading stopped: the Status, the 1-based line and a short human-readable reason.
struct LogError {
  Status status = Status::kOk;
  uint32_t line = 0;
  char reason[120] = {};
};

// How a reader treats a time stamp older than the previous one of the same stream (laser or
// IMU). Real logs have a few: intel.log.gz steps back four times, by up to 0.9 s.
enum class TimeOrder : uint8_t {
  kError,   // stop with Status::kTimeJump (the default: time going backwards is a fault)
  kAccept,  // hand the record out unchanged and count it
  kDrop,    // skip the record and count it
};

// Counters a reader keeps while it reads.
struct LogStats {
  uint32_t lines = 0;            // lines read, including skipped ones
  uint32_t laser_records = 0;    // handed out
  uint32_t imu_records = 0;      // handed out
  uint32_t skipped_lines = 0;    // comments, blank lines, message types not read
  uint32_t backward_stamps = 0;  // records whose stamp went backwards (kAccept or kDrop)
};

}  // namespace kestrel::logs
