#include "kestrel/output/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace kestrel::output {
namespace {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `target` ticks.
double nice_step(double span, int target) {
  if (!(span > 0)) return 1;
  const double raw = span / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

std::string format_tick(double v, double step) {
  char buf[32];
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, std::fabs(v) < step * 1e-9 ? 0.0 : v);
  return buf;
}

}  // namespace

Canvas plot_panels(const std::vector<Panel>& panels, const std::string& x_label, int width, int panel_height) {
  const int n = std::max<int>(1, static_cast<int>(panels.size()));
  const int left = 80, right = 20, top = 12, bottom = 40;
  Canvas c(width, top + n * panel_height + bottom);

  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  for (const Panel& p : panels)
    for (const Series& s : p.series)
      for (double v : s.x)
        if (std::isfinite(v)) {
          x_min = std::min(x_min, v);
          x_max = std::max(x_max, v);
        }
  if (!(x_max > x_min)) {
    x_min = 0;
    x_max = 1;
  }
  const int plot_w = width - left - right;
  auto px = [&](double x) { return left + static_cast<int>(std::lround((x - x_min) / (x_max - x_min) * plot_w)); };
  const double xstep = nice_step(x_max - x_min, 8);

  for (int i = 0; i < static_cast<int>(panels.size()); ++i) {
    const Panel& p = panels[static_cast<std::size_t>(i)];
    const int y0 = top + i * panel_height + 18, y1 = top + (i + 1) * panel_height - 22;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Series& s : p.series)
      for (double v : s.y)
        if (std::isfinite(v)) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
    if (!(hi > lo)) {
      lo = std::isfinite(lo) ? lo - 1 : -1;
      hi = lo + 2;
    }
    const double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
    auto py = [&](double y) { return y1 - static_cast<int>(std::lround((y - lo) / (hi - lo) * (y1 - y0))); };

    const double ystep = nice_step(hi - lo, 5);
    for (double t = std::ceil(lo / ystep) * ystep; t <= hi; t += ystep) {
      c.line(left, py(t), width - right, py(t), colors::kLightGrey);
      const std::string lab = format_tick(t, ystep);
      c.text(left - 6 - Canvas::text_width(lab), py(t) - 3, lab, colors::kBlack);
    }
    for (double t = std::ceil(x_min / xstep) * xstep; t <= x_max; t += xstep) {
      c.line(px(t), y0, px(t), y1, colors::kLightGrey);
      if (i + 1 == static_cast<int>(panels.size())) {
        const std::string lab = format_tick(t, xstep);
        c.text(px(t) - Canvas::text_width(lab) / 2, y1 + 6, lab, colors::kBlack);
      }
    }
    c.rect(left, y0, width - right, y1, colors::kBlack, false);
    c.text(left, y0 - 14, p.title + (p.y_label.empty() ? "" : "  [" + p.y_label + "]"), colors::kBlack);

    int legend_x = width - right - 8;
    for (auto it = p.series.rbegin(); it != p.series.rend(); ++it) {
      legend_x -= Canvas::text_width(it->label) + 26;
      c.line(legend_x, y0 - 11, legend_x + 14, y0 - 11, it->color, 3);
      c.text(legend_x + 18, y0 - 14, it->label, colors::kBlack);
    }
    for (const Series& s : p.series) {
      bool have_prev = false;
      int prev_x = 0, prev_y = 0;
      for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
        if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) {
          have_prev = false;
          continue;
        }
        const int xx = px(s.x[k]), yy = std::clamp(py(s.y[k]), y0, y1);
        if (have_prev) c.line(prev_x, prev_y, xx, yy, s.color, 2);
        prev_x = xx;
        prev_y = yy;
        have_prev = true;
      }
    }
  }
  c.text(left + plot_w / 2 - Canvas::text_width(x_label) / 2, c.height() - 16, x_label, colors::kBlack);
  return c;
}

}  // namespace kestrel::output
