#include "kestrel/output/pgm_map.hpp"

#include <cstdio>

namespace kestrel::output {

Status write_map(const std::string& stem, const GridImage& map) {
  if (map.width <= 0 || map.height <= 0 || map.cells.size() != static_cast<std::size_t>(map.width) * map.height ||
      !(map.resolution_m > 0))
    return Status::kInvalidArgument;
  const std::string pgm = stem + ".pgm";
  FILE* f = std::fopen(pgm.c_str(), "wb");
  if (f == nullptr) return Status::kIoError;
  std::fprintf(f, "P5\n# kestrel occupancy map\n%d %d\n255\n", map.width, map.height);
  bool ok = true;
  for (int row = map.height - 1; row >= 0 && ok; --row)
    ok = std::fwrite(map.cells.data() + static_cast<std::size_t>(row) * map.width, 1,
                     static_cast<std::size_t>(map.width), f) == static_cast<std::size_t>(map.width);
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) return Status::kIoError;

  const std::size_t slash = pgm.find_last_of('/');
  const std::string base = slash == std::string::npos ? pgm : pgm.substr(slash + 1);
  FILE* y = std::fopen((stem + ".yaml").c_str(), "w");
  if (y == nullptr) return Status::kIoError;
  std::fprintf(y,
               "image: %s\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
               "free_thresh: 0.196\nmode: trinary\n",
               base.c_str(), map.resolution_m, map.origin_x_m, map.origin_y_m);
  return std::fclose(y) == 0 ? Status::kOk : Status::kIoError;
}

}  // namespace kestrel::output
