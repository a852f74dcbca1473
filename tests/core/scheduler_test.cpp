#include "kestrel/core/scheduler.hpp"

#include <gtest/gtest.h>

namespace kestrel {
namespace {

// A task that "takes" a scripted amount of time by advancing the execution clock.
struct FakeWork {
  ManualTimeSource* exec = nullptr;
  Duration cost;
  int runs = 0;
  TimeUs last_release;
  static void run(void* ctx, TimeUs release) {
    auto* w = static_cast<FakeWork*>(ctx);
    w->exec->advance(w->cost);
    w->last_release = release;
    ++w->runs;
  }
};

TEST(Scheduler, RunsTasksAtTheirRatesOnASimulatedClock) {
  ManualTimeSource sim, exec;
  Scheduler s(sim, exec);
  FakeWork imu{&exec, Duration::from_us(100)}, laser{&exec, Duration::from_us(2000)};
  ASSERT_EQ(s.add({"imu", Duration::from_ms(5), {}, &FakeWork::run, &imu}, TimeUs{}), Status::kOk);
  ASSERT_EQ(s.add({"laser", Duration::from_ms(25), Duration::from_ms(12), &FakeWork::run, &laser}, TimeUs{}),
            Status::kOk);
  while (sim.now() < TimeUs::from_s(1.0)) {
    s.poll();
    sim.set(s.next_release());
  }
  EXPECT_EQ(imu.runs, 200);
  EXPECT_EQ(laser.runs, 40);
  const TaskStats& st = s.stats(s.find("laser"));
  EXPECT_EQ(st.runs, 40u);
  EXPECT_EQ(st.max_us, 2000);
  EXPECT_DOUBLE_EQ(st.mean_us(), 2000.0);
  EXPECT_EQ(st.deadline_misses(), 0u);
}

TEST(Scheduler, CountsOverrunsAgainstTheBudget) {
  ManualTimeSource sim, exec;
  Scheduler s(sim, exec);
  FakeWork w{&exec, Duration::from_us(3000)};
  ASSERT_EQ(s.add({"slow", Duration::from_ms(10), Duration::from_ms(2), &FakeWork::run, &w}, TimeUs{}), Status::kOk);
  for (int i = 0; i < 5; ++i) {
    s.poll();
    sim.set(s.next_release());
  }
  EXPECT_EQ(s.stats(0).overruns, 5u);
  EXPECT_EQ(s.stats(0).skipped_releases, 0u);
}

TEST(Scheduler, CountsSkippedReleasesWhenLateAndKeepsThePhase) {
  ManualTimeSource sim, exec;
  Scheduler s(sim, exec);
  FakeWork w{&exec, Duration::from_us(10)};
  ASSERT_EQ(s.add({"t", Duration::from_ms(10), {}, &FakeWork::run, &w}, TimeUs{}), Status::kOk);
  s.poll();                               // release at 0
  sim.set(TimeUs::from_us(35'000));       // releases at 10 and 20 ms were missed
  s.poll();
  EXPECT_EQ(s.stats(0).skipped_releases, 2u);
  EXPECT_EQ(w.last_release.us, 30'000);   // served the newest due release, on the grid
  EXPECT_EQ(s.next_release().us, 40'000);
}

TEST(Scheduler, RejectsBadSpecsAndAFullTable) {
  ManualTimeSource sim, exec;
  Scheduler s(sim, exec);
  FakeWork w{&exec, {}};
  EXPECT_EQ(s.add({"no-fn", Duration::from_ms(1), {}, nullptr, nullptr}, {}), Status::kInvalidArgument);
  EXPECT_EQ(s.add({"zero", Duration{}, {}, &FakeWork::run, &w}, {}), Status::kInvalidArgument);
  for (std::size_t i = 0; i < Scheduler::kMaxTasks; ++i)
    EXPECT_EQ(s.add({"t", Duration::from_ms(1), {}, &FakeWork::run, &w}, {}), Status::kOk);
  EXPECT_EQ(s.add({"t", Duration::from_ms(1), {}, &FakeWork::run, &w}, {}), Status::kCapacityExceeded);
}

}  // namespace
}  // namespace kestrel
