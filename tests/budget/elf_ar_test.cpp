// ar + ELF parsing on fixture archives compiled by the build with known array sizes.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "kestrel/budget/ar_archive.hpp"
#include "kestrel/budget/elf_sections.hpp"
#include "kestrel/budget/error.hpp"
#include "kestrel/budget/manifest.hpp"
#include "kestrel/budget/size_report.hpp"

namespace kb = kestrel::budget;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t p; (p = s.find('|', start)) != std::string::npos; start = p + 1) {
    out.push_back(s.substr(start, p - start));
  }
  out.push_back(s.substr(start));
  return out;
}

// Checks the fixture archive: the data-only member has exactly the arrays' sizes.
void check_fixture_archive(const std::string& path, bool arm) {
  const std::vector<uint8_t> image = kb::read_file_bytes(path);
  ASSERT_TRUE(kb::looks_like_ar(image));
  const std::vector<kb::ArMember> members = kb::parse_ar(image, path);
  ASSERT_EQ(members.size(), 2u);
  bool saw_data = false, saw_code = false;
  for (const kb::ArMember& m : members) {
    const kb::ElfInfo info = kb::parse_elf(m.bytes, m.name);
    if (arm) {
      EXPECT_FALSE(info.is_64);
      EXPECT_EQ(info.machine, 40);  // EM_ARM
    }
    if (m.name.find("fixture_data") != std::string::npos) {
      saw_data = true;
      EXPECT_EQ(info.sizes.bss, 1000u);
      EXPECT_EQ(info.sizes.data, 100u);
      EXPECT_EQ(info.sizes.rodata, 200u);
      EXPECT_EQ(info.sizes.code, 0u);
      EXPECT_EQ(info.sizes.ram(), 1100u);
    } else {
      // The long name comes from the GNU "//" table, complete and without the '/' suffix.
      EXPECT_EQ(m.name.rfind("budget_fixture_code_with_a_long_member_name.c", 0), 0u) << m.name;
      saw_code = true;
      EXPECT_GT(info.sizes.code, 0u);
      EXPECT_EQ(info.sizes.ram(), 0u);
    }
  }
  EXPECT_TRUE(saw_data);
  EXPECT_TRUE(saw_code);
}

}  // namespace

TEST(BudgetElfAr, HostFixtureArchiveHasKnownSizes) {
  check_fixture_archive(BUDGET_HOST_FIXTURE_AR, false);
}

#ifdef BUDGET_ARM_FIXTURE_AR
TEST(BudgetElfAr, ArmFixtureArchiveHasKnownSizes) {
  check_fixture_archive(BUDGET_ARM_FIXTURE_AR, true);
}

TEST(BudgetElfAr, LibraryReportSumsMembersAndFindsStackFrames) {
  const kb::LibraryReport r =
      kb::measure_library({"fx", BUDGET_ARM_FIXTURE_AR, split(BUDGET_ARM_FIXTURE_OBJECTS)});
  EXPECT_EQ(r.objects, 2u);
  EXPECT_EQ(r.missing_su, 0u);
  EXPECT_EQ(r.sizes.ram(), 1100u);
  EXPECT_EQ(r.sizes.rodata, 200u);
  ASSERT_FALSE(r.frames.empty());
  EXPECT_NE(r.frames.front().function.find("budget_fixture_big_frame"), std::string::npos);
  EXPECT_GE(r.frames.front().bytes, 512u);
  EXPECT_LT(r.frames.front().bytes, 640u);
  EXPECT_FALSE(r.frames.front().dynamic);
}
#endif

TEST(BudgetElfAr, TruncatedOrForeignFilesAreErrors) {
  const std::vector<uint8_t> image = kb::read_file_bytes(BUDGET_HOST_FIXTURE_AR);
  const std::vector<kb::ArMember> members = kb::parse_ar(image, "fx");
  ASSERT_FALSE(members.empty());
  const std::span<const uint8_t> elf = members.front().bytes;
  // Every prefix shorter than the section table must be refused, never read out of bounds.
  EXPECT_THROW(kb::parse_elf(elf.first(10), "cut"), kb::BudgetError);
  EXPECT_THROW(kb::parse_elf(elf.first(elf.size() / 2), "cut"), kb::BudgetError);
  std::vector<uint8_t> big_endian(elf.begin(), elf.end());
  big_endian[5] = 2;
  EXPECT_THROW(kb::parse_elf(big_endian, "be"), kb::BudgetError);
  const std::string text = "hello, not an ELF file";
  const std::vector<uint8_t> bytes(text.begin(), text.end());
  EXPECT_THROW(kb::parse_elf(bytes, "text"), kb::BudgetError);
  EXPECT_THROW(kb::parse_ar(bytes, "text"), kb::BudgetError);
  // A member whose declared size runs past the end of the archive.
  EXPECT_THROW(kb::parse_ar(std::span<const uint8_t>(image).first(image.size() - 7), "cut"),
               kb::BudgetError);
  // A corrupted member header magic.
  std::vector<uint8_t> bad(image);
  bad[8 + 58] = 'X';
  EXPECT_THROW(kb::parse_ar(bad, "bad"), kb::BudgetError);
  EXPECT_THROW(kb::read_file_bytes("/nonexistent/libnothing.a"), kb::BudgetError);
}

TEST(BudgetElfAr, StackUsagePathFollowsGccNaming) {
  EXPECT_EQ(kb::stack_usage_path("a/b.dir/src/x.cpp.o"), "a/b.dir/src/x.cpp.su");
  EXPECT_EQ(kb::stack_usage_path("a.b/x"), "a.b/x.su");
}

#ifdef BUDGET_ARM_INSN_LOOP
TEST(BudgetElfAr, LinkedArmExecutableIsMeasured) {
  const kb::ExecutableReport e = kb::measure_executable("insn_loop", BUDGET_ARM_INSN_LOOP);
  EXPECT_GT(e.sizes.code, 0u);
  EXPECT_GT(e.sizes.rodata, 0u);  // at least the dynamic-linking tables
  EXPECT_GT(e.sizes.data, 0u);    // at least the GOT
  const kb::ElfInfo info =
      kb::parse_elf(kb::read_file_bytes(BUDGET_ARM_INSN_LOOP), BUDGET_ARM_INSN_LOOP);
  EXPECT_EQ(info.machine, 40);
  EXPECT_FALSE(info.is_64);
}
#endif
