#pragma once
// `kestrel-sim --record`: every scan as a ROBOTLASER1 line with the vehicle's true pose as the
// reference (x, y, heading at the scan's first beam), every IMU sample as an IMU line, and the
// scanner and IMU timing as PARAM lines, through logs::CarmenWriter. Played back by
// logs::CarmenReader + logs::LogReplay, the scans come out identical.
#include "kestrel/logs/carmen_writer.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

class CarmenRecorder final : public SimObserver {
 public:
  // Opens the log (".gz" compresses) and writes the IMU period: kOk or kIoError.
  Status open(const char* path, Duration imu_period);
  Status close();

  void on_scan(const LaserScan& scan, const VehicleState& truth) override;
  void on_imu(const ImuSample& sample) override;

  // The first write error, or kOk.
  Status status() const { return status_; }
  uint32_t lines() const { return writer_.lines_written(); }

 private:
  logs::CarmenWriter writer_;
  Status status_ = Status::kOk;
};

}  // namespace kestrel::sim
