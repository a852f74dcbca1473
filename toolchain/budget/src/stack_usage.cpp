#include "kestrel/budget/stack_usage.hpp"

#include "kestrel/budget/error.hpp"

namespace kestrel::budget {

std::vector<StackFrame> parse_stack_usage(std::string_view text, const std::string& what) {
  std::vector<StackFrame> frames;
  size_t line_no = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    if (line.empty()) continue;
    const auto bad = [&](const char* why) {
      return BudgetError(what + ":" + std::to_string(line_no) + ": " + why);
    };
    // Split from the right: function names may contain ':' but never a tab.
    const size_t t2 = line.rfind('\t');
    if (t2 == std::string_view::npos || t2 == 0) throw bad("expected 3 tab-separated fields");
    const size_t t1 = line.rfind('\t', t2 - 1);
    if (t1 == std::string_view::npos) throw bad("expected 3 tab-separated fields");
    const std::string_view where = line.substr(0, t1);
    const std::string_view bytes = line.substr(t1 + 1, t2 - t1 - 1);
    const std::string_view qual = line.substr(t2 + 1);
    StackFrame f;
    if (bytes.empty()) throw bad("empty frame size");
    for (char c : bytes) {
      if (c < '0' || c > '9') throw bad("frame size is not a number");
      f.bytes = f.bytes * 10 + static_cast<uint64_t>(c - '0');
    }
    if (qual == "static") {
      f.dynamic = false;
    } else if (qual == "dynamic") {
      f.dynamic = true;
    } else if (qual == "dynamic,bounded") {
      f.dynamic = false;
    } else {
      throw bad("unknown qualifier (static, dynamic or dynamic,bounded)");
    }
    // "path:line:column:name": the name starts after the first ":digits:digits:" (a path may
    // hold ':' too, but not followed by that pattern in practice; names may hold '::').
    size_t cut = std::string_view::npos;
    for (size_t i = 0; i < where.size() && cut == std::string_view::npos; ++i) {
      if (where[i] != ':') continue;
      const auto digits_then_colon = [&](size_t from) -> size_t {
        size_t k = from;
        while (k < where.size() && where[k] >= '0' && where[k] <= '9') ++k;
        return (k == from || k >= where.size() || where[k] != ':') ? std::string_view::npos : k;
      };
      const size_t line_end = digits_then_colon(i + 1);
      if (line_end == std::string_view::npos) continue;
      cut = digits_then_colon(line_end + 1);
    }
    if (cut != std::string_view::npos) {
      f.location = std::string(where.substr(0, cut));
      f.function = std::string(where.substr(cut + 1));
    } else {
      f.function = std::string(where);  // no location (e.g. a compiler-generated thunk)
    }
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace kestrel::budget
