// Counting executed ARM instructions: the program runs under qemu-arm with the kestrel_insn
// TCG plugin (plugin/kestrel_insn.c), which writes the count of executed guest instructions to
// a file at exit.
//
// One run counts everything: loader, libc start-up, the program's own set-up and exit. A
// per-iteration figure therefore comes from two runs that differ only in the iteration count:
//   per_iteration = (count(n2) - count(n1)) / (n2 - n1)
// which cancels every fixed cost (see per_iteration()).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kestrel::budget {

struct CountResult {
  uint64_t insns = 0;
  int exit_status = 0;  // of the emulated program
};

// Runs `emulator... -plugin PLUGIN,outfile=TMP program_args...`. When quiet, the program's
// stdout goes to /dev/null. Throws BudgetError when the run or the plugin output fails.
CountResult count_instructions(const std::vector<std::string>& emulator, const std::string& plugin,
                               const std::vector<std::string>& program_args, bool quiet);

// Difference quotient of two counts; throws BudgetError when n2 <= n1 or counts decrease.
double per_iteration(uint64_t count1, uint64_t n1, uint64_t count2, uint64_t n2);

}  // namespace kestrel::budget
