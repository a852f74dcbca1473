#pragma once
// Writes kestrel runs as CARMEN logs that CARMEN tools and CarmenReader both read:
//   ROBOTLASER1 lines for scans of any field of view, with the true pose as the laser and
//   robot pose (the reference a scan matcher is measured against), ranges in metres with
//   millimetre precision: a no-return beam is written as the maximum range (CARMEN's
//   convention), error codes 1..19 as 0.001..0.019 m, so CarmenReader gives back exactly the
//   same LaserScan;
//   IMU lines in CARMEN's layout, with the orientation written as the unknown quaternion
//   1 0 0 0 and no magnetometer (0 0 0);
//   PARAM kestrel_laser_scan_period_us / kestrel_laser_beam_interval_us before the first
//   scan, so the scanner timing survives the round trip.
// A path ending in ".gz" is gzip-compressed. Lines are formatted in a fixed buffer and zlib's
// buffers are set up in open(): writing does not allocate, so the simulator can record while
// the allocation guard is armed.
#include <array>
#include <cstddef>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::logs {

class CarmenWriter {
 public:
  CarmenWriter() = default;
  ~CarmenWriter();
  CarmenWriter(const CarmenWriter&) = delete;
  CarmenWriter& operator=(const CarmenWriter&) = delete;

  // Creates the file and writes the header comment: kOk or kIoError.
  Status open(const char* path, const char* hostname = "kestrel");
  // Flushes and closes: kOk, or kIoError when anything failed to reach the file.
  Status close();
  bool is_open() const { return file_ != nullptr; }

  // kInvalidArgument for a scan with no beams, more than kMaxBeams, or a non-finite pose or
  // geometry; kIoError when the write fails.
  Status write_scan(const LaserScan& scan, const Pose2d& true_pose);
  // kInvalidArgument for non-finite values.
  Status write_imu(const ImuSample& imu);
  // PARAM name value: CARMEN's way of recording configuration (e.g. kestrel_imu_period_us).
  Status write_param(const char* name, long long value, TimeUs stamp);

  uint32_t lines_written() const { return lines_; }

 private:
  Status emit(std::size_t len);

  void* file_ = nullptr;  // gzFile
  char host_[32] = {};
  bool timing_written_ = false;
  bool failed_ = false;
  uint32_t lines_ = 0;
  // A ROBOTLASER1 line of 1081 beams takes at most about 1081 * 7 + 300 bytes.
  std::array<char, 16384> line_{};
};

}  // namespace kestrel::logs
