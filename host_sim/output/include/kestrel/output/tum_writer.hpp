#pragma once
// Trajectories in the TUM RGB-D benchmark format, one pose per line:
//   timestamp x y z qx qy qz qw
// with the timestamp of the measurement the pose came from (seconds, microsecond precision).
#include <cstdio>
#include <string>

#include "kestrel/core/status.hpp"

namespace kestrel::output {

class TumWriter {
 public:
  TumWriter() = default;
  ~TumWriter();
  TumWriter(const TumWriter&) = delete;
  TumWriter& operator=(const TumWriter&) = delete;

  Status open(const std::string& path);
  // A planar pose: yaw about z; roll and pitch may be given for a 3D attitude.
  Status write(double t_s, double x, double y, double z, double yaw, double roll = 0, double pitch = 0);
  Status close();

 private:
  FILE* f_ = nullptr;
};

}  // namespace kestrel::output
