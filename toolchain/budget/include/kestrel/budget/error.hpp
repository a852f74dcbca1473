// Input errors of the budget tool (unreadable or malformed files). The host tool may use
// exceptions; main() turns them into exit status 2 with the message.
#pragma once

#include <stdexcept>
#include <string>

namespace kestrel::budget {

class BudgetError : public std::runtime_error {
 public:
  explicit BudgetError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace kestrel::budget
