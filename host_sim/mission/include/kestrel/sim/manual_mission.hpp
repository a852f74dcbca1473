#pragma once
// `--mission manual`: arms the autopilot and replays a CommandScript through
// hal::FlightController, open loop. It is the simulator's own check (does the world, the
// vehicle and the sensors behave) and a way to produce logs with known motion.
#include "kestrel/sim/command_script.hpp"
#include "kestrel/sim/mission.hpp"

namespace kestrel::sim {

class ManualMission final : public Mission {
 public:
  explicit ManualMission(CommandScript script) : script_(std::move(script)) {}
  const char* name() const override { return "manual"; }
  Status start(Simulation& sim) override;
  MissionState tick(Simulation& sim) override;
  void metrics(MissionMetrics& out) const override;
  std::string failure() const override { return failure_; }

 private:
  CommandScript script_;
  std::size_t next_ = 0;
  AttitudeSetpoint current_;
  bool disarmed_ = false;
  uint32_t rejected_ = 0;
  std::string failure_;
};

}  // namespace kestrel::sim
