// The estimate's error put on a contact (metrics.json contacts[].estimate_err_m): the newest
// sample at or before the contact, and nothing when the filter had no sample near it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kestrel/flight/autonomy_mission.hpp"

namespace kestrel::flight {
namespace {

EstimateSample sample(double t_s, double est_x, double true_x, double est_y = 0.0, double true_y = 0.0) {
  EstimateSample s{};
  s.t_s = t_s;
  s.est_pos = {est_x, est_y, 1.0};
  s.true_pos = {true_x, true_y, 1.2};  // height is not the horizontal error's
  return s;
}

TEST(EstimateErrorAtContact, TakesTheNewestSampleAtOrBeforeTheContact) {
  const std::vector<EstimateSample> s{sample(1.0, 5.0, 4.0), sample(1.1, 6.0, 4.0, 2.0, 2.5),
                                      sample(1.2, 9.0, 4.0)};
  const std::optional<sim::EstimateError> e = estimate_error_at(s, 1.19, 0.5);
  ASSERT_TRUE(e.has_value());
  EXPECT_DOUBLE_EQ(e->x_m, 2.0);  // the 1.1 s sample's, not the nearer but later 1.2 s one's
  EXPECT_DOUBLE_EQ(e->y_m, -0.5);
  const std::optional<sim::EstimateError> at = estimate_error_at(s, 1.2, 0.5);
  ASSERT_TRUE(at.has_value());
  EXPECT_DOUBLE_EQ(at->x_m, 5.0);  // a sample stamped at the contact is its own
}

TEST(EstimateErrorAtContact, NothingBeforeTheFirstSampleOrLongAfterTheLast) {
  const std::vector<EstimateSample> s{sample(1.0, 5.0, 4.0), sample(2.0, 5.0, 4.0)};
  EXPECT_FALSE(estimate_error_at(s, 0.9, 0.5).has_value());
  EXPECT_FALSE(estimate_error_at(s, 2.6, 0.5).has_value());  // the filter stopped 0.6 s before
  EXPECT_TRUE(estimate_error_at(s, 2.4, 0.5).has_value());
  EXPECT_TRUE(estimate_error_at(s, 2.5, 0.5).has_value());  // exactly max_age_s old still counts
  EXPECT_FALSE(estimate_error_at({}, 1.0, 0.5).has_value());
}

TEST(EstimateErrorAtContact, OutOfOrderStampsStillGiveTheNewestBeforeTheContact) {
  // A sample recorded after a newer one (a stamp that went back) is not taken for the newest,
  // and neither a stale one nor a NaN-stamped one at the end hides an in-age sample before it.
  const std::vector<EstimateSample> s{sample(1.0, 5.0, 4.0), sample(1.3, 7.0, 4.0), sample(1.2, 9.0, 4.0)};
  const std::optional<sim::EstimateError> e = estimate_error_at(s, 1.35, 0.5);
  ASSERT_TRUE(e.has_value());
  EXPECT_DOUBLE_EQ(e->x_m, 3.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<EstimateSample> tail{sample(1.3, 7.0, 4.0), sample(0.1, 9.0, 4.0), sample(nan, 9.0, 4.0)};
  const std::optional<sim::EstimateError> t = estimate_error_at(tail, 1.35, 0.5);
  ASSERT_TRUE(t.has_value());
  EXPECT_DOUBLE_EQ(t->x_m, 3.0);
}

TEST(EstimateErrorAtContact, ANonFiniteEstimateGivesNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<EstimateSample> s{sample(1.0, nan, 4.0)};
  EXPECT_FALSE(estimate_error_at(s, 1.0, 0.5).has_value());
  EXPECT_FALSE(estimate_error_at({sample(1.0, 5.0, 4.0)}, nan, 0.5).has_value());
}

}  // namespace
}  // namespace kestrel::flight
