#pragma once
// Reader of the Mines ParisTech URG-04LX recordings distributed with BreezySLAM (exp1.dat,
// exp2.dat): one scan per line, whitespace separated. Field 0 is the time stamp in
// microseconds, fields 2 and 3 wheel odometry counters (not read), fields 24 to 705 the 682
// ranges in millimetres (0: no return; 1..19: the URG's error codes, kept as LaserScan range
// codes). A line has 706 fields, or 707 with a trailing field BreezySLAM's loader drops too.
//
// Geometry is the URG-04LX's own: 1024 steps per revolution (0.3515625 degrees), front at
// step 384, and the 682 readings are steps 44 to 725, so the first beam is at -119.53 degrees
// and the last at +119.88, counter-clockwise. One revolution takes 100 ms (10 Hz).
#include "kestrel/logs/field_cursor.hpp"
#include "kestrel/logs/line_reader.hpp"
#include "kestrel/logs/log_source.hpp"

namespace kestrel::logs {

struct MinesReaderOptions {
  TimeOrder time_order = TimeOrder::kError;
  uint16_t max_range_mm = 5600;                     // URG-04LX: 4 m guaranteed, 5.6 m reported
  Duration scan_period = Duration::from_ms(100);    // 10 Hz
};

class MinesReader final : public LogSource {
 public:
  static constexpr int kBeams = 682;
  static constexpr int kFirstRangeField = 24;  // 0-based field of the first range

  explicit MinesReader(const MinesReaderOptions& options = {}) : options_(options) {}

  Status open(const char* path);

  Status next(LogRecord& out) override;
  const LogError& error() const override { return error_; }
  const LogStats& stats() const override { return stats_; }
  Duration scan_period() const override { return options_.scan_period; }
  Duration beam_interval() const override;
  Duration imu_period() const override { return {}; }

 private:
  Status parse(std::string_view line, LogRecord& out);
  Status fail(Status s);

  MinesReaderOptions options_;
  LineReader lines_;
  LogError error_;
  LogStats stats_;
  bool have_last_ = false;
  TimeUs last_;
};

}  // namespace kestrel::logs
