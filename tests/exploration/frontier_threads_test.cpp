// The frontier explorer's two levels on two threads, as kestrel-fw runs them on a board: the
// loop steps it on one, level 3 plans on another, and nothing is shared but the one-slot
// queues and the atomics. Under host-tsan (ThreadSanitizer) a data race fails this test.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "kestrel/exploration/frontier_explorer.hpp"
#include "frontier_worlds.hpp"

namespace kestrel::exploration {
namespace {

TEST(FrontierExplorerThreads, TheLoopAndLevel3ShareOnlyTheirQueues) {
  const test::SegmentWorld w = test_worlds::room_and_corridor();
  const test::LaserModel urg = test::LaserModel::urg04lx();
  // The scans made beforehand: the loop's thread only steps.
  std::vector<LaserScan> scans;
  for (int k = 0; k < 400; ++k) {
    const double x = 1.0 + 2.5 * k / 400.0, y = 2.0;
    scans.push_back(w.scan(urg, x, y, 0.02 * k, TimeUs::from_s(0.1 * (k + 1))));
  }
  auto ex = std::make_unique<FrontierExplorer>();
  ASSERT_EQ(ex->configure(Params{}, BeamGeometry::of(scans[0])), Status::kOk);
  std::atomic<bool> done{false};
  std::atomic<uint32_t> level3_steps{0};
  std::thread level3([&] {
    while (!done.load(std::memory_order_acquire)) {
      ex->background_step();
      level3_steps.fetch_add(1, std::memory_order_relaxed);
      std::this_thread::yield();
    }
  });
  uint32_t with_target = 0;
  GuidanceSetpoint out;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const float x = static_cast<float>(1.0 + 2.5 * k / 400.0);
    EXPECT_EQ(ex->step(test::nav_at(x, 2.0f, 0.02f * static_cast<float>(k)), scans[k], out), Status::kOk);
    with_target += ex->status().has_target ? 1 : 0;
    (void)ex->finished();
    // Level 3 plans at its own pace, which under qemu or a loaded machine is far slower than
    // the loop's steps: once a simulated two seconds the loop waits until level 3 has gone round
    // twice, so it has drawn what was offered and planned, as a board's scheduler would let it.
    // The wait ends because level 3 runs until `done`.
    if (k % 20 == 19) {
      const uint32_t seen = level3_steps.load(std::memory_order_relaxed);
      while (level3_steps.load(std::memory_order_relaxed) < seen + 2) std::this_thread::yield();
    } else {
      std::this_thread::yield();
    }
  }
  done.store(true, std::memory_order_release);
  level3.join();
  const FrontierCounters c = ex->counters();
  EXPECT_GT(level3_steps.load(), 0u);
  EXPECT_GT(c.scans_drawn, 0u);
  EXPECT_GT(c.plans, 0u);
  EXPECT_GT(c.plans_taken, 0u);
  EXPECT_GT(with_target, 0u);
  // Every step offered its scan (one a draw period): taken or dropped, and level 3 drew only
  // what it was handed.
  EXPECT_EQ(c.scans_offered + c.scans_dropped, scans.size());
  EXPECT_LE(c.scans_drawn + c.draw_errors, c.scans_offered);
  EXPECT_EQ(c.draw_errors, 0u);
}

}  // namespace
}  // namespace kestrel::exploration
