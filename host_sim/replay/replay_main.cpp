// kestrel-replay: runs the scan matcher (paper 000, section 5.1) over a recorded log, laser
// only, and writes trajectory_est.tum (each pose stamped with its scan's ipc_timestamp),
// metrics.json, map.pgm/map.yaml and render.png into --out.
//   kestrel-replay --log FILE [--format carmen|mines] --out DIR    (--help: the options)
// Exit status: 0 done, 1 output error, 2 bad usage or an unreadable or malformed log.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "kestrel/cli/arg_reader.hpp"
#include "kestrel/logs/open_log.hpp"
#include "kestrel/metrics/absolute_trajectory_error.hpp"
#include "kestrel/metrics/relative_pose_error.hpp"
#include "kestrel/output/canvas.hpp"
#include "kestrel/output/json_writer.hpp"
#include "kestrel/output/pgm_map.hpp"
#include "kestrel/output/png_writer.hpp"
#include "kestrel/output/tum_writer.hpp"
#include "kestrel/scan_matching/carmen_log_params.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"

namespace {
using namespace kestrel;
using namespace kestrel::scan_matching;

// One profile per log format, never per log. The CARMEN one lives with the matcher, where the
// real-data tests use it too; the URG-04LX logs move a few centimetres between scans.
Params profile(const std::string& format) {
  if (format == "carmen") return carmen_log_params();
  Params p;
  p.resolution_m = 0.01f;
  p.sigma_m = 0.02f;
  p.angle_step_rad = 0.2f * static_cast<float>(M_PI) / 180.0f;
  p.max_range_m = 4.0f;
  p.max_accel_mps2 = 2.0f;
  p.min_window_m = 0.1f;
  p.max_window_m = 0.5f;
  p.min_window_rad = 0.1f;
  p.max_window_rad = 0.4f;
  p.min_score = 0.05f;
  p.cov_half_window = 12;
  return p;
}

constexpr int kReplayDim = 2000;  // 40 m at 2 cm: the host can afford a wider window
LikelihoodMapStorage<kReplayDim, kMaxKeyframes * kMaxBeams> g_map_a, g_map_b;

void usage(std::FILE* to) { std::fprintf(to, "usage: kestrel-replay --log FILE [--format carmen|mines] --out DIR\n"); }

void help() {
  usage(stdout);
  std::fputs(
      "Runs the scan matcher (paper 000, section 5.1) over a recorded log, laser only, with one\n"
      "fixed profile per log format (never per log).\n"
      "  --log FILE     the log: CARMEN (FLASER, ROBOTLASER1; plain or .gz) or the URG-04LX .dat format\n"
      "  --format F     carmen (default) or mines (the .dat format)\n"
      "  --out DIR      writes trajectory_est.tum (each pose stamped with its scan's time), metrics.json\n"
      "                 (RPE and ATE against the log's reference poses when it has them, lost and\n"
      "                 rejected scans, time per scan), map.pgm + map.yaml (ROS map_server), render.png\n"
      "  --help         this text\n"
      "Exit status: 0 done, 1 output error, 2 bad usage or an unreadable or malformed log.\n",
      stdout);
}

// The extent of the map's points and poses. It starts empty (not at +-1e9, which a log with no
// matched scan left in place: the width came out negative and the grid's vector threw).
struct Bounds {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  void add(double x, double y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  }
  bool empty() const { return !(x0 <= x1 && y0 <= y1); }
  // Within +-1e6 m the cell and pixel counts below stay well inside an int (a first reference
  // pose beyond 1e9 m overflowed the cast); written as !(outside) so NaN is not drawable.
  bool drawable() const {
    constexpr double kMaxM = 1e6;
    return !empty() && std::fabs(x0) <= kMaxM && std::fabs(x1) <= kMaxM && std::fabs(y0) <= kMaxM &&
           std::fabs(y1) <= kMaxM;
  }
};

// Cells across `span_m` at `resolution_m`, at most 4000 (capped before the cast to int).
int capped_cells(double span_m, double resolution_m) {
  return static_cast<int>(std::min(3999.0, span_m / resolution_m)) + 1;
}

void print_summary(int n, int rejected, int lost, int keys, bool has_ref, const metrics::RpeResult& rpe,
                   const metrics::AteResult& ate, int jumps, double t_sum, double t_max) {
  std::printf("scans %d rejected %d lost %d key %d", n, rejected, lost, keys);
  if (has_ref)
    std::printf(" rpe %.4f m %.3f deg (max %.3f m %.2f deg, jumps %d) ate %.3f m", rpe.trans_m.mean, rpe.rot_deg.mean,
                rpe.trans_m.max, rpe.rot_deg.max, jumps, ate.trans_m.rmse);
  std::printf(" time mean %.0f us max %.0f us\n", t_sum / n, t_max);
}

}  // namespace

