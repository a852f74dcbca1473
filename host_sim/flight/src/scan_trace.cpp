#include "kestrel/flight/scan_trace.hpp"

#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::flight {

const char* ScanTrace::header() {
  return "t_s,flags,rejected,lost,degenerate,key_scan,window_clamped,map_restarted,"
         "x,y,theta,cov_xx,cov_yy,cov_xy,cov_tt,score,overlap,points,axis_ratio,major_axis_rad,"
         "nav_t_s,nav_x,nav_y,nav_vx,nav_vy,nav_heading,nav_std_x,nav_std_y,nav_std_heading,"
         "true_x,true_y,true_yaw,true_vx,true_vy,match_err_m,match_err_theta,nav_err_m";
}

int ScanTrace::format_row(char* buf, std::size_t size, const scan_matching::ScanMatch& match, const NavState& f,
                          const sim::VehicleState* ts, const sim::VehicleState* tn) {
  namespace mf = scan_matching::match_flag;
  const PoseMeasurement2& m = match.measurement;
  const uint32_t fl = m.flags;
  auto bit = [fl](uint32_t b) { return (fl & b) != 0 ? 1 : 0; };
  const double nan = std::nan("");
  const double tx = ts ? ts->position_m.x() : nan, ty = ts ? ts->position_m.y() : nan;
  const double tyaw = ts ? ts->yaw_rad : nan;
  const double tvx = ts ? ts->velocity_mps.x() : nan, tvy = ts ? ts->velocity_mps.y() : nan;
  const bool ok = match.ok();
  const double match_err = ok && ts ? std::hypot(m.pose.x - tx, m.pose.y - ty) : nan;
  const double match_err_theta = ok && ts ? wrap_angle(static_cast<double>(m.pose.theta) - tyaw) : nan;
  const double nav_err =
      tn ? std::hypot(f.position_m.x() - tn->position_m.x(), f.position_m.y() - tn->position_m.y()) : nan;
  return std::snprintf(
      buf, size,
      "%.4f,%u,%d,%d,%d,%d,%d,%d,"
      "%.4f,%.4f,%.5f,%.4g,%.4g,%.4g,%.4g,%.4f,%.4f,%u,%.2f,%.4f,"
      "%.4f,%.4f,%.4f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,"
      "%.4f,%.4f,%.5f,%.4f,%.4f,%.4f,%.5f,%.4f",
      m.stamp.seconds(), static_cast<unsigned>(fl), bit(mf::kRejected), bit(mf::kLost), bit(mf::kDegenerate),
      bit(mf::kKeyScan), bit(mf::kWindowClamped), bit(mf::kMapRestarted), static_cast<double>(m.pose.x),
      static_cast<double>(m.pose.y), static_cast<double>(m.pose.theta), static_cast<double>(m.covariance(0, 0)),
      static_cast<double>(m.covariance(1, 1)), static_cast<double>(m.covariance(0, 1)),
      static_cast<double>(m.covariance(2, 2)), static_cast<double>(match.score), static_cast<double>(match.overlap),
      static_cast<unsigned>(match.points), static_cast<double>(match.axis_ratio),
      static_cast<double>(match.major_axis_rad), f.stamp.seconds(), static_cast<double>(f.position_m.x()),
      static_cast<double>(f.position_m.y()), static_cast<double>(f.velocity_mps.x()),
      static_cast<double>(f.velocity_mps.y()), static_cast<double>(f.heading_rad),
      static_cast<double>(f.position_std_m.x()), static_cast<double>(f.position_std_m.y()),
      static_cast<double>(f.heading_std_rad), tx, ty, tyaw, tvx, tvy, match_err, match_err_theta, nav_err);
}

}  // namespace kestrel::flight
