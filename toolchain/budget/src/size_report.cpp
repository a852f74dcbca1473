#include "kestrel/budget/size_report.hpp"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <tuple>

#include "kestrel/budget/ar_archive.hpp"
#include "kestrel/budget/error.hpp"

namespace kestrel::budget {
namespace {

std::string kib(uint64_t bytes) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << static_cast<double>(bytes) / 1024.0;
  return s.str();
}

std::string limit_text(const std::optional<uint64_t>& l) { return l ? kib(*l) : "-"; }

void check(std::vector<Violation>& out, const std::string& who, const char* what, uint64_t value,
           const std::optional<uint64_t>& limit) {
  if (limit && value > *limit) {
    out.push_back({who + ": " + what + " " + std::to_string(value) + " B > limit " +
                   std::to_string(*limit) + " B"});
  }
}

}  // namespace

LibraryReport measure_library(const ManifestLibrary& lib) {
  LibraryReport r;
  r.name = lib.name;
  const std::vector<uint8_t> image = read_file_bytes(lib.archive);
  for (const ArMember& m : parse_ar(image, lib.archive)) {
    r.sizes += parse_elf(m.bytes, lib.archive + "(" + m.name + ")").sizes;
    ++r.objects;
  }
  for (const std::string& obj : lib.objects) {
    const std::string su = stack_usage_path(obj);
    std::ifstream in(su);
    if (!in) {
      ++r.missing_su;
      continue;
    }
    std::stringstream text;
    text << in.rdbuf();
    for (StackFrame& f : parse_stack_usage(text.str(), su)) r.frames.push_back(std::move(f));
  }
  // Headers' inline functions appear in several .su files: keep each location once.
  std::sort(r.frames.begin(), r.frames.end(), [](const StackFrame& a, const StackFrame& b) {
    if (a.bytes != b.bytes) return a.bytes > b.bytes;
    return std::tie(a.location, a.function) < std::tie(b.location, b.function);
  });
  r.frames.erase(std::unique(r.frames.begin(), r.frames.end(),
                             [](const StackFrame& a, const StackFrame& b) {
                               return a.bytes == b.bytes && a.location == b.location &&
                                      a.function == b.function;
                             }),
                 r.frames.end());
  return r;
}

ExecutableReport measure_executable(const std::string& name, const std::string& path) {
  const std::vector<uint8_t> image = read_file_bytes(path);
  return {name, parse_elf(image, path).sizes};
}

std::vector<Violation> check_budget(const BudgetFile& budget,
                                    const std::vector<LibraryReport>& libs,
                                    const std::vector<ExecutableReport>& exes,
                                    const std::string& firmware_exe) {
  std::vector<Violation> v;
  uint64_t ram_sum = 0;
  for (const LibraryReport& lib : libs) {
    const LibraryLimits l = budget.limits_for(lib.name);
    check(v, lib.name, "code", lib.sizes.code, l.code);
    check(v, lib.name, "read-only data", lib.sizes.rodata, l.rodata);
    check(v, lib.name, "static RAM", lib.sizes.ram(), l.ram);
    if (!lib.frames.empty()) {
      check(v, lib.name, ("stack frame of " + lib.frames.front().function).c_str(),
            lib.frames.front().bytes, l.stack);
    }
    for (const StackFrame& f : lib.frames) {
      if (f.dynamic) v.push_back({lib.name + ": unbounded dynamic stack frame in " + f.function});
    }
    ram_sum += lib.sizes.ram();
  }
  // The linked firmware, when the build has it, is the true figure; otherwise the sum over
  // the libraries is an upper bound of it.
  uint64_t firmware_ram = ram_sum;
  std::string firmware_what = "firmware static RAM (sum of libraries)";
  for (const ExecutableReport& e : exes) {
    if (e.name == firmware_exe) {
      firmware_ram = e.sizes.ram();
      firmware_what = "firmware static RAM (" + e.name + ")";
    }
  }
  check(v, budget.target, firmware_what.c_str(), firmware_ram, budget.firmware_ram);
  return v;
}

void print_report(std::ostream& out, const std::string& target, const BudgetFile& budget,
                  const std::vector<LibraryReport>& libs, const std::vector<ExecutableReport>& exes,
                  size_t top_frames) {
  out << "kestrel-budget: target " << target << " (sizes in KiB; limit in brackets)\n";
  out << std::left << std::setw(28) << "library" << std::right << std::setw(18) << "code"
      << std::setw(18) << "rodata" << std::setw(18) << "RAM(data+bss)" << std::setw(18)
      << "max stack frame"
      << "\n";
  SectionSizes total;
  for (const LibraryReport& lib : libs) {
    const LibraryLimits l = budget.limits_for(lib.name);
    const auto cell = [](uint64_t v, const std::optional<uint64_t>& lim) {
      return kib(v) + " [" + limit_text(lim) + "]";
    };
    const uint64_t frame = lib.frames.empty() ? 0 : lib.frames.front().bytes;
    out << std::left << std::setw(28) << lib.name << std::right << std::setw(18)
        << cell(lib.sizes.code, l.code) << std::setw(18) << cell(lib.sizes.rodata, l.rodata)
        << std::setw(18) << cell(lib.sizes.ram(), l.ram) << std::setw(18)
        << (std::to_string(frame) + " B [" + (l.stack ? std::to_string(*l.stack) : "-") + "]")
        << "\n";
    total += lib.sizes;
  }
  out << std::left << std::setw(28) << "all firmware libraries" << std::right << std::setw(18)
      << kib(total.code) << std::setw(18) << kib(total.rodata) << std::setw(18)
      << (kib(total.ram()) + " [" + limit_text(budget.firmware_ram) + "]") << "\n";
  out << "  (.data " << total.data << " B, .bss " << total.bss
      << " B; library sums count inline/template code once per object: an upper bound)\n";
  for (const ExecutableReport& e : exes) {
    out << "executable " << e.name << ": code " << kib(e.sizes.code) << " KiB, rodata "
        << kib(e.sizes.rodata) << " KiB, .data " << e.sizes.data << " B, .bss " << e.sizes.bss
        << " B\n";
  }
  if (top_frames == 0) return;
  out << "\nlargest stack frames (-fstack-usage):\n";
  for (const LibraryReport& lib : libs) {
    out << "  " << lib.name << ":";
    if (lib.frames.empty()) out << " none recorded";
    if (lib.missing_su) out << " (" << lib.missing_su << " objects without .su file)";
    out << "\n";
    for (size_t i = 0; i < lib.frames.size() && i < top_frames; ++i) {
      const StackFrame& f = lib.frames[i];
      out << "    " << std::setw(7) << f.bytes << " B" << (f.dynamic ? " dynamic " : "  ")
          << f.function << "  (" << f.location << ")\n";
    }
  }
}

}  // namespace kestrel::budget
