// GCC -fstack-usage files (.su): one line per function,
//   "file:line:column:function<TAB>bytes<TAB>qualifiers"
// where qualifiers is "static", "dynamic" or "dynamic,bounded". A "dynamic" frame (alloca,
// variable-length array) has no compile-time bound: the budget report marks it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace kestrel::budget {

struct StackFrame {
  std::string location;  // file:line:column
  std::string function;
  uint64_t bytes = 0;
  bool dynamic = false;  // "dynamic" without ",bounded"
};

// Parses the text of one .su file; throws BudgetError naming `what` and the line on bad input.
std::vector<StackFrame> parse_stack_usage(std::string_view text, const std::string& what);

}  // namespace kestrel::budget
