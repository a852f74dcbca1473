// The build-tree manifest CMake writes for kestrel-budget.
#include "kestrel/budget/manifest.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "kestrel/budget/error.hpp"

namespace kb = kestrel::budget;

namespace {

std::string write_temp(const std::string& text) {
  char name[] = "/tmp/kestrel-manifest-test-XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  std::FILE* f = fdopen(fd, "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  return name;
}

}  // namespace

TEST(BudgetManifest, ReadsEveryEntry) {
  const std::string p = write_temp(
      "target\tovero\nbudget\t/b.txt\nemulator\tqemu-arm;-L;/\nbench\t/kb\nbench_iters\t/kbi\n"
      "library\tkestrel_core\t/libkestrel_core.a\t/a.cpp.o;/b.cpp.o\n"
      "library\tkestrel_empty\t/libkestrel_empty.a\t\nexecutable\tkestrel-fw\t/fw\n");
  const kb::Manifest m = kb::load_manifest(p);
  std::remove(p.c_str());
  EXPECT_EQ(m.target, "overo");
  EXPECT_EQ(m.budget_file, "/b.txt");
  ASSERT_EQ(m.emulator.size(), 3u);
  EXPECT_EQ(m.emulator[2], "/");
  EXPECT_EQ(m.bench_iters, "/kbi");
  ASSERT_EQ(m.libraries.size(), 2u);
  ASSERT_EQ(m.libraries[0].objects.size(), 2u);
  EXPECT_EQ(m.libraries[0].objects[1], "/b.cpp.o");
  EXPECT_TRUE(m.libraries[1].objects.empty());
  ASSERT_EQ(m.executables.size(), 1u);
  EXPECT_EQ(m.executables[0].second, "/fw");
}

TEST(BudgetManifest, MalformedManifestsAreErrors) {
  for (const char* text : {"budget\t/b.txt\n",                   // no target
                           "target\tovero\nlibrary\tx\t/x.a\n",  // missing field
                           "target\tovero\nwhatever\t1\n",       // unknown entry
                           "target\tovero\textra\n"}) {
    const std::string p = write_temp(text);
    EXPECT_THROW(kb::load_manifest(p), kb::BudgetError) << text;
    std::remove(p.c_str());
  }
  EXPECT_THROW(kb::load_manifest("/nonexistent/kestrel-budget-manifest.txt"), kb::BudgetError);
}
