#include "kestrel/output/tum_writer.hpp"

#include <cmath>

namespace kestrel::output {

TumWriter::~TumWriter() { (void)close(); }

Status TumWriter::open(const std::string& path) {
  (void)close();
  f_ = std::fopen(path.c_str(), "w");
  if (f_ == nullptr) return Status::kIoError;
  std::fprintf(f_, "# timestamp x y z qx qy qz qw\n");
  return Status::kOk;
}

Status TumWriter::write(double t_s, double x, double y, double z, double yaw, double roll, double pitch) {
  if (f_ == nullptr) return Status::kClosed;
  // ZYX Euler angles to a unit quaternion.
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
  const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  const double qw = cr * cp * cy + sr * sp * sy;
  const double qx = sr * cp * cy - cr * sp * sy;
  const double qy = cr * sp * cy + sr * cp * sy;
  const double qz = cr * cp * sy - sr * sp * cy;
  return std::fprintf(f_, "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t_s, x, y, z, qx, qy, qz, qw) > 0
             ? Status::kOk
             : Status::kIoError;
}

Status TumWriter::close() {
  if (f_ == nullptr) return Status::kOk;
  const int rc = std::fclose(f_);
  f_ = nullptr;
  return rc == 0 ? Status::kOk : Status::kIoError;
}

}  // namespace kestrel::output