int main(int argc, char** argv) {
  std::string log, format = "carmen", out_dir;
  cli::ArgReader args(argc, argv);
  while (args.next()) {
    if (args.is("--help") || args.is("-h")) {
      help();
      return 0;
    } else if (args.is("--log")) {
      args.take(log);
    } else if (args.is("--format")) {
      if (args.take(format) && format != "carmen" && format != "mines")
        args.fail("--format: unknown format '" + format + "' (carmen or mines)");
    } else if (args.is("--out")) {
      args.take(out_dir);
    } else {
      args.unknown();
    }
  }
  if (args.ok() && log.empty()) args.fail("--log FILE is required");
  if (args.ok() && out_dir.empty()) args.fail("--out DIR is required");
  if (!args.ok()) {
    std::fprintf(stderr, "kestrel-replay: %s\n", args.error().c_str());
    usage(stderr);
    return 2;
  }

  logs::LogFormat fmt = logs::LogFormat::kCarmen;
  if (!ok(logs::parse_log_format(format, fmt))) {  // the reader's own list, should it differ
    std::fprintf(stderr, "kestrel-replay: --format: the log reader does not know '%s'\n", format.c_str());
    return 2;
  }
  logs::OpenLogOptions opts;
  opts.time_order = logs::TimeOrder::kAccept;  // the matcher rejects a backwards scan itself
  logs::LogError lerr;
  std::unique_ptr<logs::LogSource> src = logs::open_log(log.c_str(), fmt, opts, lerr);
  if (!src) {
    std::fprintf(stderr, "kestrel-replay: %s: %s\n", log.c_str(), lerr.reason);
    return 2;
  }
  struct Scan {
    LaserScan scan;
    double stamp_s;
    bool has_reference;
    Pose2d reference;
  };
  std::vector<Scan> scans;
  logs::LogRecord rec;
  for (;;) {
    const Status st = src->next(rec);
    if (st == Status::kNoData) break;
    if (!ok(st)) {
      std::fprintf(stderr, "kestrel-replay: %s:%u: %s\n", log.c_str(), static_cast<unsigned>(src->error().line),
                   src->error().reason);
      return 2;
    }
    if (rec.kind != logs::LogRecord::Kind::kLaser) continue;
    scans.push_back({rec.scan, rec.timestamp_s, rec.has_pose, rec.pose});
  }
  if (scans.empty()) {
    std::fprintf(stderr, "kestrel-replay: %s: no laser scans\n", log.c_str());
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);

  const Params params = profile(format);
  static ScanMatcher matcher(params, g_map_a, g_map_b, true);
  Pose2 start;
  if (scans[0].has_reference) start = scans[0].reference.cast<float>();
  if (!start.finite()) {
    // A finite double the float start pose cannot hold: the log's fault, not the matcher's.
    std::fprintf(stderr, "kestrel-replay: %s: the first scan's reference pose (%g, %g) is beyond a float's range\n",
                 log.c_str(), scans[0].reference.x, scans[0].reference.y);
    return 2;
  }
  if (!ok(matcher.configure(params, start))) {
    std::fprintf(stderr, "kestrel-replay: bad matcher configuration\n");
    return 1;
  }

  output::TumWriter tum;
  if (!ok(tum.open(out_dir + "/trajectory_est.tum"))) {
    std::fprintf(stderr, "kestrel-replay: cannot write %s\n", out_dir.c_str());
    return 1;
  }
  std::vector<Pose2d> est, ref;
  std::vector<Point2d> points;
  int rejected = 0, lost = 0, keys = 0, degenerate = 0;
  double t_sum = 0, t_max = 0;
  for (const Scan& s : scans) {
    const auto t0 = std::chrono::steady_clock::now();
    const ScanMatch r = matcher.process(s.scan);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    t_sum += us;
    t_max = std::max(t_max, us);
    if (!r.ok()) {
      ++rejected;
      continue;
    }
    const uint32_t f = r.measurement.flags;
    lost += (f & match_flag::kLost) != 0;
    keys += (f & match_flag::kKeyScan) != 0;
    degenerate += (f & match_flag::kDegenerate) != 0;
    const Pose2d p = r.measurement.pose.cast<double>();
    (void)tum.write(s.stamp_s, p.x, p.y, 0.0, p.theta);
    est.push_back(p);
    if (s.has_reference) ref.push_back(s.reference);
    for (uint16_t b = 0; b < s.scan.beam_count; b += 1) {
      const uint16_t mm = s.scan.range_mm[b];
      if (!LaserScan::is_return(mm) || mm >= params.max_range_m * 1000) continue;
      const double a = s.scan.angle_of(b), rr = mm * 1e-3;
      points.push_back(p.transform({rr * std::cos(a), rr * std::sin(a)}));
    }
  }
  (void)tum.close();

  const bool has_ref = ref.size() == est.size() && ref.size() >= 2;
  metrics::RpeResult rpe;
  metrics::AteResult ate;
  int jumps = 0;
  if (has_ref) {
    const auto r = metrics::relative_pose_error(est, ref);
    const auto a = metrics::absolute_trajectory_error(est, ref);
    if (r.ok()) rpe = r.value();
    if (a.ok()) ate = a.value();
    for (std::size_t i = 1; i < est.size(); ++i) {
      const Pose2d e = metrics::relative_error(est[i - 1], est[i], ref[i - 1], ref[i]);
      jumps += std::hypot(e.x, e.y) > 0.2 || std::fabs(e.theta) > 5 * M_PI / 180;
    }
  }
  const int n = static_cast<int>(scans.size());
  output::JsonWriter j;
  j.begin_object();
  j.string("log", log).string("format", format);
  j.integer("scans", n).integer("rejected", rejected).integer("lost", lost).integer("key_scans", keys);
  j.integer("degenerate", degenerate);
  if (has_ref) {
    j.number("rpe_trans_m", rpe.trans_m.mean).number("rpe_trans_std_m", rpe.trans_m.std);
    j.number("rpe_rot_deg", rpe.rot_deg.mean).number("rpe_rot_std_deg", rpe.rot_deg.std);
    j.number("rpe_trans_max_m", rpe.trans_m.max).number("rpe_rot_max_deg", rpe.rot_deg.max);
    j.integer("rpe_pairs", static_cast<int64_t>(est.size() - 1)).integer("jumps", jumps);
    j.number("ate_rmse_m", ate.trans_m.rmse);
  }
  j.number("tasks.scan_match.us_mean", t_sum / n).number("tasks.scan_match.us_max", t_max);
  j.end_object();
  if (!ok(j.write_file(out_dir + "/metrics.json"))) return 1;

  // The map: every return drawn at its scan's estimated pose, 5 cm cells.
  Bounds b;
  for (const Point2d& q : points) b.add(q.x, q.y);
  for (const Pose2d& q : est) b.add(q.x, q.y);
  if (!b.drawable()) {
    // No scan matched (every beam "no return", say), or the poses lie where no grid reaches.
    std::fprintf(stderr, "kestrel-replay: %s: %s; map.pgm not written\n", log.c_str(),
                 b.empty() ? "no scan was matched" : "the matched poses lie beyond +-1e6 m");
    output::Canvas c(800, 100);
    c.text(8, 8, b.empty() ? "no scan was matched: no map" : "poses beyond +-1e6 m: no map", output::colors::kBlack, 2);
    if (!ok(output::write_png(out_dir + "/render.png", c))) return 1;
    print_summary(n, rejected, lost, keys, has_ref, rpe, ate, jumps, t_sum, t_max);
    return 0;
  }
  const double x0 = b.x0, y0 = b.y0, x1 = b.x1, y1 = b.y1;
  output::GridImage g;
  g.resolution_m = 0.05;
  g.origin_x_m = x0 - 1;
  g.origin_y_m = y0 - 1;
  g.width = capped_cells(x1 - x0 + 2, g.resolution_m);
  g.height = capped_cells(y1 - y0 + 2, g.resolution_m);
  std::vector<int> hits(static_cast<std::size_t>(g.width) * g.height, 0);
  for (const Point2d& q : points) {
    const int cx = static_cast<int>((q.x - g.origin_x_m) / g.resolution_m),
              cy = static_cast<int>((q.y - g.origin_y_m) / g.resolution_m);
    if (cx >= 0 && cy >= 0 && cx < g.width && cy < g.height) ++hits[static_cast<std::size_t>(cy) * g.width + cx];
  }
  g.cells.assign(hits.size(), output::kPgmUnknown);
  for (std::size_t i = 0; i < hits.size(); ++i) if (hits[i] >= 2) g.cells[i] = output::kPgmOccupied;
  if (!ok(output::write_map(out_dir + "/map", g))) return 1;

  const double ppm = std::min(1600.0 / (x1 - x0 + 2), 1600.0 / (y1 - y0 + 2));
  output::Canvas c(static_cast<int>((x1 - x0 + 2) * ppm) + 1, static_cast<int>((y1 - y0 + 2) * ppm) + 1);
  c.set_world_view(g.origin_x_m, g.origin_y_m, ppm);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      if (g.cells[static_cast<std::size_t>(y) * g.width + x] == output::kPgmOccupied)
        c.set(c.wx(g.origin_x_m + x * g.resolution_m), c.wy(g.origin_y_m + y * g.resolution_m), output::colors::kBlack);
  for (std::size_t i = 1; i < est.size(); ++i) {
    if (has_ref) {
      c.world_line(ref[i - 1].x, ref[i - 1].y, ref[i].x, ref[i].y, output::colors::kGreen, 2);
    }
    // Both start at the log's first pose, so they share a frame without alignment.
    c.world_line(est[i - 1].x, est[i - 1].y, est[i].x, est[i].y, output::colors::kRed, 1);
  }
  c.text(8, 8, "scan matcher (red) vs reference (green)", output::colors::kBlack, 2);
  if (!ok(output::write_png(out_dir + "/render.png", c))) return 1;

  print_summary(n, rejected, lost, keys, has_ref, rpe, ate, jumps, t_sum, t_max);
  return 0;
}
