// kestrel-budget: memory and timing budget report for the cross-built firmware (DESIGN.md,
// "Budgets"). Exit status: 0 within budget, 1 a limit exceeded (each named), 2 bad input
// (unreadable or malformed file, bad command line).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "kestrel/budget/budget_file.hpp"
#include "kestrel/budget/error.hpp"
#include "kestrel/budget/insn_counter.hpp"
#include "kestrel/budget/manifest.hpp"
#include "kestrel/budget/size_report.hpp"

namespace {

using namespace kestrel::budget;

constexpr const char* kUsage =
    "usage:\n"
    "  kestrel-budget report --build DIR [--budget FILE] [--top N]\n"
    "  kestrel-budget report --manifest FILE [--budget FILE] [--top N]\n"
    "      per firmware library: code, read-only data, static RAM, largest stack frames,\n"
    "      checked against the budget file (default: the one the build tree names)\n"
    "  kestrel-budget insns --build DIR --bench NAME [--iterations N1,N2] [--budget FILE]\n"
    "      ARM instructions per iteration of kestrel-bench benchmark NAME under qemu-arm,\n"
    "      and the share of the per-scan cycle budget\n"
    "  kestrel-budget count [--plugin SO] [--emulator 'qemu-arm -L /'] -- PROGRAM ARGS...\n"
    "      instructions one run of an ARM program executes under qemu-arm\n";

struct Args {
  std::string command, build, manifest, budget, bench, plugin = KESTREL_INSN_PLUGIN;
  std::vector<std::string> emulator;
  uint64_t n1 = 10, n2 = 60;
  size_t top = 3;
  std::vector<std::string> rest;
};

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ' ') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

Args parse_args(int argc, char** argv) {
  if (argc < 2) throw BudgetError(std::string("missing command\n") + kUsage);
  Args a;
  a.command = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--") {
      for (++i; i < argc; ++i) a.rest.push_back(argv[i]);
      break;
    }
    if (i + 1 >= argc) throw BudgetError("option " + k + " needs a value\n" + kUsage);
    const std::string v = argv[++i];
    if (k == "--build") {
      a.build = v;
    } else if (k == "--manifest") {
      a.manifest = v;
    } else if (k == "--budget") {
      a.budget = v;
    } else if (k == "--bench") {
      a.bench = v;
    } else if (k == "--plugin") {
      a.plugin = v;
    } else if (k == "--emulator") {
      a.emulator = split_words(v);
    } else if (k == "--top") {
      a.top = static_cast<size_t>(parse_count(v, "--top"));
    } else if (k == "--iterations") {
      const size_t comma = v.find(',');
      if (comma == std::string::npos) throw BudgetError("--iterations takes N1,N2");
      a.n1 = parse_count(v.substr(0, comma), "--iterations");
      a.n2 = parse_count(v.substr(comma + 1), "--iterations");
      if (a.n1 == 0 || a.n2 <= a.n1) throw BudgetError("--iterations needs 0 < N1 < N2");
    } else {
      throw BudgetError("unknown option " + k + "\n" + kUsage);
    }
  }
  return a;
}

Manifest manifest_of(const Args& a) {
  if (!a.manifest.empty()) return load_manifest(a.manifest);
  if (a.build.empty()) throw BudgetError("give --build DIR (e.g. build/overo) or --manifest FILE");
  return load_manifest(a.build + "/kestrel-budget-manifest.txt");
}

BudgetFile budget_of(const Args& a, const Manifest& m) {
  const std::string path = a.budget.empty() ? m.budget_file : a.budget;
  if (path.empty()) throw BudgetError(m.path + ": names no budget file; pass --budget FILE");
  return load_budget_file(path);
}

// Missing inputs mean the ARM tree was configured but not built: say how to build them.
void require_built(const Manifest& m, const std::string& path) {
  if (access(path.c_str(), R_OK) != 0) {
    const std::string dir = m.path.substr(0, m.path.rfind('/'));
    throw BudgetError(path + " is missing; build it first: cmake --build " + dir +
                      " --target kestrel-budget-inputs");
  }
}

