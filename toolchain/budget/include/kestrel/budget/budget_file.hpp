// The checked-in budget files (toolchain/budget-<target>.txt): a line-based format meant to be
// read and edited by people. '#' starts a comment. Lines:
//   target NAME                     which build this file is for (overo, verdex)
//   clock_mhz N                     CPU clock, for turning cycles into time
//   loop_cycles N[k|M]              real-time loop budget per scan, in CPU cycles
//   firmware_ram N[KiB|MiB]         static RAM (.data + .bss) of the whole firmware
//   default   code N rodata N ram N stack N    limits for every library not listed
//   library NAME code N rodata N ram N stack N limits for one library (missing keys: default)
// Sizes take B, KiB or MiB (powers of two); counts take k or M (powers of ten). Anything else
// is an error with the file name and line number.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace kestrel::budget {

struct LibraryLimits {
  std::optional<uint64_t> code, rodata, ram, stack;
};

struct BudgetFile {
  std::string target;
  uint64_t clock_mhz = 0;
  uint64_t loop_cycles = 0;
  std::optional<uint64_t> firmware_ram;
  LibraryLimits defaults;
  std::map<std::string, LibraryLimits> libraries;

  // The effective limits of a library: its own line, then the default line.
  LibraryLimits limits_for(const std::string& library) const;
};

BudgetFile parse_budget_file(std::string_view text, const std::string& what);
BudgetFile load_budget_file(const std::string& path);

// "64KiB" -> 65536, "9M" -> 9000000; throws BudgetError(what + message) when malformed.
uint64_t parse_size(std::string_view token, const std::string& what);
uint64_t parse_count(std::string_view token, const std::string& what);

}  // namespace kestrel::budget
