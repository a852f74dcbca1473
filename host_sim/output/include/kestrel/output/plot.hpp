#pragma once
// Line plots of time series (estimated vs true position and velocity, coverage vs time):
// stacked panels sharing the x axis, each with its own y range, ticks, labels and legend.
#include <string>
#include <vector>

#include "kestrel/output/canvas.hpp"

namespace kestrel::output {

struct Series {
  std::string label;
  Rgb color;
  std::vector<double> x;
  std::vector<double> y;
};

struct Panel {
  std::string title;
  std::string y_label;
  std::vector<Series> series;
};

// Draws the panels stacked vertically on one canvas; x_label names the shared axis.
Canvas plot_panels(const std::vector<Panel>& panels, const std::string& x_label, int width = 1000,
                   int panel_height = 260);

}  // namespace kestrel::output
