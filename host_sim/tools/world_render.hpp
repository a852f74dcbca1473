#pragma once
// render.png of a simulated run: the world seen from above (walls black, glass cyan, railings
// purple dashes, obstacles filled with a colour for their top height, hanging ones hatched),
// the reachable free area (white) and the part the laser saw (pale blue), room names, the
// true path with start and end markers, the last scan, any collision, a scale bar, axes and
// a legend.
#include "kestrel/sim/mission.hpp"
#include <string>

#include "kestrel/output/canvas.hpp"
#include "kestrel/sim/flight_recorder.hpp"
#include "kestrel/sim/world.hpp"

namespace kestrel::sim::tools {

struct RenderInfo {
  std::string title;     // first line above the map
  std::string subtitle;  // second line
};

// `mission` (optional) adds its own layer and legend rows.
output::Canvas render_run(const World& world, const FlightRecorder& rec, const std::vector<Contact>& contacts,
                          const RenderInfo& info, const Mission* mission = nullptr);

}  // namespace kestrel::sim::tools
