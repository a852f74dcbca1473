#pragma once
// A fake strap-down IMU behind hal::Imu: specific force and angular rate in the body frame
// (x forward, y left, z up; standing still it reads +g on z), each axis with white noise, a
// constant bias drawn from the seed and a bias random walk. Samples are queued at the IMU's
// rate and read oldest first.
#include <Eigen/Core>

#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/hal/imu.hpp"
#include "kestrel/sim/imu_params.hpp"
#include "kestrel/sim/random.hpp"
#include "kestrel/sim/vehicle.hpp"

namespace kestrel::sim {

class SimImu final : public hal::Imu {
 public:
  SimImu(const ImuParams& params, Rng rng);

  Duration sample_period() const override { return period_; }
  Status poll(ImuSample& out) override;

  // Takes a sample when `after.stamp` reaches the next sample time. Returns true if it did
  // (the sample is then last_sample()).
  bool on_step(const VehicleState& after);
  const ImuSample& last_sample() const { return last_; }
  Eigen::Vector3d accel_bias() const { return accel_bias_; }
  Eigen::Vector3d gyro_bias() const { return gyro_bias_; }
  uint64_t overruns() const { return overruns_; }  // samples lost because nobody read them

 private:
  ImuParams p_;
  Rng rng_;
  Duration period_;
  TimeUs next_;
  Eigen::Vector3d accel_bias_, gyro_bias_;
  double accel_sigma_, gyro_sigma_, accel_walk_, gyro_walk_;
  RingBuffer<ImuSample, 256> queue_;
  ImuSample last_;
  uint64_t overruns_ = 0;
};

}  // namespace kestrel::sim
