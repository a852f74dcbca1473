#include "kestrel/output/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "font5x7.hpp"

namespace kestrel::output {

Canvas::Canvas(int width, int height, Rgb background)
    : width_(std::max(1, width)),
      height_(std::max(1, height)),
      pixels_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), background) {}

void Canvas::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  pixels_[static_cast<std::size_t>(y) * width_ + x] = c;
}

void Canvas::blend(int x, int y, Rgb c, float alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  Rgb& p = pixels_[static_cast<std::size_t>(y) * width_ + x];
  auto mix = [alpha](uint8_t a, uint8_t b) {
    return static_cast<uint8_t>(std::lround(static_cast<float>(a) * (1 - alpha) + static_cast<float>(b) * alpha));
  };
  p = {mix(p.r, c.r), mix(p.g, c.g), mix(p.b, c.b)};
}

void Canvas::line(int x0, int y0, int x1, int y1, Rgb c, int thickness) {
  // Bresenham, with a square brush for thickness; clipping happens per pixel.
  const int r = std::max(0, (thickness - 1) / 2);
  const int extra = (thickness > 1 && thickness % 2 == 0) ? 1 : 0;
  int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
  int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  // Guard against absurd coordinates (a NaN pose mapped to pixels): give up rather than loop.
  if (dx > 100000 || -dy > 100000) return;
  for (;;) {
    for (int oy = -r; oy <= r + extra; ++oy)
      for (int ox = -r; ox <= r + extra; ++ox) set(x0 + ox, y0 + oy, c);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

void Canvas::rect(int x0, int y0, int x1, int y1, Rgb c, bool filled) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  if (filled) {
    for (int y = std::max(0, y0); y <= std::min(height_ - 1, y1); ++y)
      for (int x = std::max(0, x0); x <= std::min(width_ - 1, x1); ++x) set(x, y, c);
  } else {
    line(x0, y0, x1, y0, c);
    line(x1, y0, x1, y1, c);
    line(x1, y1, x0, y1, c);
    line(x0, y1, x0, y0, c);
  }
}

void Canvas::circle(int cx, int cy, int radius, Rgb c, bool filled) {
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) {
      const int d2 = x * x + y * y;
      if (filled ? d2 <= radius * radius : (d2 <= radius * radius && d2 > (radius - 1) * (radius - 1)))
        set(cx + x, cy + y, c);
    }
}

int Canvas::text(int x, int y, const std::string& s, Rgb c, int scale) {
  int pen = x;
  for (char ch : s) {
    const uint8_t* rows = glyph5x7(ch);
    for (int ry = 0; ry < 7; ++ry)
      for (int rx = 0; rx < 5; ++rx)
        if (rows[ry] & (0x10 >> rx))
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) set(pen + rx * scale + sx, y + ry * scale + sy, c);
    pen += 6 * scale;
  }
  return pen - x;
}

int Canvas::text_width(const std::string& s, int scale) { return static_cast<int>(s.size()) * 6 * scale; }

void Canvas::set_world_view(double origin_x_m, double origin_y_m, double pixels_per_m) {
  origin_x_ = origin_x_m;
  origin_y_ = origin_y_m;
  ppm_ = pixels_per_m > 0 ? pixels_per_m : 1;
}

int Canvas::wx(double x_m) const {
  const double v = std::round((x_m - origin_x_) * ppm_);
  return std::isfinite(v) ? static_cast<int>(std::clamp(v, -1e6, 1e6)) : -1000000;
}
int Canvas::wy(double y_m) const {
  const double v = std::round(static_cast<double>(height_ - 1) - (y_m - origin_y_) * ppm_);
  return std::isfinite(v) ? static_cast<int>(std::clamp(v, -1e6, 1e6)) : -1000000;
}

void Canvas::world_line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
  line(wx(x0), wy(y0), wx(x1), wy(y1), c, thickness);
}

void Canvas::world_circle(double x, double y, int radius_px, Rgb c, bool filled) {
  circle(wx(x), wy(y), radius_px, c, filled);
}

void Canvas::scale_bar(int x, int y, double length_m, Rgb c) {
  const int len = static_cast<int>(std::lround(length_m * ppm_));
  line(x, y, x + len, y, c, 2);
  line(x, y - 4, x, y + 4, c, 2);
  line(x + len, y - 4, x + len, y + 4, c, 2);
  char label[32];
  std::snprintf(label, sizeof(label), "%g M", length_m);
  text(x + len / 2 - text_width(label) / 2, y - 14, label, c);
}

}  // namespace kestrel::output
