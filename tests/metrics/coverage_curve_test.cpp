// Coverage-versus-time records of kestrel-sim explore runs and their mean over seeds (issue 6:
// blend, wall following and SRT-Star alone on the same axes).
#include "kestrel/metrics/coverage_curve.hpp"

#include <gtest/gtest.h>

namespace kestrel::metrics {
namespace {

TEST(CoverageCurve, ParsesTheRecordKestrelSimWrites) {
  const Result<CoverageCurve> c = parse_coverage_csv("t_s,coverage\n0.000,0.000000\n1.000,0.125000\r\n\n2.500,0.5\n");
  ASSERT_TRUE(c.ok());
  ASSERT_EQ(c.value().t_s.size(), 3u);
  EXPECT_DOUBLE_EQ(c.value().t_s[2], 2.5);
  EXPECT_DOUBLE_EQ(c.value().coverage[1], 0.125);
}

TEST(CoverageCurve, RefusesMalformedRecords) {
  EXPECT_EQ(parse_coverage_csv("").status(), Status::kMalformed);                                // no header
  EXPECT_EQ(parse_coverage_csv("time,coverage\n0,0\n").status(), Status::kMalformed);           // other header
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n").status(), Status::kNoData);                    // no rows
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n0;0.1\n").status(), Status::kMalformed);          // no comma
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n0,abc\n").status(), Status::kMalformed);          // not a number
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n0,0.1x\n").status(), Status::kMalformed);         // trailing text
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n0,nan\n").status(), Status::kMalformed);          // not finite
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n0,1.2\n").status(), Status::kMalformed);          // above 1
  EXPECT_EQ(parse_coverage_csv("t_s,coverage\n2,0.1\n1,0.2\n").status(), Status::kMalformed);   // time backwards
}

TEST(CoverageCurve, ValueIsTheLastSampleAtOrBeforeTheTime) {
  const CoverageCurve c{{1.0, 2.0, 5.0}, {0.1, 0.3, 0.6}};
  EXPECT_DOUBLE_EQ(coverage_at(c, 0.5), 0.0);  // before the first sample
  EXPECT_DOUBLE_EQ(coverage_at(c, 1.0), 0.1);
  EXPECT_DOUBLE_EQ(coverage_at(c, 4.9), 0.3);
  EXPECT_DOUBLE_EQ(coverage_at(c, 300.0), 0.6);  // a run that ended keeps what it saw
}

TEST(CoverageCurve, MeanOverRunsOnACommonGrid) {
  // Run a ends (collision) at 2 s; run b goes on to 4 s.
  const CoverageCurve a{{0.0, 1.0, 2.0}, {0.0, 0.2, 0.4}};
  const CoverageCurve b{{0.0, 1.0, 2.0, 3.0, 4.0}, {0.0, 0.4, 0.6, 0.8, 1.0}};
  const Result<CoverageCurve> m = mean_coverage({a, b}, 1.0, 4.0);
  ASSERT_TRUE(m.ok());
  const std::vector<double> t{0, 1, 2, 3, 4}, v{0.0, 0.3, 0.5, 0.6, 0.7};
  ASSERT_EQ(m.value().t_s.size(), t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_DOUBLE_EQ(m.value().t_s[i], t[i]);
    EXPECT_NEAR(m.value().coverage[i], v[i], 1e-12) << "t = " << t[i];
  }
  // A step that does not divide the end: the grid stops at the last step within half a step.
  EXPECT_EQ(mean_coverage({a}, 0.3, 1.0).value().t_s.size(), 4u);  // 0, 0.3, 0.6, 0.9
  EXPECT_EQ(mean_coverage({}, 1.0, 4.0).status(), Status::kNoData);
  EXPECT_EQ(mean_coverage({a}, 0.0, 4.0).status(), Status::kInvalidArgument);
  EXPECT_EQ(mean_coverage({a}, 1.0, -1.0).status(), Status::kInvalidArgument);
}

// Regression: the grid's size was unbounded, so a step of 1e-6 s to 1e6 s asked for 10^12
// samples (out of memory) and an end of 1e300 s overflowed lround and gave an empty curve.
TEST(CoverageCurve, MeanRefusesMoreThanTheMaximumSteps) {
  const CoverageCurve a{{0.0, 1.0}, {0.0, 0.5}};
  EXPECT_EQ(mean_coverage({a}, 1e-6, 1e6).status(), Status::kInvalidArgument);
  EXPECT_EQ(mean_coverage({a}, 1.0, 1e300).status(), Status::kInvalidArgument);
  EXPECT_EQ(mean_coverage({a}, 1.0, kMaxCoverageSteps + 1).status(), Status::kInvalidArgument);
  EXPECT_EQ(mean_coverage({a}, 1.0, kMaxCoverageSteps).value().t_s.size(),
            static_cast<std::size_t>(kMaxCoverageSteps) + 1);
}

}  // namespace
}  // namespace kestrel::metrics
