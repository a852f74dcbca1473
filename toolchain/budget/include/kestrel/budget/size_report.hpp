// The memory part of the budget report: per firmware library, code, read-only data, static RAM
// and the largest stack frames; per executable, the linked section sizes; every limit of the
// budget file checked, each excess named as a violation.
//
// Library sizes are sums over the archive's object files, so inline functions and templates
// instantiated in several objects are counted once per object (an upper bound of what the
// linker keeps after merging COMDAT groups and dropping unused objects).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "kestrel/budget/budget_file.hpp"
#include "kestrel/budget/elf_sections.hpp"
#include "kestrel/budget/manifest.hpp"
#include "kestrel/budget/stack_usage.hpp"

namespace kestrel::budget {

struct LibraryReport {
  std::string name;
  SectionSizes sizes;
  std::vector<StackFrame> frames;  // sorted, largest first
  size_t objects = 0;
  size_t missing_su = 0;  // objects without a .su file (built without -fstack-usage)
};

struct ExecutableReport {
  std::string name;
  SectionSizes sizes;
};

// Reads one static library (all members) and the .su files beside its objects.
LibraryReport measure_library(const ManifestLibrary& lib);
ExecutableReport measure_executable(const std::string& name, const std::string& path);

struct Violation {
  std::string what;  // e.g. "kestrel_core: static RAM 70000 B > limit 65536 B"
};

std::vector<Violation> check_budget(const BudgetFile& budget,
                                    const std::vector<LibraryReport>& libs,
                                    const std::vector<ExecutableReport>& exes,
                                    const std::string& firmware_exe);

void print_report(std::ostream& out, const std::string& target, const BudgetFile& budget,
                  const std::vector<LibraryReport>& libs, const std::vector<ExecutableReport>& exes,
                  size_t top_frames);

}  // namespace kestrel::budget
