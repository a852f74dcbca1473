// kestrel-fw: the firmware application for a Linux board (Overo, Verdex) or the host.
//
//   kestrel-fw --hil HOST:PORT [--laser urg04lx|utm30lx] [--mission hover|explore] [options]
//       every device through the simulator's HIL bridge (kestrel-sim --mission hil)
//   kestrel-fw --hokuyo /dev/ttyACM0 --autopilot /dev/ttyS2 [--laser ...] [options]
//       the Hokuyo on its own serial port (SCIP 2.0), IMU, altimeter and attitude autopilot
//       through an autopilot-side bridge speaking the HIL framing on a serial port
//
// Start-up (parse, open devices, build the stack) may allocate; then the stack is armed and
// the loop runs on the board's monotonic clock: pump the links, run due tasks, sleep until
// the next release. The scan matcher's map rebuild runs on its own thread (level 3), so the
// loop never waits for it. Exit status: 0 after the mission lands, 1 on a device failure,
// 2 for a usage error.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "kestrel/autonomy/autonomy_stack.hpp"
#include "kestrel/control/controller_params.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/estimation/nav_filter.hpp"
#include "kestrel/platform/linux/hil_client.hpp"
#include "kestrel/platform/linux/hokuyo_scip.hpp"
#include "kestrel/platform/linux/linux_clock.hpp"
#include "kestrel/platform/linux/serial_port.hpp"
#include "kestrel/platform/linux/tcp_link.hpp"

namespace {

using namespace kestrel;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }

void print_param_error(const std::string& path, const params::ParamError& err) {
  char buf[512];
  params::describe(path.c_str(), err, buf, sizeof(buf));
  std::fprintf(stderr, "kestrel-fw: %s\n", buf);
}

struct Options {
  std::string hil;         // HOST:PORT
  std::string hil_host;    // its parts, checked by parse()
  int hil_port = 0;
  std::string hokuyo;      // serial device
  std::string autopilot;   // serial device
  int baud = 115200;
  std::string laser = "utm30lx";
  std::string mission = "hover";
  std::string explorer = "blend";
  std::string ekf_file, controller_file;
  std::string slam = "laser";  // on, off, or the laser's default
  double hover_s = 60;
  double explore_s = 600;  // the mission's explore_time_limit_s
  double max_s = 900;
};

constexpr const char* kUsage =
    "usage: kestrel-fw (--hil HOST:PORT | --hokuyo DEV --autopilot DEV [--baud N])\n"
    "                  [--laser utm30lx|urg04lx] [--mission hover|explore] [--explorer blend|wallfollow|srt|frontier]\n"
    "                  [--hover-s S] [--explore-s S] [--max-s S] [--ekf FILE] [--controller FILE] [--slam on|off]\n";

int usage(const char* why) {
  std::fprintf(stderr, "kestrel-fw: %s\n%s", why, kUsage);
  return 2;
}

int help() {
  std::fputs(kUsage, stdout);
  std::fputs(
      "The autonomy stack on a Linux board: the devices are a Hokuyo (SCIP 2.0) and an autopilot\n"
      "on serial ports, or a simulator serving them over TCP (kestrel-sim --mission hil).\n"
      "  --hil HOST:PORT    devices from kestrel-sim --mission hil\n"
      "  --hokuyo DEV       the laser's serial device; --autopilot DEV the autopilot's; --baud N (115200)\n"
      "  --laser L          the laser model: utm30lx (default) or urg04lx\n"
      "  --mission M        hover (take off, hover --hover-s seconds (60), land; default) or explore\n"
      "  --explorer E       blend (default), wallfollow, srt or frontier, for --mission explore\n"
      "  --explore-s S      explore at most S seconds (default 600), then fly home and land\n"
      "  --max-s S          stop after S seconds (default 900; at most 1e6, as --hover-s)\n"
      "  --ekf FILE         EKF parameter file (kestrel-tune-ekf writes one), over the laser's defaults\n"
      "  --controller FILE  controller parameter file (kestrel-sysid writes one)\n"
      "  --slam on|off      the compact SLAM at level 3 (default: on with the urg04lx, off with the utm30lx)\n"
      "  --help             this text\n"
      "Exit status 2 for a usage error.\n",
      stdout);
  return 0;
}

