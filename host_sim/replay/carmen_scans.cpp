#include "carmen_scans.hpp"

#include <zlib.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace kestrel::replay {
namespace {

bool next_number(const char*& p, double& v) {
  char* end = nullptr;
  v = std::strtod(p, &end);
  if (end == p || !std::isfinite(v)) return false;
  p = end;
  return true;
}

uint16_t to_mm(double r_m) {
  if (!(r_m > 0)) return range_code::kNoReturn;
  const double mm = r_m * 1000.0;
  return mm >= 65000.0 ? range_code::kNoReturn : static_cast<uint16_t>(std::lround(mm));
}

bool parse_flaser(const char* p, LogScan& s, std::string& why) {
  double n = 0;
  if (!next_number(p, n) || n < 1 || n > static_cast<double>(kMaxBeams) || n != std::floor(n)) {
    why = "bad beam count";
    return false;
  }
  const int beams = static_cast<int>(n);
  s.scan.beam_count = static_cast<uint16_t>(beams);
  // Beams evenly spread over 180 degrees, first at -90: 181/361 include both ends.
  s.scan.first_angle_rad = static_cast<float>(-M_PI / 2);
  s.scan.angle_step_rad = static_cast<float>(beams % 2 == 1 ? M_PI / (beams - 1) : M_PI / beams);
  s.scan.max_range_mm = 65000;
  for (int i = 0; i < beams; ++i) {
    double r = 0;
    if (!next_number(p, r)) {
      why = "range " + std::to_string(i + 1) + " of " + std::to_string(beams) + " missing or not a number";
      return false;
    }
    s.scan.range_mm[static_cast<std::size_t>(i)] = to_mm(r);
  }
  double v[7];
  for (double& x : v) {
    if (!next_number(p, x)) {
      why = "pose or timestamp missing after the ranges";
      return false;
    }
  }
  s.reference = {v[0], v[1], v[2]};
  s.has_reference = true;
  s.stamp_s = v[6];
  s.scan.stamp = TimeUs::from_s(v[6]);
  return true;
}

bool parse_mines(const char* p, LogScan& s, std::string& why) {
  double v = 0;
  std::vector<double> f;
  while (next_number(p, v)) f.push_back(v);
  if (f.size() != 707) {
    why = "expected 707 fields, found " + std::to_string(f.size());
    return false;
  }
  s.stamp_s = f[0] * 1e-6;
  s.scan.stamp = TimeUs::from_us(static_cast<int64_t>(f[0]));
  s.scan.beam_count = 682;
  s.scan.first_angle_rad = static_cast<float>(-120.0 * M_PI / 180.0);
  s.scan.angle_step_rad = static_cast<float>(240.0 * M_PI / 180.0 / 681.0);
  s.scan.max_range_mm = 4000;
  for (int i = 0; i < 682; ++i) {
    const double mm = f[static_cast<std::size_t>(24 + i)];
    s.scan.range_mm[static_cast<std::size_t>(i)] = mm < 20 || mm > 65000 ? 0 : static_cast<uint16_t>(mm);
  }
  return true;
}

}  // namespace

bool read_log(const std::string& path, const std::string& format, std::vector<LogScan>& out, std::string& error) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = path + ": cannot open";
    return false;
  }
  std::string line;
  char buf[65536];
  int line_no = 0;
  bool ok = true;
  for (;;) {
    line.clear();
    bool got = false;
    while (gzgets(f, buf, sizeof buf) != nullptr) {
      got = true;
      line += buf;
      if (!line.empty() && line.back() == '\n') break;
    }
    if (!got) break;
    ++line_no;
    std::string why;
    LogScan s;
    if (format == "carmen") {
      if (line.rfind("FLASER ", 0) != 0) continue;
      ok = parse_flaser(line.c_str() + 7, s, why);
    } else {
      if (line.find_first_not_of(" \t\r\n") == std::string::npos) continue;
      ok = parse_mines(line.c_str(), s, why);
    }
    if (!ok) {
      error = path + ":" + std::to_string(line_no) + ": " + why;
      break;
    }
    out.push_back(s);
  }
  int err = 0;
  const char* msg = gzerror(f, &err);
  if (ok && err != Z_OK && err != Z_STREAM_END) {
    error = path + ":" + std::to_string(line_no) + ": read error (" + msg + ")";
    ok = false;
  }
  gzclose(f);
  return ok;
}

}  // namespace kestrel::replay
