// Real-data regression: the first scans of Freiburg building 079 (Radish, CARMEN log), laser
// only, against the log's corrected poses. Short, so it also runs under qemu-arm.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "kestrel/scan_matching/scan_matcher.hpp"
#include "kestrel_test_paths.hpp"

namespace kestrel::scan_matching {
namespace {

#if defined(__arm__)
constexpr int kScans = 60;  // qemu-arm is 10-50x slower
#else
constexpr int kScans = 250;
#endif

struct Entry {
  LaserScan scan;
  Pose2d ref;
};

std::vector<Entry> read_flaser(const std::string& path, int max) {
  std::vector<Entry> out;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) return out;
  static char line[1 << 16];
  while (static_cast<int>(out.size()) < max && gzgets(f, line, sizeof line) != nullptr) {
    if (std::string(line, 7) != "FLASER ") continue;
    char* p = line + 7;
    const int n = static_cast<int>(std::strtol(p, &p, 10));
    Entry e;
    e.scan.beam_count = static_cast<uint16_t>(n);
    e.scan.first_angle_rad = static_cast<float>(-M_PI / 2);
    e.scan.angle_step_rad = static_cast<float>(n % 2 ? M_PI / (n - 1) : M_PI / n);
    e.scan.max_range_mm = 65000;
    for (int i = 0; i < n; ++i) {
      const double r = std::strtod(p, &p);
      e.scan.range_mm[static_cast<std::size_t>(i)] = r > 0 && r < 65 ? static_cast<uint16_t>(std::lround(r * 1000)) : 0;
    }
    double v[7];
    for (double& x : v) x = std::strtod(p, &p);
    e.ref = {v[0], v[1], v[2]};
    e.scan.stamp = TimeUs::from_s(v[6]);
    out.push_back(e);
  }
  gzclose(f);
  return out;
}

LikelihoodMapStorage<2000, kMaxKeyframes * kMaxBeams> g_a, g_b;

TEST(ScanMatcherRealData, Freiburg079Slice) {
  const auto log = read_flaser(test::shared_data_path("carmen/freiburg-079.log.gz"), kScans);
  if (log.empty()) GTEST_SKIP() << "shared data not available";
  Params p;  // the kestrel-replay CARMEN profile
  p.resolution_m = 0.02f;
  p.sigma_m = 0.03f;
  p.angle_step_rad = 0.25f * static_cast<float>(M_PI) / 180.0f;
  p.max_range_m = 40.0f;
  p.max_accel_mps2 = 1.0f;
  p.max_ang_accel_radps2 = 1.0f;
  p.min_window_m = 0.3f;
  p.max_window_m = 1.6f;
  p.min_window_rad = 0.25f;
  p.max_window_rad = 0.75f;
  p.join_max_m = 0.5f;
  p.min_score = 0.05f;
  static ScanMatcher m(p, g_a, g_b, true);
  ASSERT_EQ(m.configure(p, log[0].ref.cast<float>()), Status::kOk);
  Pose2d prev;
  double sum_t = 0, sum_r = 0;
  int pairs = 0, lost = 0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const ScanMatch r = m.process(log[i].scan);
    ASSERT_TRUE(r.ok()) << i;
    lost += (r.measurement.flags & match_flag::kLost) != 0;
    const Pose2d e = r.measurement.pose.cast<double>();
    if (i > 0) {
      const Pose2d err = log[i - 1].ref.between(log[i].ref).between(prev.between(e));
      sum_t += std::hypot(err.x, err.y);
      sum_r += std::fabs(err.theta);
      ++pairs;
    }
    prev = e;
  }
  EXPECT_EQ(lost, 0);
  EXPECT_LT(sum_t / pairs, 0.03);
  EXPECT_LT(sum_r / pairs * 180 / M_PI, 0.5);
  RecordProperty("rpe_trans_m", std::to_string(sum_t / pairs));
  RecordProperty("rpe_rot_deg", std::to_string(sum_r / pairs * 180 / M_PI));
}

}  // namespace
}  // namespace kestrel::scan_matching
