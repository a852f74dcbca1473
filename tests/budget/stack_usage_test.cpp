// Parsing GCC -fstack-usage lines.
#include "kestrel/budget/stack_usage.hpp"

#include <gtest/gtest.h>

#include "kestrel/budget/error.hpp"

namespace kb = kestrel::budget;

TEST(BudgetStackUsage, ParsesLocationNameSizeAndQualifier) {
  const auto frames = kb::parse_stack_usage(
      "/src/a.cpp:12:6:void ns::f(int)\t48\tstatic\n"
      "/src/b.hpp:3:10:virtual kestrel::TimeUs kestrel::X::now() const\t0\tstatic\n"
      "/src/c.cpp:7:1:int g(std::map<int, int>&)\t4096\tdynamic,bounded\n"
      "\n"
      "/src/d.cpp:9:2:void h(unsigned)\t32\tdynamic\n",
      "t.su");
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].location, "/src/a.cpp:12:6");
  EXPECT_EQ(frames[0].function, "void ns::f(int)");
  EXPECT_EQ(frames[0].bytes, 48u);
  EXPECT_FALSE(frames[0].dynamic);
  EXPECT_EQ(frames[1].function, "virtual kestrel::TimeUs kestrel::X::now() const");
  EXPECT_EQ(frames[2].bytes, 4096u);
  EXPECT_FALSE(frames[2].dynamic);  // bounded: the size given is the bound
  EXPECT_TRUE(frames[3].dynamic);
  EXPECT_EQ(frames[3].location, "/src/d.cpp:9:2");
}

TEST(BudgetStackUsage, MalformedLinesAreErrorsNamingTheLine) {
  EXPECT_THROW(kb::parse_stack_usage("a.c:1:1:f\t12\n", "t.su"), kb::BudgetError);
  EXPECT_THROW(kb::parse_stack_usage("a.c:1:1:f\tx12\tstatic\n", "t.su"), kb::BudgetError);
  EXPECT_THROW(kb::parse_stack_usage("a.c:1:1:f\t\tstatic\n", "t.su"), kb::BudgetError);
  EXPECT_THROW(kb::parse_stack_usage("a.c:1:1:f\t12\tsometimes\n", "t.su"), kb::BudgetError);
  try {
    kb::parse_stack_usage("a.c:1:1:f\t1\tstatic\nbroken line\n", "t.su");
    FAIL() << "no error";
  } catch (const kb::BudgetError& e) {
    EXPECT_NE(std::string(e.what()).find("t.su:2"), std::string::npos) << e.what();
  }
}
