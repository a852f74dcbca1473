// kestrel-sysid: identifies paper 000 equation 1 from a logged simulator flight and designs
// the LQR position controller for it (paper 000 section 4). It flies an excitation command
// script open loop (the manual mission; --script FILE for another one, --waypoints for the
// closed-loop waypoints mission instead), records the set-points the autopilot applied and
// the true motion, fits the gains and offsets by least squares (control::fit_vehicle_model,
// with the attitude loop's lag identified per axis), prints them against the simulator's
// true VehicleParams, computes the LQR gains (control::design_controller; the command limits
// are the ones the stack flies with, autonomy::vehicle_controller_params()) and writes
//   OUT/controller.params   (control::load_controller_params reads it)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "kestrel/autonomy/stack_config.hpp"
#include "kestrel/cli/arg_reader.hpp"
#include "kestrel/control/controller_params.hpp"
#include "kestrel/params/param_file.hpp"
#include "kestrel/sim/command_script.hpp"
#include "kestrel/sim/config_file.hpp"
#include "kestrel/tuning/sysid.hpp"

namespace {

using namespace kestrel;

// A parameter file's error in the words every tool uses (params::describe), then `why`.
void print_param_error(const std::string& path, const params::ParamError& err, const char* why) {
  char buf[512];
  params::describe(path.c_str(), err, buf, sizeof(buf));
  std::fprintf(stderr, "kestrel-sysid: %s%s\n", buf, why);
}

struct Options {
  std::string out = "sysid-out";
  std::string script;  // path; "" = the built-in excitation flight
  std::string config;  // sim config file (vehicle.*, laser.*, imu.*, sim.*), as kestrel-sim --config
  bool waypoints = false;
  uint64_t seed = 1;
  double seconds = 0;  // 0: the script's length (manual) or 60 s (waypoints)
  double dt = 0.025;   // controller period (the UTM-30LX scan period)
  bool help = false;
};

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: kestrel-sysid [--out DIR] [--script FILE | --waypoints] [--seed N] [--seconds S] [--dt S]\n"
               "                    [--config SIM_CONFIG_FILE]\n");
}

void help() {
  usage(stdout);
  std::fputs(
      "Identifies paper 000 equation 1 (gain, offset and attitude lag per axis) from a simulated\n"
      "flight, prints it against the simulator's true values and designs the LQR controller.\n"
      "  --out DIR       writes DIR/controller.params (default sysid-out)\n"
      "  --script FILE   excitation command script flown open loop (default: the built-in one)\n"
      "  --waypoints     fly the closed-loop waypoints mission instead of a script\n"
      "  --seed N        simulator seed (default 1)\n"
      "  --seconds S     flight length (default: the script's length, or 60 s with --waypoints)\n"
      "  --dt S          controller period the gains are designed for (default 0.025, the UTM-30LX)\n"
      "  --config FILE   simulator overrides (vehicle.*, laser.*, imu.*, sim.*), as kestrel-sim --config\n"
      "  --help          this text\n"
      "Exit status: 0 done, 1 the flight, fit or output failed, 2 bad usage.\n",
      stdout);
}

