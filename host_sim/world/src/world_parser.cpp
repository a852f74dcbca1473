#include "kestrel/sim/world_parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace kestrel::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// An indoor world lies well within +-this many metres of its origin in x and y (the built-in
// ones are a few tens of metres across; tests lay walls 200 m long to face the laser with a
// plane). The simulator's grids over the world (free space and the flight recorder's seen
// cells at 0.1 m, the ray caster's segment grid) grow with the area of its bounding box: a
// mistyped coordinate such as 1e12 would overflow their sizes. A world filling the whole
// square would take 10^8 cells at 0.1 m: slow to build and large, but no overflow.
constexpr double kMaxCoordinateM = 500;
constexpr double kMaxWallThicknessM = 10;
// A yaw is written in degrees within one turn either way. Beyond that it is a typo, and a huge
// one (1e308) overflows to inf in radians: its sine and cosine are NaN, and NaN corners passed
// every later check, so the simulator hung on the world.
constexpr double kMaxYawDeg = 360;

// Written as !(within) so that a NaN coordinate counts as outside.
bool outside_extent(const Eigen::Vector2d& p) {
  return !(std::fabs(p.x()) <= kMaxCoordinateM && std::fabs(p.y()) <= kMaxCoordinateM);
}

bool yaw_out_of_range(double deg) {
  return !(std::fabs(deg) <= kMaxYawDeg);
}

// `what` is the yaw as written (yaw=1e308, or start's YAW_DEG).
std::string yaw_error(const std::string& what) {
  return what + " lies outside +-360 deg";
}

std::string extent_error(const std::string& what, const Eigen::Vector2d& p) {
  std::ostringstream ss;
  ss << what << ": point (" << p.x() << ", " << p.y() << ") lies outside +-" << kMaxCoordinateM
     << " m (an indoor world's extent)";
  return ss.str();
}

struct Options {
  bool has_z = false;
  double z_min = 0, z_max = 0;
  Material material = Material::kOpaque;
  double return_probability = 1;
  bool has_yaw = false;
  double yaw_deg = 0;
};

bool parse_number(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

bool is_option(const std::string& t) {
  return t == "glass" || t == "opaque" || t.find('=') != std::string::npos;
}

// Parses trailing OPTIONS; returns an empty string or the reason.
std::string parse_options(const std::vector<std::string>& toks, std::size_t first, Options& o,
                          bool allow_yaw) {
  for (std::size_t i = first; i < toks.size(); ++i) {
    const std::string& t = toks[i];
    if (t == "glass") {
      o.material = Material::kGlass;
      o.return_probability = 0;
    } else if (t == "opaque") {
      o.material = Material::kOpaque;
      o.return_probability = 1;
    } else if (t.rfind("railing=", 0) == 0) {
      double p = 0;
      if (!parse_number(t.substr(8), p) || p < 0 || p > 1)
        return "railing=P needs a probability between 0 and 1, got '" + t.substr(8) + "'";
      o.material = Material::kRailing;
      o.return_probability = p;
    } else if (t.rfind("z=", 0) == 0) {
      const std::string v = t.substr(2);
      const auto colon = v.find(':');
      if (colon == std::string::npos || !parse_number(v.substr(0, colon), o.z_min) ||
          !parse_number(v.substr(colon + 1), o.z_max))
        return "z=ZMIN:ZMAX expected, got '" + t + "'";
      if (o.z_max <= o.z_min) return "z range '" + t + "' is empty (ZMAX must exceed ZMIN)";
      o.has_z = true;
    } else if (allow_yaw && t.rfind("yaw=", 0) == 0) {
      if (!parse_number(t.substr(4), o.yaw_deg)) return "yaw=DEG expected, got '" + t + "'";
      if (yaw_out_of_range(o.yaw_deg)) return yaw_error(t);
      o.has_yaw = true;
    } else {
      return "unknown option '" + t + "'";
    }
  }
  return {};
}

// Reads numbers from toks[first..] until the first option; returns how many were read or
// -1 (with `bad` set) when a token is neither a number nor an option.
int read_numbers(const std::vector<std::string>& toks, std::size_t first, std::vector<double>& out,
                 std::string& bad) {
  out.clear();
  for (std::size_t i = first; i < toks.size(); ++i) {
    if (is_option(toks[i])) break;
    double v = 0;
    if (!parse_number(toks[i], v)) {
      bad = toks[i];
      return -1;
    }
    out.push_back(v);
  }
  return static_cast<int>(out.size());
}

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Makes the polygon counter-clockwise; returns false if it is not strictly convex.
bool make_convex_ccw(std::vector<Eigen::Vector2d>& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  int sign = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double c = cross(poly[i], poly[(i + 1) % n], poly[(i + 2) % n]);
    if (!(std::fabs(c) >= 1e-12)) return false;  // NaN-safe: a NaN corner is not convex
    const int s = c > 0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign) return false;
  }
  // Also reject self-intersecting "stars" whose turns agree: total turning must be 2*pi.
  if (!(std::fabs(polygon_signed_area(poly)) >= 1e-12)) return false;
  double turning = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d e1 = poly[(i + 1) % n] - poly[i];
    const Eigen::Vector2d e2 = poly[(i + 2) % n] - poly[(i + 1) % n];
    turning += std::atan2(e1.x() * e2.y() - e1.y() * e2.x(), e1.dot(e2));
  }
  if (!(std::fabs(std::fabs(turning) - 2 * kPi) <= 1e-6)) return false;
  if (sign < 0) std::reverse(poly.begin(), poly.end());
  return true;
}

}  // namespace

