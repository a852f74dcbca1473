#pragma once
// A mode enum's names, for kestrel-sim's options and config files. Each enum keeps two things of
// its own: its to_string, a switch (so the compiler flags a value it leaves out), and the one
// list of its values. These read both, so a mode added to the list is known and parsed with no
// other change.
#include <cstddef>
#include <cstring>

#include "kestrel/core/status.hpp"

namespace kestrel {

template <typename Mode, std::size_t N>
constexpr bool listed(Mode mode, const Mode (&modes)[N]) {
  for (const Mode m : modes)
    if (m == mode) return true;
  return false;
}

// to_string(Mode) is found in Mode's own namespace. kInvalidArgument for a name no mode of the
// list has, or nullptr.
template <typename Mode, std::size_t N>
Result<Mode> parse_by_name(const char* name, const Mode (&modes)[N]) {
  if (name == nullptr) return Status::kInvalidArgument;
  for (const Mode m : modes)
    if (std::strcmp(name, to_string(m)) == 0) return m;
  return Status::kInvalidArgument;
}

}  // namespace kestrel
