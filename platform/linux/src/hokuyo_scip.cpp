#include "kestrel/platform/linux/hokuyo_scip.hpp"

#include <numbers>

namespace kestrel::platform {

hal::LaserGeometry HokuyoModel::geometry() const {
  const float step = 2.0f * std::numbers::pi_v<float> / static_cast<float>(steps_per_rev);
  hal::LaserGeometry g;
  g.beam_count = static_cast<uint16_t>(last_step - first_step + 1);
  g.first_angle_rad = static_cast<float>(static_cast<int>(first_step) - static_cast<int>(front_step)) * step;
  g.angle_step_rad = step;
  g.min_range_mm = min_range_mm;
  g.max_range_mm = max_range_mm;
  g.scan_period = scan_period;
  return g;
}

Status HokuyoScip::start() {
  char req[20];
  const std::size_t n = comms::scip_md_request(model_.first_step, model_.last_step, 1, 0, 0, req, sizeof(req));
  if (n == 0) return Status::kInvalidArgument;
  const Result<std::size_t> w = link_.write(reinterpret_cast<const uint8_t*>(req), n);
  if (!w.ok()) return w.status();
  return w.value() == n ? Status::kOk : Status::kIoError;
}

Status HokuyoScip::pump() {
  uint8_t buf[512];
  // At most kMaxPumpBytes a call: a device that never pauses must not keep the loop here.
  for (std::size_t taken = 0; taken < kMaxPumpBytes;) {
    const Result<std::size_t> r = link_.read(buf, sizeof(buf));
    if (!r.ok()) return r.status();
    if (r.value() == 0) return Status::kOk;
    const TimeUs arrival = clock_.now();
    for (std::size_t i = 0; i < r.value(); ++i)
      if (decoder_.push(buf[i])) convert(arrival);
    taken += r.value();
  }
  return Status::kOk;
}

void HokuyoScip::convert(TimeUs arrival) {
  const comms::ScipScan& s = decoder_.scan();
  // The sensor clock is 24 bits of milliseconds: unwrap it so stamps stay monotonic.
  const uint32_t ms = s.sensor_time_ms & 0xFFFFFFu;
  if (sensor_clock_.known()) {
    unwrapped_ms_ += static_cast<int64_t>((ms - last_sensor_ms_) & 0xFFFFFFu);
  } else {
    unwrapped_ms_ = ms;
  }
  last_sensor_ms_ = ms;

  const hal::LaserGeometry g = model_.geometry();
  const int64_t step_us = model_.scan_period.us / model_.steps_per_rev;
  const TimeUs sensor_stamp{unwrapped_ms_ * 1000};
  if (!sensor_clock_.observe(sensor_stamp, arrival)) return;  // a stamp not to be believed: no scan
  scan_.stamp = scan_stamps_.to_board(sensor_clock_, sensor_stamp);
  scan_.scan_period = model_.scan_period;
  scan_.beam_interval = Duration{step_us};
  scan_.first_angle_rad = g.first_angle_rad +
                          static_cast<float>(s.start_step - model_.first_step) * g.angle_step_rad;
  scan_.angle_step_rad = g.angle_step_rad;
  scan_.max_range_mm = model_.max_range_mm;
  scan_.beam_count = s.count;
  for (std::size_t i = 0; i < s.count; ++i)
    scan_.range_mm[i] = comms::scip_to_range_mm(s.range_mm[i], model_.max_range_mm);
  fresh_ = true;
}

Status HokuyoScip::poll(LaserScan& out) {
  if (!fresh_) return Status::kNoData;
  out = scan_;
  fresh_ = false;
  return Status::kOk;
}

}  // namespace kestrel::platform
