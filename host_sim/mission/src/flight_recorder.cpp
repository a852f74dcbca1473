#include "kestrel/sim/flight_recorder.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::sim {

FlightRecorder::FlightRecorder(const World& world, const FreeSpaceMap& free_space, Duration expected_duration)
    : world_(world), free_(free_space) {
  const double s = std::max(1.0, expected_duration.seconds());
  scan_truth_.reserve(static_cast<std::size_t>(s * 40 + 64));  // up to 40 Hz scans
  path_.reserve(static_cast<std::size_t>(s * 50 + 64));        // every 20 steps of 1 ms
  coverage_series_.reserve(static_cast<std::size_t>(s / kCoveragePeriodS + 8));
  seen_.assign(static_cast<std::size_t>(free_.width()) * free_.height(), 0);
  room_entry_.assign(world_.rooms.size(), -1.0);
}

void FlightRecorder::on_step(const VehicleState& s) {
  if (have_prev_) distance_ += (s.position_m - prev_.position_m).norm();
  prev_ = s;
  have_prev_ = true;
  max_speed_ = std::max(max_speed_, s.velocity_mps.norm());
  max_z_ = std::max(max_z_, s.position_m.z());
  if (steps_++ % 20 == 0)
    path_.push_back({s.stamp, s.position_m.x(), s.position_m.y(), s.position_m.z(), s.yaw_rad});
  if (steps_ % 10 == 0) {
    const int room = world_.room_at(s.position_m.x(), s.position_m.y());
    if (room >= 0 && room_entry_[static_cast<std::size_t>(room)] < 0) {
      room_entry_[static_cast<std::size_t>(room)] = s.stamp.seconds();
      if (rooms_entered() == static_cast<int>(room_entry_.size())) t_all_rooms_ = s.stamp.seconds();
    }
  }
}

void FlightRecorder::on_imu(const ImuSample&) { ++imu_samples_; }
void FlightRecorder::on_contact(const Contact&) {}

void FlightRecorder::on_scan(const LaserScan& scan, const VehicleState& truth) {
  scan_truth_.push_back(truth);
  last_scan_ = scan;
  last_scan_truth_ = truth;
  if (scans_++ % 4 == 0) mark_beams(scan, truth);
}

void FlightRecorder::mark_beams(const LaserScan& scan, const VehicleState& truth) {
  const double res = free_.resolution_m();
  const double x0 = truth.position_m.x(), y0 = truth.position_m.y();
  for (std::size_t i = 0; i < scan.beam_count; i += 4) {
    const uint16_t r = scan.range_mm[i];
    if (r == range_code::kDeflected || r == range_code::kDropout || r == range_code::kTooNear) continue;
    const double range = LaserScan::is_return(r) ? r * 1e-3 : scan.max_range_mm * 1e-3;
    const double a = truth.yaw_rad + scan.angle_of(i);
    const double dx = std::cos(a), dy = std::sin(a);
    const int n = static_cast<int>(range / (res * 0.5));
    for (int k = 0; k <= n; ++k) {
      int ix = 0, iy = 0;
      free_.cell_of(x0 + dx * k * res * 0.5, y0 + dy * k * res * 0.5, ix, iy);
      if (!free_.in_map(ix, iy)) break;
      if (free_.occupied(ix, iy)) break;
      uint8_t& cell = seen_[static_cast<std::size_t>(iy) * free_.width() + ix];
      if (!cell) {
        cell = 1;
        if (free_.reachable(ix, iy)) ++seen_reachable_;
      }
    }
  }
  const double t = scan.stamp.seconds();
  if (t90_ < 0 && coverage() >= 0.9) t90_ = t;
  // The newest sample follows every update until the next period starts a new one; past the
  // reserved length (a run longer than announced) the series stops growing instead of
  // allocating in the loop.
  if (t >= next_coverage_t_ && coverage_series_.size() < coverage_series_.capacity()) {
    coverage_series_.push_back({t, coverage()});
    next_coverage_t_ = (std::floor(t / kCoveragePeriodS) + 1.0) * kCoveragePeriodS;
  } else if (!coverage_series_.empty()) {
    coverage_series_.back() = {t, coverage()};
  }
}

double FlightRecorder::coverage() const {
  return free_.reachable_cells() ? static_cast<double>(seen_reachable_) / free_.reachable_cells() : 0.0;
}

int FlightRecorder::rooms_entered() const {
  int n = 0;
  for (double t : room_entry_) n += t >= 0 ? 1 : 0;
  return n;
}

}  // namespace kestrel::sim