WorldParseResult parse_world(std::string_view text, std::string_view source_name) {
  WorldParseResult r;
  World& w = r.world;
  double wall_height = 2.5;
  bool have_start = false;
  int line_no = 0;
  std::size_t pos = 0;
  std::vector<double> nums;
  auto fail = [&](const std::string& why) {
    r.ok = false;
    r.error = std::string(source_name) + ":" + std::to_string(line_no) + ": " + why;
    return r;
  };
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view raw = text.substr(pos, nl == std::string_view::npos ? text.size() - pos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    const auto hash = raw.find('#');
    if (hash != std::string_view::npos) raw = raw.substr(0, hash);
    std::istringstream ls{std::string(raw)};
    std::vector<std::string> toks;
    for (std::string t; ls >> t;) toks.push_back(t);
    if (toks.empty()) continue;
    const std::string& kw = toks[0];
    std::string bad;
    Options opt;
    if (kw == "name") {
      if (toks.size() != 2) return fail("name needs exactly one word");
      w.name = toks[1];
    } else if (kw == "start") {
      if (read_numbers(toks, 1, nums, bad) != 4 || toks.size() != 5)
        return fail("start needs 4 numbers: X Y Z YAW_DEG");
      if (!(nums[2] >= 0)) return fail("start height Z must not be below the floor");
      if (!(nums[2] <= kMaxCoordinateM))
        return fail("start height Z must be at most " + std::to_string(static_cast<int>(kMaxCoordinateM)) + " m");
      if (outside_extent({nums[0], nums[1]})) return fail(extent_error("start", {nums[0], nums[1]}));
      if (yaw_out_of_range(nums[3])) return fail(yaw_error("start: YAW_DEG " + toks[4]));
      w.start = {nums[0], nums[1], nums[2], nums[3] * kPi / 180.0};
      have_start = true;
    } else if (kw == "wall_height" || kw == "wall_thickness" || kw == "ceiling") {
      if (read_numbers(toks, 1, nums, bad) != 1 || toks.size() != 2)
        return fail(kw + " needs one number");
      if (!(nums[0] >= 0) || (kw != "ceiling" && nums[0] == 0)) return fail(kw + " must be positive");
      if (kw == "wall_thickness" && nums[0] > kMaxWallThicknessM)
        return fail(kw + " must be at most " + std::to_string(static_cast<int>(kMaxWallThicknessM)) +
                    " m (use a box for a thick obstacle)");
      if (kw == "wall_height") wall_height = nums[0];
      if (kw == "wall_thickness") w.wall_thickness_m = nums[0];
      if (kw == "ceiling") w.ceiling_m = nums[0];
    } else if (kw == "wall") {
      const int n = read_numbers(toks, 1, nums, bad);
      if (n < 0) return fail("wall: '" + bad + "' is not a number");
      if (n != 4) return fail("wall needs 4 numbers X1 Y1 X2 Y2, got " + std::to_string(n));
      const std::string e = parse_options(toks, 5, opt, false);
      if (!e.empty()) return fail(e);
      Wall wall;
      wall.a = {nums[0], nums[1]};
      wall.b = {nums[2], nums[3]};
      if ((wall.a - wall.b).norm() < 1e-6) return fail("wall has zero length");
      for (const Eigen::Vector2d& p : {wall.a, wall.b})
        if (outside_extent(p)) return fail(extent_error("wall", p));
      wall.z_min = opt.has_z ? opt.z_min : 0;
      wall.z_max = opt.has_z ? opt.z_max : wall_height;
      wall.material = opt.material;
      wall.return_probability = opt.return_probability;
      wall.line = line_no;
      w.walls.push_back(wall);
    } else if (kw == "box" || kw == "pillar" || kw == "poly") {
      const int n = read_numbers(toks, 1, nums, bad);
      if (n < 0) return fail(kw + ": '" + bad + "' is not a number");
      const std::string e = parse_options(toks, 1 + static_cast<std::size_t>(n), opt, kw == "box");
      if (!e.empty()) return fail(e);
      Obstacle o;
      if (kw == "box") {
        if (n != 4) return fail("box needs 4 numbers CX CY SIZE_X SIZE_Y, got " + std::to_string(n));
        if (!(nums[2] > 0 && nums[3] > 0)) return fail("box sizes must be positive");
        const double c = std::cos(opt.yaw_deg * kPi / 180.0), s = std::sin(opt.yaw_deg * kPi / 180.0);
        const double hx = nums[2] / 2, hy = nums[3] / 2;
        const double corners[4][2] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
        for (const auto& k : corners)
          o.polygon.emplace_back(nums[0] + c * k[0] - s * k[1], nums[1] + s * k[0] + c * k[1]);
      } else if (kw == "pillar") {
        if (n != 3) return fail("pillar needs 3 numbers CX CY RADIUS, got " + std::to_string(n));
        if (!(nums[2] > 0)) return fail("pillar radius must be positive");
        for (int k = 0; k < 16; ++k) {
          const double a = 2 * kPi * k / 16;
          o.polygon.emplace_back(nums[0] + nums[2] * std::cos(a), nums[1] + nums[2] * std::sin(a));
        }
      } else {
        if (n < 6 || n % 2 != 0)
          return fail("poly needs at least 3 points (an even count of numbers), got " +
                      std::to_string(n) + " numbers");
        for (int k = 0; k < n; k += 2) o.polygon.emplace_back(nums[k], nums[k + 1]);
      }
      for (const Eigen::Vector2d& p : o.polygon)
        if (outside_extent(p)) return fail(extent_error(kw, p));
      if (!make_convex_ccw(o.polygon)) return fail(kw + " is not a convex polygon");
      o.z_min = opt.has_z ? opt.z_min : 0;
      o.z_max = opt.has_z ? opt.z_max : wall_height;
      o.material = opt.material;
      o.return_probability = opt.return_probability;
      o.line = line_no;
      w.obstacles.push_back(std::move(o));
    } else if (kw == "room") {
      if (toks.size() < 2) return fail("room needs a NAME and at least 3 points");
      const int n = read_numbers(toks, 2, nums, bad);
      if (n < 0) return fail("room: '" + bad + "' is not a number");
      if (n < 6 || n % 2 != 0 || static_cast<std::size_t>(n) + 2 != toks.size())
        return fail("room needs a NAME and at least 3 points X Y");
      // Metrics name rooms (metrics.json's room_entry_s): two of one name would be one key.
      for (const Room& other : w.rooms)
        if (other.name == toks[1]) return fail("room: the name '" + toks[1] + "' is already used");
      Room room;
      room.name = toks[1];
      for (int k = 0; k < n; k += 2) room.polygon.emplace_back(nums[k], nums[k + 1]);
      for (const Eigen::Vector2d& p : room.polygon)
        if (outside_extent(p)) return fail(extent_error("room", p));
      w.rooms.push_back(std::move(room));
    } else {
      return fail("unknown keyword '" + kw + "'");
    }
  }
  line_no = 0;
  if (w.walls.empty() && w.obstacles.empty()) return fail("the world has no walls or obstacles");
  if (!have_start) return fail("the world has no 'start X Y Z YAW_DEG' line");
  if (w.name.empty()) w.name = std::string(source_name);
  r.ok = true;
  return r;
}

WorldParseResult load_world_file(const std::string& path) {
  // A directory opens as a stream and then reads as empty: say so rather than parse nothing.
  // Both refusals are in the words the parameter files' loader (modules/params) uses; the
  // callers print them as they are, and the path says which of their files it was.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    WorldParseResult r;
    r.error = "cannot read '" + path + "' (is a directory)";
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    WorldParseResult r;
    r.error = "cannot open '" + path + "'";
    return r;
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_world(ss.str(), path);
}

}  // namespace kestrel::sim
