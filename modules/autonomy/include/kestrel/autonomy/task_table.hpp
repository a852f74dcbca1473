#pragma once
// The real-time loop's task table (level 2 of paper 000 Figure 4), one constexpr row per task:
// name, release period and execution budget. Periods of the sensor tasks are polling periods:
// a task releases often so that a measurement waits little, and does work only when one has
// arrived. Budgets follow DESIGN.md: scan matching + EKF + guidance + control share half the
// CPU of one scan period (12.5 ms of 25 ms on the Overo; 50 of 100 ms on the Verdex).
#include <array>

#include "kestrel/core/time.hpp"

namespace kestrel::autonomy {

enum class TaskId : uint8_t { kImu, kScanMatch, kGuidance, kControl, kCount };

struct TaskRow {
  TaskId id;
  const char* name;
  Duration period;
  Duration budget;
};

// `scan_period` is the laser's (25 ms for the UTM-30LX, 100 ms for the URG-04LX).
constexpr std::array<TaskRow, 4> task_table(Duration scan_period) {
  return {{
      {TaskId::kImu, "imu", Duration::from_ms(5), Duration::from_us(500)},
      {TaskId::kScanMatch, "scan_match", Duration::from_ms(5), Duration{scan_period.us * 2 / 5}},
      {TaskId::kGuidance, "guidance", Duration::from_ms(5), Duration{scan_period.us / 20}},
      {TaskId::kControl, "control", Duration::from_ms(10), Duration::from_us(500)},
  }};
}

}  // namespace kestrel::autonomy
