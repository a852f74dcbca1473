// kestrel-bench-iters: kestrel-bench with a fixed iteration count, for instruction counting.
//
// Google Benchmark 1.7 (Debian 12) picks iteration counts from wall-clock time, so two runs
// under qemu-arm would execute different amounts of work. The budget tool needs runs whose
// only difference is a known number of iterations (see insn_counter.hpp). Benchmark 1.7 sets
// a fixed count only through Benchmark::Iterations() on the registered object, and the
// BENCHMARK() macros keep those objects private; so this executable defines the registration
// function itself (the library is linked as a shared object, and an executable's definition
// takes precedence), remembers each benchmark and forwards to the library's own definition
// found with dlsym(RTLD_NEXT). main() then applies --kestrel_iterations=N to all of them.
// Benchmarks that call MinTime() cannot also take a fixed count: kestrel benchmarks don't.
#include <benchmark/benchmark.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

std::vector<benchmark::internal::Benchmark*>& registered() {
  static std::vector<benchmark::internal::Benchmark*> all;
  return all;
}

// With --kestrel_quiet nothing is printed: the console report's text depends on measured
// times and the machine's load, and formatting it would add a varying number of instructions
// to each run.
class SilentReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

}  // namespace

namespace benchmark::internal {

Benchmark* RegisterBenchmarkInternal(Benchmark* b) {
  using Fn = Benchmark* (*)(Benchmark*);
  static Fn library = reinterpret_cast<Fn>(
      dlsym(RTLD_NEXT, "_ZN9benchmark8internal25RegisterBenchmarkInternalEPNS0_9BenchmarkE"));
  if (library == nullptr) {
    std::fprintf(stderr, "kestrel-bench-iters: libbenchmark's registration not found\n");
    std::abort();
  }
  registered().push_back(b);
  return library(b);
}

}  // namespace benchmark::internal

int main(int argc, char** argv) {
  long long iterations = 0;
  bool quiet = false;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    static const char key[] = "--kestrel_iterations=";
    if (std::strncmp(argv[i], key, sizeof key - 1) == 0) {
      char* end = nullptr;
      iterations = std::strtoll(argv[i] + sizeof key - 1, &end, 10);
      if (*end != '\0' || iterations <= 0) {
        std::fprintf(stderr, "kestrel-bench-iters: bad %s\n", argv[i]);
        return 2;
      }
    } else if (std::strcmp(argv[i], "--kestrel_quiet") == 0) {
      quiet = true;
    } else {
      rest.push_back(argv[i]);
    }
  }
  if (iterations == 0) {
    std::fprintf(stderr,
                 "usage: kestrel-bench-iters --kestrel_iterations=N [--kestrel_quiet] "
                 "[benchmark flags]\n");
    return 2;
  }
  for (benchmark::internal::Benchmark* b : registered()) b->Iterations(iterations);
  int n = static_cast<int>(rest.size());
  rest.push_back(nullptr);
  benchmark::Initialize(&n, rest.data());
  if (benchmark::ReportUnrecognizedArguments(n, rest.data())) return 2;
  SilentReporter silent;
  const size_t ran =
      quiet ? benchmark::RunSpecifiedBenchmarks(&silent) : benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return ran == 0 ? 3 : 0;  // a filter matching nothing must not look like a cheap benchmark
}
