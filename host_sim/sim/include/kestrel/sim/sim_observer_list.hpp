#pragma once
// Several SimObservers behind the Simulation's one observer slot (e.g. the flight recorder and
// the CARMEN recorder of kestrel-sim). Fixed capacity, no allocation.
#include <array>

#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

class SimObserverList final : public SimObserver {
 public:
  static constexpr std::size_t kCapacity = 8;
  // False when full.
  bool add(SimObserver* o) {
    if (n_ == kCapacity || o == nullptr) return false;
    list_[n_++] = o;
    return true;
  }
  void on_scan(const LaserScan& s, const VehicleState& t) override {
    for (std::size_t i = 0; i < n_; ++i) list_[i]->on_scan(s, t);
  }
  void on_imu(const ImuSample& s) override {
    for (std::size_t i = 0; i < n_; ++i) list_[i]->on_imu(s);
  }
  void on_contact(const Contact& c) override {
    for (std::size_t i = 0; i < n_; ++i) list_[i]->on_contact(c);
  }
  void on_step(const VehicleState& t) override {
    for (std::size_t i = 0; i < n_; ++i) list_[i]->on_step(t);
  }

 private:
  std::array<SimObserver*, kCapacity> list_{};
  std::size_t n_ = 0;
};

}  // namespace kestrel::sim
