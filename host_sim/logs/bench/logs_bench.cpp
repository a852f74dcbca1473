// Log throughput: reading a real CARMEN log, and recording 1081-beam scans as the simulator
// does with --record.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <unistd.h>

#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/logs/carmen_writer.hpp"

namespace {

using namespace kestrel;

void BM_ReadFreiburg079(benchmark::State& state) {
  const std::string path = std::string(KESTREL_SHARED_DATA_DIR) + "/carmen/freiburg-079.log.gz";
  logs::LogRecord rec;
  int64_t scans = 0;
  for (auto _ : state) {
    logs::CarmenReader reader;
    if (!ok(reader.open(path.c_str()))) {
      state.SkipWithError("cannot open freiburg-079.log.gz");
      return;
    }
    while (ok(reader.next(rec))) ++scans;
  }
  state.SetItemsProcessed(scans);
}
BENCHMARK(BM_ReadFreiburg079)->Name("logs/read_freiburg_079")->Unit(benchmark::kMillisecond);

void BM_WriteUtm30Scan(benchmark::State& state) {
  const bool gz = state.range(0) != 0;
  const std::string path = "/tmp/kestrel-bench-" + std::to_string(::getpid()) + (gz ? ".log.gz" : ".log");
  LaserScan scan;
  scan.beam_count = 1081;
  scan.first_angle_rad = -2.35619449f;
  scan.angle_step_rad = 0.00436332313f;
  scan.max_range_mm = 30000;
  scan.scan_period = Duration::from_us(25000);
  for (std::size_t i = 0; i < scan.beam_count; ++i) scan.range_mm[i] = static_cast<uint16_t>(500 + (i * 37) % 9000);
  logs::CarmenWriter writer;
  if (!ok(writer.open(path.c_str()))) {
    state.SkipWithError("cannot create the output file");
    return;
  }
  int64_t k = 0;
  for (auto _ : state) {
    scan.stamp = TimeUs::from_us(25000 * k++);
    benchmark::DoNotOptimize(writer.write_scan(scan, Pose2d{1.0, 2.0, 0.5}));
  }
  (void)writer.close();
  std::remove(path.c_str());
  state.SetItemsProcessed(k);
}
BENCHMARK(BM_WriteUtm30Scan)->Name("logs/write_utm30_scan")->Arg(0)->Arg(1);

}  // namespace
