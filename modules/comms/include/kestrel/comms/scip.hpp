#pragma once
// Hokuyo SCIP 2.0 (the URG-04LX's and UTM-30LX's serial protocol), as a pure codec:
//   - request builders (MD: continuous scanning, QT: stop, PP: parameters);
//   - a byte-at-a-time decoder of MD scan responses: echo line, status "99" + sum, time stamp
//     (4-character encoding, ms) + sum, then data blocks of up to 64 characters each followed by
//     its sum, ended by an empty line. Ranges use the 3-character encoding (6 bits per
//     character, offset 0x30). Every line's sum (low 6 bits of the byte sum, plus 0x30) is
//     checked; a bad line drops that scan and is counted.
//   - an encoder of MD scan responses, so the simulator can stand in for a real scanner on a
//     serial line and the real driver runs against it.
// Range values below 20 mm are the scanner's error codes; they map to core's range codes.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::comms {

char scip_sum(const uint8_t* data, std::size_t size);

// "MDssssEEEEccinn\n": start step, end step, cluster count, scan interval, number of scans
// (0 = unlimited). Returns the length written (16), or 0 if out is too small or a field
// does not fit.
std::size_t scip_md_request(uint16_t start_step, uint16_t end_step, uint8_t cluster, uint8_t interval,
                            uint8_t scans, char* out, std::size_t cap);

struct ScipScan {
  uint32_t sensor_time_ms = 0;  // the scanner's own 24-bit millisecond clock
  uint16_t start_step = 0;
  uint16_t count = 0;
  std::array<uint16_t, kMaxBeams> range_mm{};
};

class ScipDecoder {
 public:
  // Feeds one byte; true when a whole, checked scan has just completed (see scan()).
  bool push(uint8_t byte);
  const ScipScan& scan() const { return scan_; }
  uint32_t sum_errors() const { return sum_errors_; }
  uint32_t format_errors() const { return format_errors_; }
  uint32_t status_errors() const { return status_errors_; }  // status other than 00 / 99

 private:
  bool end_line();
  void fail(uint32_t& counter);

  std::array<uint8_t, 80> line_{};
  std::size_t line_len_ = 0;
  bool line_overflow_ = false;
  enum class Stage : uint8_t { kEcho, kStatus, kTime, kData, kSkipToBlank } stage_ = Stage::kEcho;
  uint16_t expected_ = 0;
  uint32_t carry_ = 0;  // pending 6-bit groups of a value split across lines
  uint8_t carry_chars_ = 0;
  ScipScan scan_;
  ScipScan building_;
  uint32_t sum_errors_ = 0;
  uint32_t format_errors_ = 0;
  uint32_t status_errors_ = 0;
};

// Writes an MD scan response for `ranges` (count values from start_step) into out; returns
// its length, or 0 if it does not fit (or a step does not fit the echo's four digits).
std::size_t scip_encode_md_scan(uint16_t start_step, uint16_t end_step, uint32_t sensor_time_ms,
                                const uint16_t* ranges, std::size_t count, uint8_t* out, std::size_t cap);

// Maps a SCIP range value to core's convention (values below 20 are error codes).
uint16_t scip_to_range_mm(uint16_t value, uint16_t max_range_mm);

}  // namespace kestrel::comms
