#pragma once
// Watches a simulated flight through SimObserver and keeps what the outputs of a run need:
// the true pose at every scan (trajectory_truth.tum), a decimated true path (render.png), the
// last scan, distance and speed, contacts, the rooms entered and the laser's coverage of the
// world's reachable free area (metrics.json: coverage, coverage_t90_s, rooms_entered,
// t_all_rooms_s) and its history (coverage_vs_time.png: one sample a second). Coverage marks
// the free-space cells each beam crosses (every 4th beam of every 4th scan, in 2D along the
// true heading) up to its return or the maximum range.
#include <vector>

#include "kestrel/sim/free_space_map.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

class FlightRecorder final : public SimObserver {
 public:
  // `expected_duration` sizes the buffers up front, so recording a flight of that length does
  // not allocate once it runs.
  FlightRecorder(const World& world, const FreeSpaceMap& free_space, Duration expected_duration = Duration::from_s(60));

  void on_scan(const LaserScan& scan, const VehicleState& truth) override;
  void on_imu(const ImuSample& sample) override;
  void on_contact(const Contact& contact) override;
  void on_step(const VehicleState& truth) override;

  struct PathPoint {
    TimeUs stamp;
    double x, y, z, yaw;
  };
  const std::vector<VehicleState>& scan_truth() const { return scan_truth_; }
  const std::vector<PathPoint>& path() const { return path_; }
  const LaserScan& last_scan() const { return last_scan_; }
  const VehicleState& last_scan_truth() const { return last_scan_truth_; }
  bool has_scan() const { return scans_ > 0; }
  uint64_t scans() const { return scans_; }
  uint64_t imu_samples() const { return imu_samples_; }
  double distance_m() const { return distance_; }
  double max_speed_mps() const { return max_speed_; }
  double max_altitude_m() const { return max_z_; }
  double coverage() const;
  double coverage_t90_s() const { return t90_; }  // < 0 if never reached
  struct CoverageSample {
    double t_s;
    double coverage;
  };
  // Coverage sampled when it is updated, at most once per kCoveragePeriodS (the first update
  // at or after each whole period), plus the value at the newest update.
  static constexpr double kCoveragePeriodS = 1.0;
  const std::vector<CoverageSample>& coverage_series() const { return coverage_series_; }
  int rooms_entered() const;
  double t_all_rooms_s() const { return t_all_rooms_; }  // < 0 if never
  const std::vector<double>& room_entry_s() const { return room_entry_; }  // < 0: not entered
  const FreeSpaceMap& free_space() const { return free_; }
  bool seen(int ix, int iy) const {
    return free_.in_map(ix, iy) && seen_[static_cast<std::size_t>(iy) * free_.width() + ix];
  }

 private:
  void mark_beams(const LaserScan& scan, const VehicleState& truth);

  const World& world_;
  const FreeSpaceMap& free_;
  std::vector<uint8_t> seen_;
  std::size_t seen_reachable_ = 0;
  std::vector<VehicleState> scan_truth_;
  std::vector<PathPoint> path_;
  LaserScan last_scan_;
  VehicleState last_scan_truth_;
  VehicleState prev_;
  bool have_prev_ = false;
  uint64_t scans_ = 0, imu_samples_ = 0, steps_ = 0;
  double distance_ = 0, max_speed_ = 0, max_z_ = 0;
  double t90_ = -1;
  std::vector<CoverageSample> coverage_series_;
  double next_coverage_t_ = 0;
  std::vector<double> room_entry_;
  double t_all_rooms_ = -1;
};

}  // namespace kestrel::sim
