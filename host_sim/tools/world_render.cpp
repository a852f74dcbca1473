#include "world_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kestrel::sim::tools {
namespace {

using output::Canvas;
using output::Rgb;

constexpr int kTop = 70;       // title band
constexpr int kBottom = 60;    // scale bar band
constexpr int kLeft = 30;
constexpr int kLegendW = 330;

// Obstacle colour by top height: pale yellow (low) through orange to dark red (>= 2.2 m).
Rgb height_colour(double z) {
  const double t = std::clamp(z / 2.2, 0.0, 1.0);
  const Rgb lo{250, 225, 120}, mid{240, 140, 40}, hi{150, 30, 30};
  auto mix = [](Rgb a, Rgb b, double f) {
    return Rgb{static_cast<uint8_t>(a.r + (b.r - a.r) * f), static_cast<uint8_t>(a.g + (b.g - a.g) * f),
               static_cast<uint8_t>(a.b + (b.b - a.b) * f)};
  };
  return t < 0.5 ? mix(lo, mid, t * 2) : mix(mid, hi, (t - 0.5) * 2);
}

struct View {
  double ox, oy, ppm;
  int map_h;  // pixel rows of the map area, whose bottom is at canvas row kTop + map_h
  double wx(int px) const { return ox + (px + 0.5) / ppm; }
};

void fill_polygon(Canvas& c, const std::vector<Eigen::Vector2d>& poly, Rgb col, bool hatch) {
  int x0 = c.width(), x1 = -1, y0 = c.height(), y1 = -1;
  for (const auto& p : poly) {
    x0 = std::min(x0, c.wx(p.x()));
    x1 = std::max(x1, c.wx(p.x()));
    y0 = std::min(y0, c.wy(p.y()));
    y1 = std::max(y1, c.wy(p.y()));
  }
  const double ppm = c.pixels_per_m();
  // Invert the canvas mapping through two reference points.
  const double ox = -c.wx(0.0) / ppm;
  const double oy_row = c.wy(0.0);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d w(ox + x / ppm, (oy_row - y) / ppm);
      if (!point_in_polygon(poly, w)) continue;
      if (hatch && ((x + y) / 4) % 2 == 0) {
        c.set(x, y, Rgb{255, 255, 255});
      } else {
        c.set(x, y, col);
      }
    }
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& a = poly[i];
    const auto& b = poly[(i + 1) % poly.size()];
    c.world_line(a.x(), a.y(), b.x(), b.y(), Rgb{90, 60, 30}, 1);
  }
}

void dashed(Canvas& c, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb col, int thick, double dash_m) {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(len / dash_m));
  for (int k = 0; k < n; k += 2) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(k) / n);
    const Eigen::Vector2d q = a + (b - a) * (std::min(1.0, static_cast<double>(k + 1) / n));
    c.world_line(p.x(), p.y(), q.x(), q.y(), col, thick);
  }
}

void legend_swatch_line(Canvas& c, int x, int y, Rgb col, int thick, bool dash) {
  if (dash) {
    for (int k = 0; k < 30; k += 10) c.line(x + k, y + 7, x + k + 5, y + 7, col, thick);
  } else {
    c.line(x, y + 7, x + 30, y + 7, col, thick);
  }
}

}  // namespace

