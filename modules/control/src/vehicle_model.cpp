#include "kestrel/control/vehicle_model.hpp"

#include <cmath>

namespace kestrel::control {

Status validate(const VehicleModel& m) {
  for (const AxisModel* a : {&m.pitch, &m.roll, &m.thrust, &m.yaw}) {
    if (!std::isfinite(a->k) || !std::isfinite(a->b)) return Status::kNotFinite;
    if (!(a->k > 1e-3f)) return Status::kInvalidArgument;
  }
  return Status::kOk;
}

}  // namespace kestrel::control
