#pragma once
// A simulated indoor world: 2D wall segments and convex obstacles, each standing over a height
// range [z_min, z_max], so that the slice a tilted 2D laser sees changes with the vehicle's
// altitude and attitude (paper 000, section 3.3). Materials model what lasers meet indoors:
// opaque surfaces, glass (the beam passes, no return) and railings (a beam returns with a
// given probability, the rest pass between the bars).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace kestrel::sim {

enum class Material : uint8_t { kOpaque, kGlass, kRailing };
const char* to_string(Material m);

// One straight piece of a wall (or one face of its box), or one edge of an obstacle, as the
// ray caster sees it.
struct Segment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  // m, world frame
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  // m
  double z_min = 0;                              // m above the floor
  double z_max = 0;                              // m
  Material material = Material::kOpaque;
  double return_probability = 1;  // per beam, for kRailing
  int piece = 0;                  // index into World::pieces() (walls first, then obstacles)
  int obstacle = -1;              // index into World::obstacles for an obstacle edge, else -1
};

struct Wall {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  double z_min = 0;
  double z_max = 2.5;
  Material material = Material::kOpaque;
  double return_probability = 1;
  int line = 0;  // source line, for messages
};

// A convex obstacle: a prism over a counter-clockwise convex polygon.
struct Obstacle {
  std::vector<Eigen::Vector2d> polygon;
  double z_min = 0;
  double z_max = 2.5;
  Material material = Material::kOpaque;
  double return_probability = 1;
  int line = 0;
};

struct Room {
  std::string name;
  std::vector<Eigen::Vector2d> polygon;  // simple polygon, either orientation
};

struct StartPose {
  double x = 0, y = 0, z = 0;  // m; z = 0 is standing on the floor
  double yaw_rad = 0;          // counter-clockwise from the world x axis
};

// How the laser sees walls (SimConfig::laser_sees_wall_thickness).
enum class WallSurfaces : uint8_t { kCentreLines, kBoxOutlines };

struct Bounds2 {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
};

class World {
 public:
  std::string name;
  StartPose start;
  double wall_thickness_m = 0.1;  // walls are this thick for collisions (and for the laser
                                  // with WallSurfaces::kBoxOutlines)
  double ceiling_m = 0;           // ceiling height for laser returns, 0 = none
  std::vector<Wall> walls;
  std::vector<Obstacle> obstacles;
  std::vector<Room> rooms;

  // Every surface the laser can meet, tagged with its piece index: walls 0..W-1, obstacles
  // W.... With kCentreLines a wall is its segment, zero thick; with kBoxOutlines an opaque
  // wall is the outline of the box the collision checker uses (wall_outline: two faces and
  // two end caps), so a beam along the wall's line meets its end and a doorway is as wide
  // for the laser as for the vehicle. Glass and railings stay one segment on the wall's line
  // either way (a pane, a row of bars: one crossing, one chance of a return).
  std::vector<Segment> segments(WallSurfaces walls = WallSurfaces::kCentreLines) const;
  std::size_t piece_count() const { return walls.size() + obstacles.size(); }
  Bounds2 bounds() const;
  // Index of the smallest room containing (x, y) (rooms may nest), or -1.
  int room_at(double x, double y) const;
};

// The box a wall occupies: its segment widened to `thickness_m` and extended by half of it past
// each end, so that walls meeting at a corner close it. Counter-clockwise.
std::array<Eigen::Vector2d, 4> wall_outline(const Wall& wall, double thickness_m);

bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p);
// Area enclosed by a simple polygon (m^2): positive counter-clockwise, negative clockwise.
double polygon_signed_area(const std::vector<Eigen::Vector2d>& poly);

}  // namespace kestrel::sim
