// Benchmarks of the scan matcher at the paper's configuration (paper 000, section 5.1).
// Heap use here is set-up before each benchmark's timed loop (large objects that would not fit
// on the stack); the timed code itself never allocates (see the alloc_guard tests).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "kestrel/scan_matching/relocaliser.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"

namespace {
using namespace kestrel;
using namespace kestrel::scan_matching;

// A realistic indoor scan: a 6 x 4 m room with a doorway, a pillar and a railing, seen by a
// UTM-30LX (1081 beams over 270 degrees) from `pose`; `scale` multiplies every wall's
// coordinates (2.5: a 15 x 10 m hall, which fills most of the on-board map at the benchmarks'
// 7.5 mm cells, 15 m).
LaserScan room_scan(const Pose2& pose, TimeUs t, float scale = 1.0f) {
  LaserScan s;
  s.stamp = t;
  s.beam_count = 1081;
  s.first_angle_rad = -2.35619449f;
  s.angle_step_rad = 4.71238898f / 1080.0f;
  s.max_range_mm = 30000;
  struct Seg { float ax, ay, bx, by; };
  const Seg segs[] = {{-3, -2, 3, -2}, {3, -2, 3, 2}, {3, 2, 0.5f, 2}, {-0.5f, 2, -3, 2}, {-3, 2, -3, -2},
                      {0.5f, 2, 0.5f, 3}, {-0.5f, 2, -0.5f, 3}, {1.2f, 0.3f, 1.5f, 0.3f}, {1.5f, 0.3f, 1.5f, 0.6f},
                      {1.2f, 0.6f, 1.5f, 0.6f}, {1.2f, 0.3f, 1.2f, 0.6f}, {-2, -1, -2, 1}};
  for (int i = 0; i < 1081; ++i) {
    const float a = pose.theta + s.angle_of(static_cast<std::size_t>(i));
    const float dx = std::cos(a), dy = std::sin(a);
    float best = 1e9f;
    for (std::size_t j = 0; j < sizeof(segs) / sizeof(segs[0]); ++j) {
      const Seg g{segs[j].ax * scale, segs[j].ay * scale, segs[j].bx * scale, segs[j].by * scale};
      const float ex = g.bx - g.ax, ey = g.by - g.ay;
      const float den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-9f) continue;
      const float wx = g.ax - pose.x, wy = g.ay - pose.y;
      const float t1 = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
      // The railing (x = -2) is transparent every third beam.
      if (j == 11 && i % 3 == 0) continue;
      if (t1 > 0.02f && u >= 0 && u <= 1 && t1 < best) best = t1;
    }
    s.range_mm[static_cast<std::size_t>(i)] = best < 29.0f ? static_cast<uint16_t>(std::lround(best * 1000)) : 0;
  }
  return s;
}

struct PaperSetup {
  Params p;
  std::unique_ptr<OnboardMapStorage> storage = std::make_unique<OnboardMapStorage>();
  std::unique_ptr<ScanMatcher> matcher;
  LaserScan next;
  PaperSetup(bool multi) {
    p.multi_resolution = multi;
    // About 15,000 candidate poses: 21 x 21 translations (+-7.5 cm) x 35 rotations (+-2.55 deg).
    p.min_window_m = p.max_window_m = 10 * 0.0075f;
    p.min_window_rad = p.max_window_rad = 17 * p.angle_step_rad;
    matcher = std::make_unique<ScanMatcher>(p, storage->map_a, storage->map_b, true);
    (void)matcher->process(room_scan({0.1f, 0.05f, 0.1f}, TimeUs::from_s(0)));
    next = room_scan({0.13f, 0.03f, 0.105f}, TimeUs::from_s(0.025));
  }
};

void paper_config(benchmark::State& st, bool multi) {
  PaperSetup s(multi);
  std::unique_ptr<ScanMatcher>& m = s.matcher;
  for (auto _ : st) {
    // The same scan each time against the same map: the overlap rule keeps the map.
    ScanMatch r = m->process(s.next);
    benchmark::DoNotOptimize(r);
  }
  const double poses = 21.0 * 21.0 * 35.0;
  st.counters["candidate_poses"] = poses;
  st.counters["poses_per_s"] =
      benchmark::Counter(poses * static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
}

void BM_PaperMulti(benchmark::State& st) { paper_config(st, true); }
void BM_PaperExhaustive(benchmark::State& st) { paper_config(st, false); }
BENCHMARK(BM_PaperMulti)->Name("scan_matcher/paper_000")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PaperExhaustive)->Name("scan_matcher/paper_000_exhaustive")->Unit(benchmark::kMicrosecond);

void BM_Contours350(benchmark::State& st) {
  Params p;
  LaserScan scan = room_scan({0.1f, 0.05f, 0.1f}, TimeUs{});
  ScanPoints pts;
  pts.angle_step_rad = scan.angle_step_rad * 3;
  for (std::size_t i = 0; i < 1050; i += 3) {
    const float a = scan.angle_of(i), r = scan.range_mm[i] * 1e-3f;
    if (scan.range_mm[i] < 20) continue;
    pts.x[pts.count] = r * std::cos(a);
    pts.y[pts.count] = r * std::sin(a);
    pts.range_mm[pts.count] = scan.range_mm[i];
    pts.beam[pts.count] = static_cast<uint16_t>(i / 3);
    ++pts.count;
  }
  auto ex = std::make_unique<ContourExtractor>(p);
  auto c = std::make_unique<Contours>();
  for (auto _ : st) {
    ex->extract(pts, *c);
    benchmark::DoNotOptimize(c->segment_count);
  }
  st.counters["points"] = pts.count;
}
BENCHMARK(BM_Contours350)->Name("scan_matcher/contours_350")->Unit(benchmark::kMicrosecond);