constexpr int kMaxBaud = 4000000;

// The whole of `s` as a decimal integer in [lo, hi]. Strict, unlike atoi, which took "5801x"
// as port 5801 (and strtod, which took a baud of "0.5" as 0).
bool parse_whole(const std::string& s, int lo, int hi, int& out) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  const long v = std::strtol(s.c_str(), nullptr, 10);  // at most 9 digits: no overflow
  if (v < lo || v > hi) return false;
  out = static_cast<int>(v);
  return true;
}

bool parse(int argc, char** argv, Options& o, std::string& err) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc) {
        err = a + " needs a value";
        return false;
      }
      out = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--hil") {
      if (!value(o.hil)) return false;
    } else if (a == "--hokuyo") {
      if (!value(o.hokuyo)) return false;
    } else if (a == "--autopilot") {
      if (!value(o.autopilot)) return false;
    } else if (a == "--laser") {
      if (!value(o.laser)) return false;
      if (o.laser != "utm30lx" && o.laser != "urg04lx") return err = "unknown laser '" + o.laser + "'", false;
    } else if (a == "--mission") {
      if (!value(o.mission)) return false;
      if (o.mission != "hover" && o.mission != "explore") return err = "unknown mission '" + o.mission + "'", false;
    } else if (a == "--explorer") {
      if (!value(o.explorer)) return false;
    } else if (a == "--ekf") {
      if (!value(o.ekf_file)) return false;
    } else if (a == "--controller") {
      if (!value(o.controller_file)) return false;
    } else if (a == "--slam") {
      if (!value(o.slam)) return false;
      if (o.slam != "on" && o.slam != "off") return err = "--slam: expected on or off, got '" + o.slam + "'", false;
    } else if (a == "--baud") {
      if (!value(v)) return false;
      if (!parse_whole(v, 1, kMaxBaud, o.baud)) return err = a + ": '" + v + "' is not a whole number of baud", false;
    } else if (a == "--hover-s" || a == "--explore-s" || a == "--max-s") {
      if (!value(v)) return false;
      char* end = nullptr;
      const double d = std::strtod(v.c_str(), &end);
      // Bounded (NaN-safe): --max-s inf or 1e13 overflowed Duration and the run stopped at once.
      if (end == v.c_str() || *end != '\0' || !(d > 0 && d <= kMaxRunSeconds))
        return err = a + ": '" + v + "' is not a number of seconds in (0, 1e6]", false;
      if (a == "--hover-s") o.hover_s = d;
      if (a == "--explore-s") o.explore_s = d;
      if (a == "--max-s") o.max_s = d;
    } else {
      err = "unknown option '" + a + "'";
      return false;
    }
  }
  if (o.hil.empty() == (o.hokuyo.empty() && o.autopilot.empty())) {
    err = "give either --hil HOST:PORT or --hokuyo DEV and --autopilot DEV";
    return false;
  }
  if (o.hil.empty() && (o.hokuyo.empty() || o.autopilot.empty())) {
    err = "--hokuyo and --autopilot go together";
    return false;
  }
  if (!o.hil.empty()) {
    const std::size_t colon = o.hil.rfind(':');
    if (colon == std::string::npos || colon == 0) return err = "--hil expects HOST:PORT, got '" + o.hil + "'", false;
    if (!parse_whole(o.hil.substr(colon + 1), 1, 65535, o.hil_port))
      return err = "--hil: '" + o.hil.substr(colon + 1) + "' is not a port (1 to 65535)", false;
    o.hil_host = o.hil.substr(0, colon);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return help();
  Options opt;
  std::string err;
  if (!parse(argc, argv, opt, err)) return usage(err.c_str());

  autonomy::StackConfig cfg;
  cfg.mission_kind = opt.mission == "explore" ? mission::MissionKind::kExplore : mission::MissionKind::kHover;
  cfg.mission.hover_duration_s = static_cast<float>(opt.hover_s);
  cfg.mission.explore_time_limit_s = static_cast<float>(opt.explore_s);
  const Result<exploration::ExplorerKind> kind = exploration::parse_explorer_kind(opt.explorer.c_str());
  if (!kind.ok()) return usage(("unknown explorer '" + opt.explorer + "'").c_str());
  cfg.explorer_kind = kind.value();
  const platform::HokuyoModel model =
      opt.laser == "urg04lx" ? platform::HokuyoModel::urg04lx() : platform::HokuyoModel::utm30lx();
  cfg.ekf = autonomy::vehicle_ekf_params(model.max_range_mm);  // --ekf FILE loads over these
  cfg.slam_enabled = opt.slam == "laser" ? autonomy::vehicle_slam_enabled(model.max_range_mm) : opt.slam == "on";
  params::ParamError perr;
  if (!opt.ekf_file.empty() && estimation::load_ekf_params(opt.ekf_file.c_str(), cfg.ekf, perr) != Status::kOk) {
    print_param_error(opt.ekf_file, perr);
    return 2;
  }
  if (!opt.controller_file.empty() &&
      control::load_controller_params(opt.controller_file.c_str(), cfg.controller, perr) != Status::kOk) {
    print_param_error(opt.controller_file, perr);
    return 2;
  }

  static platform::LinuxClock clock;

  // Devices: every object lives for the whole run and is created before arming.
  static platform::TcpLink tcp;
  static platform::SerialPort hokuyo_port, autopilot_port;
  hal::Link* autopilot_link = nullptr;
  if (!opt.hil.empty()) {
    const Status s = tcp.connect(opt.hil_host.c_str(), static_cast<uint16_t>(opt.hil_port), Duration::from_s(5));
    if (s != Status::kOk) {
      std::fprintf(stderr, "kestrel-fw: cannot connect to the HIL bridge at %s: %s\n", opt.hil.c_str(), to_string(s));
      return 1;
    }
    autopilot_link = &tcp;
  } else {
    if (hokuyo_port.open(opt.hokuyo.c_str(), opt.baud) != Status::kOk) {
      std::fprintf(stderr, "kestrel-fw: cannot open the Hokuyo at %s\n", opt.hokuyo.c_str());
      return 1;
    }
    if (autopilot_port.open(opt.autopilot.c_str(), opt.baud) != Status::kOk) {
      std::fprintf(stderr, "kestrel-fw: cannot open the autopilot bridge at %s\n", opt.autopilot.c_str());
      return 1;
    }
    autopilot_link = &autopilot_port;
  }
  static platform::HilClient bridge(*autopilot_link, clock, model.geometry(), Duration::from_ms(5));
  static platform::HokuyoScip hokuyo(hokuyo_port, clock, model);
  hal::LaserScanner* laser = &bridge;
  if (opt.hil.empty()) {
    if (hokuyo.start() != Status::kOk) {
      std::fprintf(stderr, "kestrel-fw: the Hokuyo did not take the scan request\n");
      return 1;
    }
    laser = &hokuyo;
  }

  const autonomy::Devices devices{clock, *laser, bridge, &bridge, bridge};
  // The one large allocation, before arming: maps, filter history, explorer trees.
  auto stack = std::make_unique<autonomy::AutonomyStack>(devices, clock);
  std::fprintf(stderr, "kestrel-fw: autonomy stack: %zu bytes allocated at start-up\n",
               sizeof(autonomy::AutonomyStack));
  if (stack->configure(cfg) != Status::kOk) {
    std::fprintf(stderr, "kestrel-fw: configuration rejected: %s\n", stack->configure_error());
    return 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  // Level 3 on its own thread: it only ever touches the scan matcher's idle map buffer and the
  // compact SLAM, which the scan task reaches through one-slot mailboxes (autonomy_stack.hpp).
  std::atomic<bool> run_background{true};
  std::thread background([&] {
    while (run_background.load()) {
      stack->background_step();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });

  int rc = 0;
  if (stack->start() != Status::kOk) {
    std::fprintf(stderr, "kestrel-fw: the loop could not start\n");
    rc = 1;
  }
  const TimeUs t_start = clock.now();
  const TimeUs t_end = t_start + Duration::from_s(opt.max_s);
  while (rc == 0 && !g_stop.load() && !stack->finished() && clock.now() < t_end) {
    if (bridge.pump() == Status::kClosed) {
      std::fprintf(stderr, "kestrel-fw: the autopilot link closed\n");
      rc = 1;
      break;
    }
    if (opt.hil.empty() && hokuyo.pump() == Status::kClosed) {
      std::fprintf(stderr, "kestrel-fw: the Hokuyo link closed\n");
      rc = 1;
      break;
    }
    stack->poll();
    // Sleep until the next release, but wake at least every millisecond to read the links.
    const TimeUs wake = std::min(stack->next_release(), clock.now() + Duration::from_ms(1));
    (void)clock.sleep_until(wake);
  }
  run_background.store(false);
  background.join();

  const Scheduler& s = stack->scheduler();
  std::fprintf(stderr, "kestrel-fw: mission %s, phase %s; scans %u matched %u; silences imu %u laser %u\n",
               stack->finished() ? "finished" : "stopped", mission::to_string(stack->mission().phase()),
               stack->counters().scans, stack->counters().scans_matched, stack->silences().imu,
               stack->silences().scan);
  // The mission's account: when each phase began, from the loop's start on the mission's own
  // clock (a stalled loop counts at most 1 s a step there), and how the flight
  // home went (a landing soon after return began, not at home, is a flight home that stalled).
  const mission::MissionController& mission = stack->mission();
  std::fprintf(stderr, "kestrel-fw: phases");
  for (std::size_t i = 0; i < mission::kPhaseCount; ++i) {
    const auto phase = static_cast<mission::Phase>(i);
    TimeUs at;
    if (mission.first_entered(phase, at))
      std::fprintf(stderr, " %s %.1f s", mission::to_string(phase), (at - t_start).seconds());
  }
  std::fprintf(stderr, "; returned home %s, shortcuts %u, realignments %u, home fixes %u (refused %u)\n",
               mission.returned_home() ? "yes" : "no", mission.shortcuts(), mission.realignments(),
               stack->counters().home_fixes, stack->counters().home_fixes_refused);
  // The link's health, for a bench test: damaged frames and bytes lost between frames.
  const platform::HilCounters& link = bridge.counters();
  std::fprintf(stderr,
               "kestrel-fw: link frames %u, bad CRC or length %u, skipped bytes %u, malformed %u, bad stamps %u\n",
               link.frames, link.crc_errors, link.skipped_bytes, link.malformed, link.bad_stamps);
  // The filter's counts: whether it refused input (and why) or drifted on good input.
  // The compact SLAM's counts (zero when it is off), read after level 3's thread has joined.
  const slam::SlamCounters& sc = stack->slam().counters();
  std::fprintf(stderr, "kestrel-fw: slam %s, scans %u corrections %u\n", cfg.slam_enabled ? "on" : "off", sc.scans,
               sc.corrections);
  std::fprintf(stderr, "kestrel-fw: filter");
  const estimation::NavFilterCounters& nav = stack->filter().counters();
  for (const estimation::NavFilterCounterField& f : estimation::kNavFilterCounterFields)
    std::fprintf(stderr, " %s %u", f.name, nav.*f.member);
  std::fprintf(stderr, "\n");
  for (std::size_t i = 0; i < s.task_count(); ++i)
    std::fprintf(stderr, "  task %-10s runs %8llu  mean %8.1f us  max %8lld us  misses %llu\n", s.spec(i).name,
                 static_cast<unsigned long long>(s.stats(i).runs), s.stats(i).mean_us(),
                 static_cast<long long>(s.stats(i).max_us),
                 static_cast<unsigned long long>(s.stats(i).deadline_misses()));
  return rc;
}
