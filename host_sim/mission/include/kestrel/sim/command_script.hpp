#pragma once
// A scripted command sequence for the `manual` mission: one set-point per line, held from
// its time until the next line's. Columns (whitespace separated, `#` comments):
//
//   T_S  PITCH_DEG  ROLL_DEG  THRUST  YAW_RATE_DPS
//
// the inputs u of paper 000 equation 1 (positive pitch accelerates forward, positive roll to
// the left, thrust 0..1 with hover at 0.5 by default, yaw rate counter-clockwise). A line
// `disarm T_S` stops the motors at T_S. Times must not decrease.
#include <string>
#include <string_view>
#include <vector>

#include "kestrel/core/messages.hpp"

namespace kestrel::sim {

// The latest time a step may have: kestrel-sim's longest --duration. A later one would not fly,
// and beyond ~9.2e12 s TimeUs::from_s overflowed and the step fired at t = 0.
inline constexpr double kMaxScriptTimeS = kMaxRunSeconds;

struct ScriptStep {
  double t_s = 0;
  AttitudeSetpoint setpoint;  // stamp unused
  bool disarm = false;
};

struct CommandScript {
  std::vector<ScriptStep> steps;

  // "" or "SOURCE:LINE: reason".
  std::string parse(std::string_view text, std::string_view source_name);
  // read_text(path) then parse(text, path).
  std::string load(const std::string& path);
  // The file's text, for a caller that passes it on rather than parse it here: "" or why it
  // cannot be read (a directory is refused, not read as empty).
  static std::string read_text(const std::string& path, std::string& text);
  // The default flight: take off to 1 m, fly down the iarc-arena hallway, turn, come back,
  // enter room C through its doorway, turn around and land. Open loop, so it is exact only
  // without gusts.
  static std::string_view default_text();
};

}  // namespace kestrel::sim
