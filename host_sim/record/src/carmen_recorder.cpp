#include "kestrel/sim/carmen_recorder.hpp"

namespace kestrel::sim {

Status CarmenRecorder::open(const char* path, Duration imu_period) {
  status_ = writer_.open(path, "kestrel-sim");
  if (status_ != Status::kOk) return status_;
  status_ = writer_.write_param("kestrel_imu_period_us", imu_period.us, TimeUs{});
  return status_;
}

Status CarmenRecorder::close() {
  const Status s = writer_.close();
  if (status_ == Status::kOk) status_ = s;
  return status_;
}

void CarmenRecorder::on_scan(const LaserScan& scan, const VehicleState& truth) {
  if (!writer_.is_open()) return;
  const Pose2d pose{truth.position_m.x(), truth.position_m.y(), truth.yaw_rad};
  const Status s = writer_.write_scan(scan, pose);
  if (status_ == Status::kOk) status_ = s;
}

void CarmenRecorder::on_imu(const ImuSample& sample) {
  if (!writer_.is_open()) return;
  const Status s = writer_.write_imu(sample);
  if (status_ == Status::kOk) status_ = s;
}

}  // namespace kestrel::sim
