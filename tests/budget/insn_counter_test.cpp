// The QEMU instruction counter on an ARM program whose loop is exactly two instructions.
#include "kestrel/budget/insn_counter.hpp"

#include <gtest/gtest.h>

#include "kestrel/budget/error.hpp"

namespace kb = kestrel::budget;

TEST(BudgetInsnCounter, DifferenceQuotientCancelsFixedCost) {
  EXPECT_DOUBLE_EQ(kb::per_iteration(1000 + 10 * 7, 10, 1000 + 30 * 7, 30), 7.0);
  EXPECT_THROW(kb::per_iteration(10, 5, 20, 5), kb::BudgetError);
  EXPECT_THROW(kb::per_iteration(30, 5, 20, 10), kb::BudgetError);
}

#ifdef BUDGET_ARM_INSN_LOOP
TEST(BudgetInsnCounter, CountsExactlyTwoInstructionsPerLoopIteration) {
  // Same number of digits in both runs, so parsing the argument costs the same.
  const std::vector<std::string> qemu = {"qemu-arm", "-L", "/"};
  const kb::CountResult a =
      kb::count_instructions(qemu, BUDGET_INSN_PLUGIN, {BUDGET_ARM_INSN_LOOP, "0001000"}, true);
  const kb::CountResult b =
      kb::count_instructions(qemu, BUDGET_INSN_PLUGIN, {BUDGET_ARM_INSN_LOOP, "0051000"}, true);
  EXPECT_EQ(a.exit_status, 0);
  EXPECT_EQ(b.exit_status, 0);
  EXPECT_GT(a.insns, 2000u);  // loader and libc start-up come on top of the loop
  EXPECT_EQ(b.insns - a.insns, 2u * 50000u);
  EXPECT_DOUBLE_EQ(kb::per_iteration(a.insns, 1000, b.insns, 51000), 2.0);
}

TEST(BudgetInsnCounter, MissingProgramOrPluginIsAnError) {
  const std::vector<std::string> qemu = {"qemu-arm", "-L", "/"};
  EXPECT_THROW(
      kb::count_instructions(qemu, "/nonexistent/libplugin.so", {BUDGET_ARM_INSN_LOOP, "1"}, true),
      kb::BudgetError);
  EXPECT_THROW(kb::count_instructions({"/nonexistent/qemu"}, BUDGET_INSN_PLUGIN,
                                      {BUDGET_ARM_INSN_LOOP, "1"}, true),
               kb::BudgetError);
  EXPECT_THROW(kb::count_instructions(qemu, BUDGET_INSN_PLUGIN, {}, true), kb::BudgetError);
}
#endif
