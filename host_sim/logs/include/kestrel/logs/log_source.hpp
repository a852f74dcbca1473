#pragma once
// A stream of log records, whatever the file format: what the replay drivers and the replay
// tool read from.
#include "kestrel/core/status.hpp"
#include "kestrel/logs/log_record.hpp"

namespace kestrel::logs {

class LogSource {
 public:
  virtual ~LogSource() = default;

  // Fills `out` with the next record: kOk; kNoData at the clean end of the log; any other
  // Status is an error, described by error(). Errors are sticky: once next() has failed it
  // returns the same Status again. After a failure the contents of `out` are unspecified.
  virtual Status next(LogRecord& out) = 0;
  virtual const LogError& error() const = 0;
  virtual const LogStats& stats() const = 0;
  // Scanner timing the log declares (zero when it does not): copied into every scan.
  virtual Duration scan_period() const = 0;
  virtual Duration beam_interval() const = 0;
  // IMU sample period the log declares, zero when it does not.
  virtual Duration imu_period() const = 0;
};

}  // namespace kestrel::logs
