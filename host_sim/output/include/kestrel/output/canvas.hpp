#pragma once
// An RGB raster to draw run pictures on (render.png, plots), with a world-to-pixel mapping so
// callers draw in metres. Host-side output code: it allocates its pixels once, at creation.
#include <cstdint>
#include <string>
#include <vector>

namespace kestrel::output {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb, Rgb) = default;
};

namespace colors {
inline constexpr Rgb kWhite{255, 255, 255};
inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kGrey{128, 128, 128};
inline constexpr Rgb kLightGrey{215, 215, 215};
inline constexpr Rgb kRed{215, 40, 40};
inline constexpr Rgb kGreen{30, 160, 60};
inline constexpr Rgb kBlue{40, 90, 220};
inline constexpr Rgb kOrange{240, 140, 20};
inline constexpr Rgb kPurple{140, 60, 180};
inline constexpr Rgb kCyan{20, 170, 190};
}  // namespace colors

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = colors::kWhite);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const std::vector<Rgb>& pixels() const { return pixels_; }

  // Pixel coordinates: x right, y down. Out-of-canvas drawing is clipped, never an error.
  void set(int x, int y, Rgb c);
  void blend(int x, int y, Rgb c, float alpha);
  void line(int x0, int y0, int x1, int y1, Rgb c, int thickness = 1);
  void rect(int x0, int y0, int x1, int y1, Rgb c, bool filled);
  void circle(int cx, int cy, int radius, Rgb c, bool filled);
  // 5x7 bitmap text scaled by `scale`; returns the width drawn in pixels.
  int text(int x, int y, const std::string& s, Rgb c, int scale = 1);
  static int text_width(const std::string& s, int scale = 1);

  // World mapping: metres to pixels with y up. `scale` is pixels per metre.
  void set_world_view(double origin_x_m, double origin_y_m, double pixels_per_m);
  int wx(double x_m) const;
  int wy(double y_m) const;
  double pixels_per_m() const { return ppm_; }
  void world_line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void world_circle(double x, double y, int radius_px, Rgb c, bool filled);
  // A scale bar of `length_m` with its label, at pixel (x, y).
  void scale_bar(int x, int y, double length_m, Rgb c);

 private:
  int width_;
  int height_;
  std::vector<Rgb> pixels_;
  double origin_x_ = 0, origin_y_ = 0, ppm_ = 1;
};

}  // namespace kestrel::output
