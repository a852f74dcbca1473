#include "kestrel/flight/slam_trace.hpp"

#include <cmath>
#include <cstdio>

namespace kestrel::flight {

const char* SlamTrace::header() {
  return "t_s,flags,started,drawn,matched,corrected,warming_up,too_few_points,not_finite,no_fit,no_gain,too_far,"
         "unpinned,"
         "points,level,prior_level,prior_x,prior_y,prior_theta,fit_x,fit_y,fit_theta,fit_move_m,"
         "true_x,true_y,true_yaw,prior_err_m,fit_err_m,true_level";
}

int SlamTrace::format_row(char* buf, std::size_t size, const autonomy::SlamStep& step, const sim::VehicleState* t,
                          double true_level) {
  namespace sf = slam::slam_flag;
  const slam::SlamResult& r = step.result;
  auto bit = [&r](uint32_t b) { return (r.flags & b) != 0 ? 1 : 0; };
  const double nan = std::nan("");
  const double tx = t ? t->position_m.x() : nan, ty = t ? t->position_m.y() : nan;
  const double tyaw = t ? t->yaw_rad : nan;
  const Pose2& p = step.prior;
  const Pose2& f = step.fit;
  const auto dist = [](double ax, double ay, double bx, double by) { return std::hypot(ax - bx, ay - by); };
  return std::snprintf(buf, size,
                       "%.4f,%u,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,"
                       "%u,%.2f,%.2f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,%.4f,"
                       "%.4f,%.4f,%.5f,%.4f,%.4f,%.2f",
                       step.stamp.seconds(), static_cast<unsigned>(r.flags), bit(sf::kStarted), bit(sf::kDrawn),
                       bit(sf::kMatched), bit(sf::kCorrected), bit(sf::kWarmingUp), bit(sf::kTooFewPoints),
                       bit(sf::kNotFinite), bit(sf::kNoFit), bit(sf::kNoGain), bit(sf::kTooFar), bit(sf::kUnpinned),
                       static_cast<unsigned>(r.points),
                       static_cast<double>(r.level), static_cast<double>(r.prior_level), static_cast<double>(p.x),
                       static_cast<double>(p.y), static_cast<double>(p.theta), static_cast<double>(f.x),
                       static_cast<double>(f.y), static_cast<double>(f.theta), dist(f.x, f.y, p.x, p.y), tx, ty, tyaw,
                       dist(p.x, p.y, tx, ty), dist(f.x, f.y, tx, ty), true_level);
}

}  // namespace kestrel::flight
