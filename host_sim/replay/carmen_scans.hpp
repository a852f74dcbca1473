#pragma once
// A minimal reader of the laser lines of CARMEN logs (FLASER) and of the URG-04LX `.dat`
// format of the Mines ParisTech recording, for kestrel-replay. Host only. The shared reader of
// host_sim/logs replaces it once it is on main.
#include <string>
#include <vector>

#include "kestrel/core/messages.hpp"

namespace kestrel::replay {

struct LogScan {
  LaserScan scan;
  double stamp_s = 0;       // ipc_timestamp (CARMEN) or the recorded time (mines)
  bool has_reference = false;
  Pose2d reference;         // the log's corrected pose, when it has one
};

// Reads every scan; on a malformed line returns false with "FILE:LINE: reason" in `error`.
bool read_log(const std::string& path, const std::string& format, std::vector<LogScan>& out, std::string& error);

}  // namespace kestrel::replay