// A full rebuild of a 7.5 mm local map from 5 key scans of the room, scaled by `scale`. The
// rebuild's coarse levels cover the area the walls span, so the hall measures what a wide
// map costs where its width is used.
void map_build(benchmark::State& st, float scale) {
  Params p;
  auto storage = std::make_unique<OnboardMapStorage>();
  auto local = std::make_unique<LocalMap>(p, storage->map_a, storage->map_b);
  auto key = std::make_unique<KeyScan>();
  for (int i = 0; i < 5; ++i) {
    const LaserScan s = room_scan({0.05f * i, 0.0f, 0.02f * i}, TimeUs{}, scale);
    key->pose = {0.05f * i, 0.0f, 0.02f * i};
    key->points.count = 0;
    key->points.angle_step_rad = s.angle_step_rad;
    for (std::size_t b = 0; b < 1081; ++b) {
      if (s.range_mm[b] < 20) continue;
      const float a = s.angle_of(b), r = s.range_mm[b] * 1e-3f;
      auto& pt = key->points;
      pt.x[pt.count] = r * std::cos(a);
      pt.y[pt.count] = r * std::sin(a);
      pt.range_mm[pt.count] = s.range_mm[b];
      pt.beam[pt.count] = static_cast<uint16_t>(b);
      ++pt.count;
    }
    (void)local->submit(*key);
    (void)local->rebuild();
  }
  for (auto _ : st) {
    (void)local->submit(*key);  // the newest scan again: a full redraw of all five
    benchmark::DoNotOptimize(local->rebuild());
  }
}
void BM_MapBuild(benchmark::State& st) { map_build(st, 1.0f); }
void BM_MapBuildHall(benchmark::State& st) { map_build(st, 2.5f); }
BENCHMARK(BM_MapBuild)->Name("scan_matcher/map_build")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MapBuildHall)->Name("scan_matcher/map_build_15m_hall")->Unit(benchmark::kMicrosecond);

// The room scan with every `stride`-th beam.
LaserScan room_scan_strided(const Pose2& pose, float scale, std::size_t stride) {
  const LaserScan full = room_scan(pose, TimeUs{}, scale);
  LaserScan s = full;
  s.angle_step_rad = full.angle_step_rad * static_cast<float>(stride);
  s.beam_count = 0;
  for (std::size_t b = 0; b < full.beam_count; b += stride) s.range_mm[s.beam_count++] = full.range_mm[b];
  return s;
}

// The room scan's returns as points, every `stride`-th beam.
ScanPoints room_points(const Pose2& pose, float scale, std::size_t stride) {
  const LaserScan s = room_scan(pose, TimeUs{}, scale);
  ScanPoints pt;
  pt.angle_step_rad = s.angle_step_rad * static_cast<float>(stride);
  for (std::size_t b = 0; b < s.beam_count; b += stride) {
    if (s.range_mm[b] < 20) continue;
    const float a = s.angle_of(b), r = s.range_mm[b] * 1e-3f;
    pt.x[pt.count] = r * std::cos(a);
    pt.y[pt.count] = r * std::sin(a);
    pt.range_mm[pt.count] = s.range_mm[b];
    pt.beam[pt.count] = static_cast<uint16_t>(b / stride);
    ++pt.count;
  }
  return pt;
}

// One home re-localisation search (level 3, at most once a second on the way home): the
// default window, +-4.5 m and +-0.3 rad at 4 cm and 0.01 rad, against five reference scans of
// the 15 x 10 m hall, the guess 1.4 m and 0.1 rad off; then the rival peak outside 0.5 m at
// the best rotation, and the beams walked for see-through against the raw scan, as in flight.
// The UTM-30LX's 1081 beams, and every other one of them (541: about the URG-04LX's returns
// in a room, though its 4 m reach sees less of the hall).
void relocalise(benchmark::State& st, std::size_t stride) {
  Params m;
  auto r = std::make_unique<Relocaliser>();
  if (r->configure(RelocaliserParams{}, m) != Status::kOk) {
    st.SkipWithError("configure");
    return;
  }
  const Pose2 refs[] = {{0, 0, 0}, {0, 0, 1.2f}, {0, 0, 2.4f}, {0, 0, 3.6f}, {0, 0, 4.8f}};
  for (const Pose2& p : refs) (void)r->add_reference(room_points(p, 2.5f, stride), p);
  const Pose2 truth{1.5f, 0.8f, 0.7f};
  const ScanPoints pts = room_points(truth, 2.5f, stride);
  const LaserScan scan = room_scan_strided(truth, 2.5f, stride);
  const Pose2 guess{truth.x + 1.0f, truth.y - 1.0f, truth.theta + 0.1f};
  int fixed = 0;
  for (auto _ : st) {
    const Relocalisation fix = r->locate(pts, guess, &scan);
    fixed += fix.fixed() ? 1 : 0;
    benchmark::DoNotOptimize(fix);
  }
  st.counters["points"] = pts.count;
  st.counters["fixed"] = benchmark::Counter(fixed, benchmark::Counter::kAvgIterations);
}
void BM_RelocaliseUtm(benchmark::State& st) { relocalise(st, 1); }
void BM_RelocaliseHalf(benchmark::State& st) { relocalise(st, 2); }
BENCHMARK(BM_RelocaliseUtm)->Name("relocaliser/locate_1081")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelocaliseHalf)->Name("relocaliser/locate_541")->Unit(benchmark::kMillisecond);

}  // namespace
