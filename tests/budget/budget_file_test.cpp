// Budget-file parsing and the checks that turn measurements into named violations.
#include "kestrel/budget/budget_file.hpp"

#include <gtest/gtest.h>

#include "kestrel/budget/error.hpp"
#include "kestrel/budget/size_report.hpp"

namespace kb = kestrel::budget;

namespace {

constexpr const char* kGood =
    "# comment line\n"
    "target overo\n"
    "clock_mhz 720   # trailing comment\n"
    "loop_cycles 9M\n"
    "firmware_ram 16MiB\n"
    "default code 256KiB rodata 64KiB ram 1MiB stack 16KiB\n"
    "library kestrel_core code 64KiB ram 1000B\n";

kb::LibraryReport lib(const std::string& name, uint64_t code, uint64_t data, uint64_t bss,
                      uint64_t frame) {
  kb::LibraryReport r;
  r.name = name;
  r.sizes.code = code;
  r.sizes.data = data;
  r.sizes.bss = bss;
  if (frame) r.frames.push_back({"x.cpp:1:1", "f()", frame, false});
  return r;
}

}  // namespace

TEST(BudgetFile, ParsesValuesUnitsAndPerLibraryOverrides) {
  const kb::BudgetFile b = kb::parse_budget_file(kGood, "good.txt");
  EXPECT_EQ(b.target, "overo");
  EXPECT_EQ(b.clock_mhz, 720u);
  EXPECT_EQ(b.loop_cycles, 9000000u);
  EXPECT_EQ(*b.firmware_ram, 16u * 1024 * 1024);
  const kb::LibraryLimits core = b.limits_for("kestrel_core");
  EXPECT_EQ(*core.code, 64u * 1024);
  EXPECT_EQ(*core.ram, 1000u);
  EXPECT_EQ(*core.rodata, 64u * 1024);  // from the default line
  EXPECT_EQ(*core.stack, 16u * 1024);
  const kb::LibraryLimits other = b.limits_for("kestrel_other");
  EXPECT_EQ(*other.ram, 1024u * 1024);
  EXPECT_EQ(kb::parse_count("20M", "x"), 20000000u);
  EXPECT_EQ(kb::parse_count("9k", "x"), 9000u);
  EXPECT_EQ(kb::parse_size("3KiB", "x"), 3072u);
}

TEST(BudgetFile, MalformedFilesAreErrorsWithTheLine) {
  const char* bad[] = {
      "target overo\nclock_mhz 720\nloop_cycles 9M\n",                         // no default line
      "clock_mhz 720\nloop_cycles 9M\ndefault ram 1MiB\n",                     // no target
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1 MiB\n",          // odd pairs
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1GiB\n",           // unknown unit
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault heap 1MiB\n",          // unknown limit
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1MiB ram 2MiB\n",  // twice
      "target o\nclock_mhz 720\nloop_cycles nine\ndefault ram 1MiB\n",         // not a number
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1MiB\nspeed 3\n",  // unknown key
      "target o p\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1MiB\n",         // two values
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 99999999999999999999\n",  // overflow
      "target o\nclock_mhz 720\nloop_cycles 9M\ndefault ram 1MiB\nlibrary a ram 1KiB\n"
      "library a ram 2KiB\n",  // library twice
  };
  for (const char* text : bad) {
    EXPECT_THROW(kb::parse_budget_file(text, "bad.txt"), kb::BudgetError) << text;
  }
  try {
    kb::parse_budget_file("target o\nclock_mhz 720\nloop_cycles 9M\ndefault heap 1MiB\n", "b.txt");
  } catch (const kb::BudgetError& e) {
    EXPECT_NE(std::string(e.what()).find("b.txt:4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(kb::load_budget_file("/nonexistent/budget.txt"), kb::BudgetError);
}

TEST(BudgetFile, EveryExceededLimitIsNamedAndLimitsAreInclusive) {
  const kb::BudgetFile b = kb::parse_budget_file(kGood, "good.txt");
  // Exactly at every limit: no violation.
  std::vector<kb::LibraryReport> libs = {lib("kestrel_core", 64 * 1024, 600, 400, 16 * 1024)};
  EXPECT_TRUE(kb::check_budget(b, libs, {}, "kestrel-fw").empty());
  // One byte over the core's RAM limit, and a frame over the stack limit.
  libs = {lib("kestrel_core", 64 * 1024, 600, 401, 16 * 1024 + 1)};
  auto v = kb::check_budget(b, libs, {}, "kestrel-fw");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NE(v[0].what.find("kestrel_core: static RAM 1001 B > limit 1000 B"), std::string::npos);
  EXPECT_NE(v[1].what.find("stack frame of f()"), std::string::npos);
  // Code over the default of a library without its own line.
  libs = {lib("kestrel_x", 256 * 1024 + 1, 0, 0, 0)};
  v = kb::check_budget(b, libs, {}, "kestrel-fw");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].what.find("kestrel_x: code"), std::string::npos);
  // Whole firmware: the sum of the libraries, or the linked firmware when present.
  libs = {lib("kestrel_a", 0, 0, 1000 * 1024, 0), lib("kestrel_b", 0, 0, 1000 * 1024, 0),
          lib("kestrel_c", 0, 0, 1000 * 1024, 0)};
  for (int i = 0; i < 14; ++i)
    libs.push_back(lib("kestrel_m" + std::to_string(i), 0, 0, 1000 * 1024, 0));
  v = kb::check_budget(b, libs, {}, "kestrel-fw");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].what.find("firmware static RAM (sum of libraries)"), std::string::npos);
  kb::ExecutableReport fw{"kestrel-fw", {}};
  fw.sizes.bss = 15 * 1024 * 1024;
  EXPECT_TRUE(kb::check_budget(b, libs, {fw}, "kestrel-fw").empty());
  // A dynamic (unbounded) frame is always named.
  libs = {lib("kestrel_core", 0, 0, 0, 0)};
  libs[0].frames.push_back({"y.cpp:2:2", "g()", 8, true});
  v = kb::check_budget(b, libs, {}, "kestrel-fw");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].what.find("unbounded dynamic stack frame in g()"), std::string::npos);
}
