#include "kestrel/sim/sim_clock.hpp"

#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

TimeUs SimClock::now() const { return sim_.now(); }
Status SimClock::sleep_until(TimeUs t) { return sim_.step_until(t); }

}  // namespace kestrel::sim
