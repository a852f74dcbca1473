#include "kestrel/logs/range_conversion.hpp"

#include <cmath>

#include "kestrel/core/messages.hpp"

namespace kestrel::logs {

Status metres_to_range_mm(double metres, double max_range_m, uint16_t& out_mm) {
  if (metres < 0) return Status::kMalformed;
  if (metres >= max_range_m) {
    out_mm = range_code::kNoReturn;
    return Status::kOk;
  }
  const long long mm = std::llround(metres * 1000.0);
  // Beyond what a uint16 can hold is beyond every supported sensor: treat as no return.
  out_mm = mm > 65535 ? range_code::kNoReturn : static_cast<uint16_t>(mm);
  return Status::kOk;
}

uint16_t max_range_to_mm(double max_range_m) {
  if (!(max_range_m > 0)) return 0;
  const long long mm = std::llround(max_range_m * 1000.0);
  return mm > 65535 ? uint16_t{65535} : static_cast<uint16_t>(mm);
}

}  // namespace kestrel::logs
