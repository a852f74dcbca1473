#include "kestrel/core/scheduler.hpp"

#include <cstring>

namespace kestrel {

Status Scheduler::add(const TaskSpec& spec, TimeUs first_release) {
  if (spec.run == nullptr || spec.period.us <= 0 || spec.budget.us < 0) return Status::kInvalidArgument;
  Task t{spec, first_release, {}};
  if (t.spec.budget.us == 0) t.spec.budget = t.spec.period;
  return tasks_.push_back(t) ? Status::kOk : Status::kCapacityExceeded;
}

std::size_t Scheduler::poll() {
  std::size_t ran = 0;
  for (Task& t : tasks_) {
    const TimeUs now = release_clock_.now();
    if (now < t.next_release) continue;
    // Periods that elapsed entirely before this run are releases we never served.
    const int64_t late_periods = (now - t.next_release).us / t.spec.period.us;
    t.stats.skipped_releases += static_cast<uint64_t>(late_periods);
    const TimeUs release = t.next_release + t.spec.period * late_periods;

    const TimeUs start = exec_clock_.now();
    t.spec.run(t.spec.context, release);
    const int64_t took = (exec_clock_.now() - start).us;

    t.stats.runs += 1;
    t.stats.total_us += took;
    if (took > t.stats.max_us) t.stats.max_us = took;
    if (took > t.spec.budget.us) t.stats.overruns += 1;
    t.next_release = release + t.spec.period;
    ++ran;
  }
  return ran;
}

TimeUs Scheduler::next_release() const {
  TimeUs earliest{INT64_MAX};
  for (const Task& t : tasks_)
    if (t.next_release < earliest) earliest = t.next_release;
  return earliest;
}

std::size_t Scheduler::find(const char* name) const {
  for (std::size_t i = 0; i < tasks_.size(); ++i)
    if (std::strcmp(tasks_[i].spec.name, name) == 0) return i;
  return tasks_.size();
}

}  // namespace kestrel
