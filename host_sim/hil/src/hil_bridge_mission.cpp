#include "kestrel/hil/hil_bridge_mission.hpp"

#include <cstdio>
#include <ctime>
#include <thread>

#include "kestrel/comms/hil_messages.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::hil {
namespace {

int64_t wall_us() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

}  // namespace

std::unique_ptr<sim::Mission> make_hil_bridge(const sim::MissionOptions& options, std::string& error) {
  long port = 5760;
  double wait_s = 30;
  for (const auto& [key, value] : options.values) {
    char* end = nullptr;
    if (key == "port") {
      port = std::strtol(value.c_str(), &end, 10);
      if (end == value.c_str() || *end != '\0' || port <= 0 || port > 65535) {
        error = "port: '" + value + "' is not a TCP port";
        return nullptr;
      }
    } else if (key == "wait_s") {
      wait_s = std::strtod(value.c_str(), &end);
      // At most a day: Duration::from_s of a wilder value overflows its microseconds.
      if (end == value.c_str() || *end != '\0' || !(wait_s > 0 && wait_s <= 86400)) {
        error = "wait_s: '" + value + "' is not a number of seconds in (0, 86400]";
        return nullptr;
      }
    } else {
      error = "mission 'hil' has no option '" + key + "'";
      return nullptr;
    }
  }
  return std::make_unique<HilBridgeMission>(static_cast<uint16_t>(port), wait_s);
}

Status HilBridgeMission::start(sim::Simulation&) {
  if (listener_.listen("127.0.0.1", port_) != Status::kOk) {
    failure_ = "cannot listen on 127.0.0.1:" + std::to_string(port_);
    return Status::kIoError;
  }
  std::fprintf(stderr, "kestrel-sim: HIL bridge waiting for kestrel-fw on 127.0.0.1:%u\n", listener_.port());
  if (listener_.accept(link_, Duration::from_s(wait_s_)) != Status::kOk) {
    failure_ = "no firmware connected within " + std::to_string(wait_s_) + " s";
    return Status::kTimeout;
  }
  wall0_us_ = wall_us();
  return Status::kOk;
}

template <class Msg>
void HilBridgeMission::send(uint8_t type, const Msg& m) {
  static uint8_t payload[comms::kHilMaxPayload];
  static uint8_t frame[comms::kHilMaxPayload + comms::kHilOverhead];
  const std::size_t p = comms::encode_payload(m, payload, sizeof(payload));
  const std::size_t n = comms::hil_encode(type, payload, p, frame, sizeof(frame));
  std::size_t sent = 0;
  // The firmware reads every millisecond; a full socket buffer for long means it is gone.
  for (int tries = 0; sent < n && tries < 1000; ++tries) {
    const Result<std::size_t> w = link_.write(frame + sent, n - sent);
    if (!w.ok()) {
      disconnected_ = true;
      return;
    }
    sent += w.value();
    if (sent < n) {
      ++send_stalls_;
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }
  if (sent < n) disconnected_ = true;
  ++frames_out_;
}

void HilBridgeMission::receive(sim::Simulation& sim) {
  uint8_t buf[512];
  for (;;) {
    const Result<std::size_t> r = link_.read(buf, sizeof(buf));
    if (!r.ok()) {
      disconnected_ = true;
      return;
    }
    if (r.value() == 0) return;
    for (std::size_t i = 0; i < r.value(); ++i) {
      if (!decoder_.push(buf[i])) continue;
      ++frames_in_;
      const auto type = static_cast<comms::HilType>(decoder_.type());
      if (type == comms::HilType::kAttitudeSetpoint) {
        AttitudeSetpoint sp;
        if (comms::decode_payload(decoder_.payload(), decoder_.size(), sp) == Status::kOk) {
          sp.stamp = sim.now();  // the firmware's clock is not the simulator's
          (void)sim.flight_controller().send(sp);
        } else {
          ++bad_frames_;
        }
      } else if (type == comms::HilType::kArm) {
        bool armed = false;
        if (comms::decode_arm(decoder_.payload(), decoder_.size(), armed) == Status::kOk) {
          (void)sim.flight_controller().arm(armed);
        } else {
          ++bad_frames_;
        }
      } else {
        ++bad_frames_;
      }
    }
  }
}

sim::MissionState HilBridgeMission::tick(sim::Simulation& sim) {
  // Pace: simulated time may not run ahead of the wall clock.
  const int64_t ahead = sim.now().us - (wall_us() - wall0_us_);
  if (ahead > 0) std::this_thread::sleep_for(std::chrono::microseconds(ahead));

  static LaserScan scan;
  while (sim.laser().poll(scan) == Status::kOk) send(static_cast<uint8_t>(comms::HilType::kLaserScan), scan);
  ImuSample imu;
  while (sim.imu().poll(imu) == Status::kOk) send(static_cast<uint8_t>(comms::HilType::kImu), imu);
  AltimeterSample alt;
  while (sim.altimeter().poll(alt) == Status::kOk) send(static_cast<uint8_t>(comms::HilType::kAltitude), alt);
  FlightStatus st;
  if (sim.flight_controller().poll_status(st) == Status::kOk)
    send(static_cast<uint8_t>(comms::HilType::kFlightStatus), st);
  receive(sim);
  return disconnected_ ? sim::MissionState::kDone : sim::MissionState::kRunning;
}

void HilBridgeMission::metrics(sim::MissionMetrics& out) const {
  out.emplace_back("hil_frames_out", static_cast<double>(frames_out_));
  out.emplace_back("hil_frames_in", static_cast<double>(frames_in_));
  out.emplace_back("hil_send_stalls", static_cast<double>(send_stalls_));
  out.emplace_back("hil_bad_frames",
                   static_cast<double>(bad_frames_ + decoder_.crc_errors() + decoder_.length_errors()));
  out.emplace_back("hil_skipped_bytes", static_cast<double>(decoder_.skipped_bytes()));
}

}  // namespace kestrel::hil
