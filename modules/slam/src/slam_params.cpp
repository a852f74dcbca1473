#include "kestrel/slam/slam_params.hpp"


namespace kestrel::slam {

std::array<params::ParamField, kSlamParamCount> slam_param_fields(SlamParams& p) {
  return {{
      {"cell_m", &p.cell_m, 0.01f, 0.5f, "m", "map cell side"},
      {"hole_width_m", &p.hole_width_m, 0.02f, 2.0f, "m", "width of the trough drawn across each return"},
      {"clear_reach_m", &p.clear_reach_m, 0.0f, 60.0f, "m", "how far before each return its ray clears the map"},
      {"weight", &p.weight, 1.0f, 255.0f, "1/256", "how far a cell moves towards a return's profile"},
      {"draw_every_m", &p.draw_every_m, 0.0f, 10.0f, "m", "a scan is drawn after the sensor has moved this far"},
      {"draw_every_rad", &p.draw_every_rad, 0.0f, 3.2f, "rad", "...or turned this much since the last scan drawn"},
      {"draw_min_curvature", &p.draw_min_curvature, 0.0f, 1e7f, "level/m^2",
       "a scan is drawn only where the fit's curvature is at least this both ways (0: always)"},
      {"iterations", &p.iterations, 1.0f, 5000.0f, "1", "Monte Carlo candidates per scan"},
      {"sigma_xy_m", &p.sigma_xy_m, 0.001f, 2.0f, "m", "first spread of the candidates, position"},
      {"sigma_theta_rad", &p.sigma_theta_rad, 0.0f, 1.0f, "rad", "first spread of the candidates, heading"},
      {"anchor_per_m2", &p.anchor_per_m2, 0.0f, 1e5f, "level/m^2",
       "what a candidate pays for its distance from the filter's pose"},
      {"anchor_per_rad2", &p.anchor_per_rad2, 0.0f, 1e6f, "level/rad^2",
       "what a candidate pays for its turn from the filter's heading"},
      {"min_curvature", &p.min_curvature, 0.0f, 1e7f, "level/m^2",
       "flatter directions of the fit keep the filter's position"},
      {"max_points", &p.max_points, 2.0f, 2048.0f, "1", "the scan is thinned to at most this many returns"},
      {"min_points", &p.min_points, 2.0f, 2048.0f, "1", "fewer returns: the scan is neither matched nor drawn"},
      {"warmup_scans", &p.warmup_scans, 0.0f, 1e6f, "1", "the first scans only draw the map"},
      {"max_fit_level", &p.max_fit_level, 0.0f, 255.0f, "level", "a correction's mean map value must be below"},
      {"min_gain_level", &p.min_gain_level, 0.0f, 255.0f, "level", "and this much below the filter pose's"},
      {"max_correction_m", &p.max_correction_m, 0.0f, 10.0f, "m", "larger corrections are refused"},
      {"max_correction_rad", &p.max_correction_rad, 0.0f, 3.2f, "rad", "larger heading corrections are refused"},
  }};
}

Status validate(const SlamParams& p) {
  SlamParams copy = p;
  if (params::check_ranges(slam_param_fields(copy)) != Status::kOk) return Status::kInvalidArgument;
  if (p.min_points > p.max_points) return Status::kInvalidArgument;
  return Status::kOk;
}

Status load_slam_params(const char* path, SlamParams& out, params::ParamError& error) {
  return params::load_params_struct(path, out, slam_param_fields, [](const SlamParams& p) { return validate(p); },
                                    "inconsistent SLAM parameters: need min_points <= max_points", error);
}

}  // namespace kestrel::slam