Canvas render_run(const World& world, const FlightRecorder& rec, const std::vector<Contact>& contacts,
                  const RenderInfo& info, const Mission* mission) {
  const Bounds2 b = world.bounds();
  const double wm = std::max(1.0, b.max.x() - b.min.x()), hm = std::max(1.0, b.max.y() - b.min.y());
  const double ppm = std::clamp(std::min(1200.0 / wm, 800.0 / hm), 8.0, 120.0);
  const int map_w = static_cast<int>(std::ceil(wm * ppm)) + 2;
  const int map_h = static_cast<int>(std::ceil(hm * ppm)) + 2;
  const int width = kLeft + map_w + 30 + kLegendW;
  const int height = std::max(kTop + map_h + kBottom, kTop + 560);
  Canvas c(width, height, Rgb{205, 205, 205});
  // World origin so that b.min sits at (kLeft, bottom of the map area).
  const double bottom_rows = height - (kTop + map_h);  // rows below the map
  c.set_world_view(b.min.x() - kLeft / ppm, b.min.y() - (bottom_rows - 1) / ppm, ppm);

  // Free space: reachable white, seen by the laser pale blue, the rest stays grey.
  const FreeSpaceMap& fs = rec.free_space();
  const double res = fs.resolution_m();
  for (int iy = 0; iy < fs.height(); ++iy)
    for (int ix = 0; ix < fs.width(); ++ix) {
      if (!fs.reachable(ix, iy)) continue;
      const Rgb col = rec.seen(ix, iy) ? Rgb{205, 228, 250} : Rgb{255, 255, 255};
      const double x0 = fs.origin().x() + ix * res, y0 = fs.origin().y() + iy * res;
      c.rect(c.wx(x0), c.wy(y0 + res), c.wx(x0 + res), c.wy(y0), col, true);
    }
  // Obstacles, coloured by top height; hanging ones (not standing on the floor) hatched.
  for (const Obstacle& o : world.obstacles) {
    if (o.material == Material::kGlass) continue;
    fill_polygon(c, o.polygon, height_colour(o.z_max), o.z_min > 0.05);
  }
  // Walls.
  const int wall_px = std::max(2, static_cast<int>(std::lround(world.wall_thickness_m * ppm)));
  for (const Wall& w : world.walls) {
    switch (w.material) {
      case Material::kOpaque:
        c.world_line(w.a.x(), w.a.y(), w.b.x(), w.b.y(),
                     (w.z_max < 1.5 || w.z_min > 0.05) ? height_colour(w.z_max) : output::colors::kBlack, wall_px);
        break;
      case Material::kGlass:
        c.world_line(w.a.x(), w.a.y(), w.b.x(), w.b.y(), Rgb{0, 190, 220}, wall_px + 1);
        break;
      case Material::kRailing:
        dashed(c, w.a, w.b, Rgb{150, 50, 190}, wall_px, 0.25);
        break;
    }
  }
  // Room names.
  for (const Room& r : world.rooms) {
    Eigen::Vector2d ctr = Eigen::Vector2d::Zero();
    for (const auto& p : r.polygon) ctr += p;
    ctr /= static_cast<double>(r.polygon.size());
    const int tw = Canvas::text_width(r.name, 2);
    c.text(c.wx(ctr.x()) - tw / 2, c.wy(ctr.y()) - 7, r.name, Rgb{150, 150, 170}, 2);
  }
  // The last scan's returns, from the true pose it was taken at.
  if (rec.has_scan()) {
    const LaserScan& s = rec.last_scan();
    const VehicleState& t = rec.last_scan_truth();
    for (std::size_t i = 0; i < s.beam_count; ++i) {
      if (!LaserScan::is_return(s.range_mm[i])) continue;
      const double a = t.yaw_rad + s.angle_of(i), r = s.range_mm[i] * 1e-3;
      const int px = c.wx(t.position_m.x() + r * std::cos(a)), py = c.wy(t.position_m.y() + r * std::sin(a));
      c.rect(px - 1, py - 1, px + 1, py + 1, Rgb{230, 60, 140}, true);
    }
  }
  // The true path.
  const auto& path = rec.path();
  for (std::size_t i = 1; i < path.size(); ++i)
    c.world_line(path[i - 1].x, path[i - 1].y, path[i].x, path[i].y, Rgb{30, 80, 220}, 3);
  if (mission != nullptr) mission->draw(c);
  // Start and end markers.
  c.world_circle(world.start.x, world.start.y, 9, Rgb{20, 150, 50}, true);
  c.world_line(world.start.x, world.start.y, world.start.x + 0.9 * std::cos(world.start.yaw_rad),
               world.start.y + 0.9 * std::sin(world.start.yaw_rad), Rgb{20, 150, 50}, 3);
  c.text(c.wx(world.start.x) - 30, c.wy(world.start.y) + 14, "START", Rgb{20, 120, 40}, 2);
  if (!path.empty()) {
    const auto& e = path.back();
    const int ex = c.wx(e.x), ey = c.wy(e.y);
    c.circle(ex, ey, 9, Rgb{200, 30, 30}, false);
    c.circle(ex, ey, 8, Rgb{200, 30, 30}, false);
    c.world_line(e.x, e.y, e.x + 0.9 * std::cos(e.yaw), e.y + 0.9 * std::sin(e.yaw), Rgb{200, 30, 30}, 3);
    c.text(ex + 12, ey - 20, "END", Rgb{180, 20, 20}, 2);
  }
  for (const Contact& k : contacts) {
    const int x = c.wx(k.position_m.x()), y = c.wy(k.position_m.y());
    c.line(x - 12, y - 12, x + 12, y + 12, Rgb{230, 0, 0}, 4);
    c.line(x - 12, y + 12, x + 12, y - 12, Rgb{230, 0, 0}, 4);
    char buf[64];
    std::snprintf(buf, sizeof(buf), "COLLISION T=%.2fS", k.stamp.seconds());
    c.text(x + 16, y + 6, buf, Rgb{230, 0, 0}, 2);
  }

  // Title.
  c.rect(0, 0, width - 1, kTop - 8, Rgb{245, 245, 245}, true);
  c.text(12, 10, info.title, output::colors::kBlack, 3);
  c.text(12, 42, info.subtitle, Rgb{70, 70, 70}, 2);
  // Scale bar and axes under the map.
  const double bar = ppm * 5 > 60 ? 5.0 : 10.0;
  c.rect(kLeft - 6, height - 44, kLeft + static_cast<int>(bar * ppm) + 70, height - 4, Rgb{245, 245, 245}, true);
  c.scale_bar(kLeft + 4, height - 12, bar, output::colors::kBlack);
  const int ax = kLeft + static_cast<int>(bar * ppm) + 30, ay = height - 10;
  c.line(ax, ay, ax + 28, ay, output::colors::kBlack, 2);
  c.line(ax, ay, ax, ay - 28, output::colors::kBlack, 2);
  c.text(ax + 31, ay - 4, "X", output::colors::kBlack, 1);
  c.text(ax - 2, ay - 38, "Y", output::colors::kBlack, 1);

  // Legend.
  const int lx = kLeft + map_w + 30;
  int ly = kTop + 10;
  c.rect(lx - 10, kTop, width - 1, height - 1, Rgb{245, 245, 245}, true);
  c.text(lx, ly, "LEGEND", output::colors::kBlack, 2);
  ly += 30;
  auto item = [&](const char* label, auto&& draw) {
    draw(lx, ly);
    c.text(lx + 42, ly + 1, label, output::colors::kBlack, 2);
    ly += 26;
  };
  item("WALL", [&](int x, int y) { legend_swatch_line(c, x, y, output::colors::kBlack, 4, false); });
  item("GLASS (NO RETURN)", [&](int x, int y) { legend_swatch_line(c, x, y, Rgb{0, 190, 220}, 4, false); });
  item("RAILING (SOME RETURN)", [&](int x, int y) { legend_swatch_line(c, x, y, Rgb{150, 50, 190}, 4, true); });
  item("TRUE PATH", [&](int x, int y) { legend_swatch_line(c, x, y, Rgb{30, 80, 220}, 3, false); });
  if (mission != nullptr)
    for (const Mission::LegendRow& row : mission->legend())
      item(row.label, [&](int x, int y) { legend_swatch_line(c, x, y, row.color, 3, false); });
  item("START", [&](int x, int y) { c.circle(x + 15, y + 7, 7, Rgb{20, 150, 50}, true); });
  item("END", [&](int x, int y) { c.circle(x + 15, y + 7, 7, Rgb{200, 30, 30}, false); });
  item("LAST LASER SCAN", [&](int x, int y) {
    for (int k = 0; k < 5; ++k) c.rect(x + 3 + 6 * k, y + 6, x + 5 + 6 * k, y + 8, Rgb{230, 60, 140}, true);
  });
  item("SEEN BY THE LASER", [&](int x, int y) { c.rect(x, y, x + 30, y + 14, Rgb{205, 228, 250}, true); });
  item("FREE, NOT SEEN", [&](int x, int y) {
    c.rect(x, y, x + 30, y + 14, output::colors::kWhite, true);
    c.rect(x, y, x + 30, y + 14, output::colors::kGrey, false);
  });
  item("UNREACHABLE", [&](int x, int y) { c.rect(x, y, x + 30, y + 14, Rgb{205, 205, 205}, true); });
  item("COLLISION", [&](int x, int y) {
    c.line(x + 8, y, x + 22, y + 14, Rgb{230, 0, 0}, 3);
    c.line(x + 8, y + 14, x + 22, y, Rgb{230, 0, 0}, 3);
  });
  ly += 10;
  c.text(lx, ly, "OBSTACLE TOP HEIGHT", output::colors::kBlack, 2);
  ly += 24;
  for (int k = 0; k <= 240; ++k) c.line(lx + k, ly, lx + k, ly + 16, height_colour(2.2 * k / 240.0), 1);
  c.text(lx, ly + 22, "0", output::colors::kBlack, 2);
  c.text(lx + 100, ly + 22, "1 M", output::colors::kBlack, 2);
  c.text(lx + 206, ly + 22, "2.2+", output::colors::kBlack, 2);
  ly += 50;
  c.rect(lx, ly, lx + 30, ly + 14, height_colour(1.8), true);
  for (int y = ly; y <= ly + 14; ++y)
    for (int x = lx; x <= lx + 30; ++x)
      if (((x + y) / 4) % 2 == 0) c.set(x, y, output::colors::kWhite);
  c.text(lx + 42, ly + 1, "HANGING (OFF FLOOR)", output::colors::kBlack, 2);
  return c;
}

}  // namespace kestrel::sim::tools
