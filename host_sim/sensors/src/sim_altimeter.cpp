#include "kestrel/sim/sim_altimeter.hpp"

namespace kestrel::sim {

Status SimAltimeter::poll(AltimeterSample& out) {
  return queue_.pop(out) ? Status::kOk : Status::kNoData;
}

}  // namespace kestrel::sim
