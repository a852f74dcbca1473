#pragma once
// The one error policy of the fixed-capacity containers: a contract violation (an index out of
// range, a pop from an empty container) is a programming error, not an input error. Input
// errors are reported as Status values by the API (push returns false when full); what reaches
// this check is a bug, and the firmware stops at once rather than corrupt memory.
#include <cstdlib>

namespace kestrel {

[[noreturn]] inline void contract_violation(const char* /*what*/) { std::abort(); }

}  // namespace kestrel

#define KESTREL_EXPECTS(cond, what) \
  do {                              \
    if (!(cond)) ::kestrel::contract_violation(what); \
  } while (false)