int run_report(const Args& a) {
  const Manifest m = manifest_of(a);
  const BudgetFile budget = budget_of(a, m);
  for (const ManifestLibrary& lib : m.libraries) require_built(m, lib.archive);
  for (const auto& exe : m.executables) require_built(m, exe.second);
  std::vector<LibraryReport> libs;
  for (const ManifestLibrary& lib : m.libraries) libs.push_back(measure_library(lib));
  std::vector<ExecutableReport> exes;
  for (const auto& [name, path] : m.executables) exes.push_back(measure_executable(name, path));
  print_report(std::cout, m.target, budget, libs, exes, a.top);
  if (budget.target != m.target) {
    std::cout << "\nnote: budget file is for '" << budget.target << "', build tree is '" << m.target
              << "'\n";
  }
  for (const auto& [name, limits] : budget.libraries) {
    bool built = false;
    for (const LibraryReport& lib : libs) built = built || lib.name == name;
    if (!built) std::cout << "note: budget file lists '" << name << "', not in this build\n";
  }
  const std::vector<Violation> v = check_budget(budget, libs, exes, "kestrel-fw");
  if (v.empty()) {
    std::cout << "\nwithin budget (" << budget.target << ")\n";
    return 0;
  }
  std::cout << "\n";
  for (const Violation& x : v) std::cout << "BUDGET VIOLATION: " << x.what << "\n";
  return 1;
}

std::vector<std::string> default_emulator() { return {"qemu-arm", "-L", "/"}; }

int run_count(const Args& a) {
  const std::vector<std::string> emu = a.emulator.empty() ? default_emulator() : a.emulator;
  const CountResult r = count_instructions(emu, a.plugin, a.rest, false);
  std::cout << "instructions: " << r.insns << "\n";
  if (r.exit_status != 0) {
    std::cerr << "kestrel-budget: the program exited with status " << r.exit_status << "\n";
    return 1;
  }
  return 0;
}

int run_insns(const Args& a) {
  if (a.bench.empty()) throw BudgetError("insns needs --bench NAME (e.g. core/fixed_mac_1024)");
  const Manifest m = manifest_of(a);
  const BudgetFile budget = budget_of(a, m);
  if (m.bench_iters.empty()) throw BudgetError(m.path + ": no bench_iters runner listed");
  require_built(m, m.bench_iters);
  const std::vector<std::string> emu = m.emulator.empty() ? default_emulator() : m.emulator;
  // The name is matched exactly: a regex anchored at both ends, special characters escaped.
  std::string re = "^";
  for (char c : a.bench) {
    if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) re += '\\';
    re += c;
  }
  re += "(/iterations:[0-9]+)?$";  // a fixed count adds this suffix to the name
  const auto run = [&](uint64_t n) {
    const CountResult r =
        count_instructions(emu, a.plugin,
                           {m.bench_iters, "--kestrel_iterations=" + std::to_string(n),
                            "--kestrel_quiet", "--benchmark_filter=" + re},
                           true);
    if (r.exit_status == 3)
      throw BudgetError("no benchmark named '" + a.bench + "' in kestrel-bench");
    if (r.exit_status != 0) {
      throw BudgetError(m.bench_iters + " exited with status " + std::to_string(r.exit_status) +
                        " (build it: cmake --build <dir> --target kestrel-bench-iters)");
    }
    return r.insns;
  };
  const uint64_t c1 = run(a.n1);
  const uint64_t c2 = run(a.n2);
  if (c1 == c2) throw BudgetError("no benchmark named '" + a.bench + "' ran (same count twice)");
  const double per = per_iteration(c1, a.n1, c2, a.n2);
  const double share = per / static_cast<double>(budget.loop_cycles);
  const bool verdex = m.target == "verdex";
  std::cout << std::fixed << std::setprecision(0);
  std::cout << "benchmark " << a.bench << " on " << m.target << " (qemu-arm, kestrel_insn plugin)\n"
            << "  run with " << a.n1 << " iterations: " << c1 << " instructions\n"
            << "  run with " << a.n2 << " iterations: " << c2 << " instructions\n"
            << "  instructions per iteration: " << per << "\n"
            << "  cycles per iteration at IPC = 1: " << per << " = " << std::setprecision(2)
            << per / static_cast<double>(budget.clock_mhz) << " us at " << budget.clock_mhz
            << " MHz = " << 100.0 * share << " % of the per-scan loop budget ("
            << budget.loop_cycles << " cycles)\n"
            << "  IPC = 1 is an approximation: qemu counts instructions, not cycles. "
            << (verdex ? "The XScale issues at most one instruction per cycle, so cycles >= "
                         "instructions; cache misses, multiplies and soft-float calls add more."
                       : "The Cortex-A8 can dual-issue (fewer cycles) but stalls on cache "
                         "misses, NEON/VFP hand-offs and branches (more cycles).")
            << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse_args(argc, argv);
    if (a.command == "report") return run_report(a);
    if (a.command == "insns") return run_insns(a);
    if (a.command == "count") return run_count(a);
    if (a.command == "--help" || a.command == "help") {
      std::cout << kUsage;
      return 0;
    }
    throw BudgetError("unknown command '" + a.command + "'\n" + kUsage);
  } catch (const BudgetError& e) {
    std::cerr << "kestrel-budget: error: " << e.what() << "\n";
    return 2;
  }
}
