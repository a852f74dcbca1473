#pragma once
// Fixed-rate cooperative scheduler of the real-time loop. Each task has a period and a budget;
// at every poll the scheduler runs, in table order (the table order is the priority), each task
// whose release time has come, then releases it again one period later. It records per task
// the worst and mean execution time and the deadline misses:
//   - an overrun: a run that took longer than the task's budget;
//   - a skipped release: the task was so late that one or more whole periods passed unrun.
// Releases are timed by one TimeSource and execution by another, so the loop can run in
// lockstep on the simulator's clock (deterministic releases) while measuring real CPU time,
// or entirely on a manual clock in tests.
#include <cstddef>
#include <cstdint>

#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel {

struct TaskStats {
  uint64_t runs = 0;
  int64_t total_us = 0;
  int64_t max_us = 0;
  uint64_t overruns = 0;          // runs longer than the budget
  uint64_t skipped_releases = 0;  // periods that passed without a run
  uint64_t deadline_misses() const { return overruns + skipped_releases; }
  double mean_us() const { return runs == 0 ? 0.0 : static_cast<double>(total_us) / static_cast<double>(runs); }
};

struct TaskSpec {
  const char* name = "";
  Duration period;          // release interval
  Duration budget;          // longest acceptable run; zero means "the period"
  void (*run)(void* context, TimeUs release) = nullptr;
  void* context = nullptr;
};

class Scheduler {
 public:
  static constexpr std::size_t kMaxTasks = 16;

  Scheduler(const TimeSource& release_clock, const TimeSource& exec_clock)
      : release_clock_(release_clock), exec_clock_(exec_clock) {}

  // Adds a task first released at `first_release`. Fails on a bad spec or a full table.
  Status add(const TaskSpec& spec, TimeUs first_release);

  // Runs every task that is due now; returns the number of tasks run.
  std::size_t poll();

  // The earliest pending release, so the caller can sleep (or the simulator step) until then.
  TimeUs next_release() const;

  std::size_t task_count() const { return tasks_.size(); }
  const TaskSpec& spec(std::size_t i) const { return tasks_[i].spec; }
  const TaskStats& stats(std::size_t i) const { return tasks_[i].stats; }
  // Index of the task with this name, or task_count() if none.
  std::size_t find(const char* name) const;

 private:
  struct Task {
    TaskSpec spec;
    TimeUs next_release;
    TaskStats stats;
  };
  const TimeSource& release_clock_;
  const TimeSource& exec_clock_;
  StaticVector<Task, kMaxTasks> tasks_;
};

}  // namespace kestrel
