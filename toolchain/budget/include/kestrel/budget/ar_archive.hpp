// Members of a Unix `ar` archive (static library) as produced by GNU ar: the common
// "!<arch>\n" format with the GNU "/" symbol table and "//" long-name table. The symbol
// tables are skipped; every other member is returned with its resolved name.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace kestrel::budget {

struct ArMember {
  std::string name;
  std::span<const uint8_t> bytes;  // view into the archive image
};

// Throws BudgetError on a malformed archive. `what` names the archive in errors.
std::vector<ArMember> parse_ar(std::span<const uint8_t> image, const std::string& what);

bool looks_like_ar(std::span<const uint8_t> image);

}  // namespace kestrel::budget
