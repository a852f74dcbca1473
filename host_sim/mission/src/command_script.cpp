#include "kestrel/sim/command_script.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kestrel::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

constexpr std::string_view kDefault = R"(# manual flight for iarc-arena (start 2.0 7.5 heading +x)
# t_s  pitch_deg roll_deg thrust yaw_rate_dps
0      0   0   0.55  0     # climb ...
1      0   0   0.45  0     # ... and stop at ~1 m
2      0   0   0.50  0     # hover
3      5   0   0.50  0     # accelerate down the hallway
5      0   0   0.50  0     # cruise at 1.7 m/s
13    -5   0   0.50  0     # brake
15     0   0   0.50  0
16     0   0   0.50  45    # turn around
20     0   0   0.50  0
21     5   0   0.50  0     # back up the hallway
23     0   0   0.50  0
26.56 -5   0   0.50  0     # stop in front of room C's doorway
28.56  0   0   0.50  0
29.5   0   0   0.50  -45   # face the doorway (north)
31.5   0   0   0.50  0
32.5   4   0   0.50  0     # through the doorway
33.5   0   0   0.50  0
37    -4   0   0.50  0
38     0   0   0.50  0
39     0   0   0.50  60    # look around the room
45     0   0   0.50  0
46     0   3   0.50  0     # sidestep left
47     0  -3   0.50  0
48     0   0   0.45  0     # descend ...
49     0   0   0.55  0     # ... and stop at the floor
50     0   0   0.45  0
disarm 51
)";

}  // namespace

std::string_view CommandScript::default_text() { return kDefault; }

std::string CommandScript::parse(std::string_view text, std::string_view source_name) {
  steps.clear();
  const std::string src(source_name);
  std::istringstream in{std::string(text)};
  std::string raw;
  int line_no = 0;
  double last_t = -1e300;
  while (std::getline(in, raw)) {
    ++line_no;
    const auto hash = raw.find('#');
    if (hash != std::string::npos) raw.resize(hash);
    std::istringstream ls(raw);
    std::vector<std::string> toks;
    for (std::string t; ls >> t;) toks.push_back(t);
    if (toks.empty()) continue;
    const std::string where = src + ":" + std::to_string(line_no) + ": ";
    auto num = [](const std::string& s, double& v) {
      char* end = nullptr;
      v = std::strtod(s.c_str(), &end);
      return !s.empty() && end == s.c_str() + s.size() && std::isfinite(v);
    };
    ScriptStep st;
    if (toks[0] == "disarm") {
      if (toks.size() != 2 || !num(toks[1], st.t_s)) return where + "expected 'disarm T_S'";
      st.disarm = true;
    } else {
      if (toks.size() != 5)
        return where + "expected 5 numbers: T_S PITCH_DEG ROLL_DEG THRUST YAW_RATE_DPS";
      double v[5];
      for (int i = 0; i < 5; ++i)
        if (!num(toks[static_cast<std::size_t>(i)], v[i]))
          return where + "'" + toks[static_cast<std::size_t>(i)] + "' is not a number";
      if (v[3] < 0 || v[3] > 1) return where + "thrust must be between 0 and 1";
      st.t_s = v[0];
      st.setpoint.pitch_rad = static_cast<float>(v[1] * kDeg);
      st.setpoint.roll_rad = static_cast<float>(v[2] * kDeg);
      st.setpoint.thrust = static_cast<float>(v[3]);
      st.setpoint.yaw_rate_radps = static_cast<float>(v[4] * kDeg);
    }
    if (st.t_s < 0) return where + "time must not be negative";
    if (st.t_s > kMaxScriptTimeS) return where + "time must be at most 1e6 s (kestrel-sim's longest --duration)";
    if (st.t_s < last_t) return where + "time goes backwards";
    last_t = st.t_s;
    steps.push_back(st);
  }
  if (steps.empty()) return src + ": the script has no commands";
  return {};
}

std::string CommandScript::read_text(const std::string& path, std::string& text) {
  // A directory opens as a stream and then reads as empty: say so rather than parse nothing.
  // Both refusals are in the words the parameter files' loader (modules/params) uses; the
  // callers print them as they are, and the path says which of their files it was.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return "cannot read '" + path + "' (is a directory)";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open '" + path + "'";
  std::ostringstream ss;
  ss << in.rdbuf();
  text = ss.str();
  return {};
}

std::string CommandScript::load(const std::string& path) {
  std::string text;
  if (std::string e = read_text(path, text); !e.empty()) return e;
  return parse(text, path);
}

}  // namespace kestrel::sim