// Returns "" or the first mistake, naming the option.
std::string parse_args(int argc, char** argv, Options& o) {
  cli::ArgReader args(argc, argv);
  while (args.next()) {
    if (args.is("--help") || args.is("-h")) {
      o.help = true;
    } else if (args.is("--waypoints")) {
      o.waypoints = true;
    } else if (args.is("--out")) {
      args.take(o.out);
    } else if (args.is("--config")) {
      args.take(o.config);
    } else if (args.is("--script")) {
      args.take(o.script);
    } else if (args.is("--seed")) {
      args.take_u64(o.seed);
    } else if (args.is("--seconds")) {
      args.take_double(o.seconds, 1e-3, 1e6);
    } else if (args.is("--dt")) {
      args.take_double(o.dt, 1e-4, 0.999);
    } else {
      args.unknown();
    }
  }
  return args.error();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const std::string e = parse_args(argc, argv, o); !e.empty()) {
    std::fprintf(stderr, "kestrel-sysid: %s\n", e.c_str());
    usage(stderr);
    return 2;
  }
  if (o.help) {
    help();
    return 0;
  }
  tuning::FlightSpec spec;
  spec.sim.seed = o.seed;
  if (!o.config.empty()) {
    sim::ConfigFile file;
    std::string e = file.load(o.config);
    if (e.empty()) e = spec.sim.apply(file);
    if (!e.empty()) {
      std::fprintf(stderr, "kestrel-sysid: %s\n", e.c_str());
      return 1;
    }
  }
  if (o.waypoints) {
    spec.kind = tuning::FlightKind::kWaypoints;
    spec.waypoints = tuning::arena_waypoints();
    spec.duration_s = o.seconds > 0 ? o.seconds : 60;
  } else {
    spec.kind = tuning::FlightKind::kManual;
    if (o.script.empty()) {
      spec.script_text = tuning::sysid_script_text();
    } else {
      // Read once, as kestrel-sim reads it (a directory refused); fly_and_record parses it
      // before flying and names FILE:LINE, or the file when it has no commands.
      if (const std::string e = sim::CommandScript::read_text(o.script, spec.script_text); !e.empty()) {
        std::fprintf(stderr, "kestrel-sysid: %s\n", e.c_str());
        return 1;
      }
      spec.script_name = o.script;
    }
    spec.duration_s = o.seconds > 0 ? o.seconds : 14;
  }
  tuning::FlightLog log;
  if (const std::string e = tuning::fly_and_record(spec, log); !e.empty()) {
    std::fprintf(stderr, "kestrel-sysid: %s\n", e.c_str());
    return 1;
  }
  std::printf("flight: %zu physics steps, %s\n", log.truth.size(), log.end_message.c_str());
  const tuning::SysidResult r = tuning::identify_vehicle(log);
  if (r.status != Status::kOk) {
    std::fprintf(stderr, "kestrel-sysid: the fit failed: %s (does the flight excite every axis?)\n",
                 to_string(r.status));
    return 1;
  }
  const sim::VehicleParams& t = spec.sim.vehicle;
  std::printf("equation 1 fit (%zu samples):\n", r.samples);
  std::printf("  %-7s %10s %10s %10s %10s %9s %12s %12s\n", "axis", "k fitted", "k true", "b fitted", "b true",
              "lag (s)", "rms no lag", "rms at lag");
  const char* names[4] = {"pitch", "roll", "thrust", "yaw"};
  const control::AxisModel* fitted[4] = {&r.model.pitch, &r.model.roll, &r.model.thrust, &r.model.yaw};
  const double k_true[4] = {t.k_pitch, t.k_roll, t.k_thrust, t.k_yaw};
  const double b_true[4] = {t.b_pitch, t.b_roll, t.b_thrust, t.b_yaw};
  for (int a = 0; a < 4; ++a)
    std::printf("  %-7s %10.4f %10.4f %10.4f %10.4f %9.3f %12.4f %12.4f\n", names[a], fitted[a]->k, k_true[a],
                fitted[a]->b, b_true[a], r.lag_s[a], r.rms_no_lag[a], r.rms[a]);
  std::printf("  simulator attitude lag (vehicle.attitude_tau_s): %.3f s, command delay %.3f s\n", t.attitude_tau_s,
              spec.sim.command_delay_s);

  const Result<control::ControllerParams> designed =
      control::design_controller(r.model, control::LqrWeights{}, o.dt, autonomy::vehicle_controller_params());
  if (!designed.ok()) {
    std::fprintf(stderr, "kestrel-sysid: LQR design failed: %s\n", to_string(designed.status()));
    return 1;
  }
  control::ControllerParams p = designed.value();
  const control::ControllerParams d = autonomy::vehicle_controller_params();
  std::printf("LQR gains (dt %.3f s, default weights), fitted model vs default model:\n", o.dt);
  std::printf("  gain_x_p %.4f (%.4f)  gain_x_d %.4f (%.4f)\n", p.gain_x_p, d.gain_x_p, p.gain_x_d, d.gain_x_d);
  std::printf("  gain_y_p %.4f (%.4f)  gain_y_d %.4f (%.4f)\n", p.gain_y_p, d.gain_y_p, p.gain_y_d, d.gain_y_d);
  std::printf("  gain_z_p %.4f (%.4f)  gain_z_d %.4f (%.4f)\n", p.gain_z_p, d.gain_z_p, p.gain_z_d, d.gain_z_d);
  std::printf("  gain_yaw %.4f (%.4f)  hover thrust %.4f (%.4f)\n", p.gain_yaw, d.gain_yaw, p.model.hover_thrust(),
              d.model.hover_thrust());

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  const std::string path = o.out + "/controller.params";
  params::ParamError perr;
  if (params::save_params_file(path.c_str(), control::controller_param_fields(p),
                               "controller parameters identified by kestrel-sysid", perr) != Status::kOk) {
    print_param_error(path, perr, "");
    return 1;
  }
  control::ControllerParams back;
  if (control::load_controller_params(path.c_str(), back, perr) != Status::kOk) {
    print_param_error(path, perr, " (written but does not load back)");
    return 1;
  }
  std::printf("wrote %s\n", path.c_str());
  return 0;
}
