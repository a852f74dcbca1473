#pragma once
// Occupancy maps in the ROS map_server convention: an 8-bit PGM image (row 0 is the top, i.e.
// the largest y) and a YAML file naming it with the resolution and the origin of the
// lower-left pixel.
#include <cstdint>
#include <string>
#include <vector>

#include "kestrel/core/status.hpp"

namespace kestrel::output {

struct GridImage {
  int width = 0;
  int height = 0;
  double resolution_m = 0.05;              // metres per pixel
  double origin_x_m = 0, origin_y_m = 0;   // world position of the lower-left pixel's corner
  // Row-major from the bottom row (y = origin) upwards, as a map is naturally filled;
  // 0 = occupied (black), 254 = free (white), 205 = unknown, per map_server's trinary mode.
  std::vector<uint8_t> cells;
};

inline constexpr uint8_t kPgmOccupied = 0;
inline constexpr uint8_t kPgmFree = 254;
inline constexpr uint8_t kPgmUnknown = 205;

// Writes <stem>.pgm and <stem>.yaml; the YAML refers to the PGM by its file name.
Status write_map(const std::string& stem, const GridImage& map);

}  // namespace kestrel::output
