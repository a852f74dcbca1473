#pragma once
// Hardware in the loop: kestrel-sim serves its simulated devices over TCP so that kestrel-fw
// (on the host, or on a board on the network) flies the simulated vehicle through its own HAL
// (platform/linux HilClient). The simulation is paced to the wall clock, since the firmware
// runs on its real clock. Sensor data goes out as it is produced; set-points and arm commands
// come in and go to the simulated autopilot. The run ends when the firmware disconnects.
//
// Options: port=N (default 5760), wait_s=S (how long to wait for the firmware, default 30).
#include <memory>
#include <string>

#include "kestrel/comms/hil_codec.hpp"
#include "kestrel/platform/linux/tcp_link.hpp"
#include "kestrel/sim/mission.hpp"
#include "kestrel/sim/mission_registry.hpp"

namespace kestrel::hil {

class HilBridgeMission final : public sim::Mission {
 public:
  HilBridgeMission(uint16_t port, double wait_s) : port_(port), wait_s_(wait_s) {}
  const char* name() const override { return "hil"; }
  Status start(sim::Simulation& sim) override;
  sim::MissionState tick(sim::Simulation& sim) override;
  Duration tick_period() const override { return Duration::from_ms(1); }
  void metrics(sim::MissionMetrics& out) const override;
  std::string failure() const override { return failure_; }

 private:
  template <class Msg>
  void send(uint8_t type, const Msg& m);
  void receive(sim::Simulation& sim);

  uint16_t port_;
  double wait_s_;
  platform::TcpListener listener_;
  platform::TcpLink link_;
  comms::HilDecoder decoder_;
  int64_t wall0_us_ = 0;
  std::string failure_;
  uint64_t frames_out_ = 0, frames_in_ = 0, send_stalls_ = 0, bad_frames_ = 0;
  bool disconnected_ = false;
};

std::unique_ptr<sim::Mission> make_hil_bridge(const sim::MissionOptions& options, std::string& error);

}  // namespace kestrel::hil
