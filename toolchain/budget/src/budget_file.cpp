#include "kestrel/budget/budget_file.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include "kestrel/budget/error.hpp"

namespace kestrel::budget {
namespace {

uint64_t number_with_suffix(std::string_view token, const std::string& what,
                            std::initializer_list<std::pair<std::string_view, uint64_t>> units,
                            const char* kind) {
  size_t digits = 0;
  uint64_t v = 0;
  while (digits < token.size() && token[digits] >= '0' && token[digits] <= '9') {
    if (v > UINT64_MAX / 10 - 1)
      throw BudgetError(what + ": number too large: " + std::string(token));
    v = v * 10 + static_cast<uint64_t>(token[digits] - '0');
    ++digits;
  }
  if (digits == 0)
    throw BudgetError(what + ": expected a " + kind + ", got '" + std::string(token) + "'");
  const std::string_view unit = token.substr(digits);
  if (unit.empty()) return v;
  for (const auto& [name, scale] : units) {
    if (unit == name) {
      if (v > UINT64_MAX / scale)
        throw BudgetError(what + ": number too large: " + std::string(token));
      return v * scale;
    }
  }
  throw BudgetError(what + ": unknown unit '" + std::string(unit) + "' in '" + std::string(token) +
                    "'");
}

LibraryLimits parse_limits(const std::vector<std::string>& words, size_t first,
                           const std::string& where) {
  LibraryLimits l;
  if ((words.size() - first) % 2 != 0 || words.size() == first) {
    throw BudgetError(where + ": expected pairs 'code N rodata N ram N stack N'");
  }
  for (size_t i = first; i < words.size(); i += 2) {
    const std::string& key = words[i];
    const uint64_t v = parse_size(words[i + 1], where);
    std::optional<uint64_t>* slot = key == "code"     ? &l.code
                                    : key == "rodata" ? &l.rodata
                                    : key == "ram"    ? &l.ram
                                    : key == "stack"  ? &l.stack
                                                      : nullptr;
    if (slot == nullptr)
      throw BudgetError(where + ": unknown limit '" + key + "' (code, rodata, ram, stack)");
    if (slot->has_value()) throw BudgetError(where + ": limit '" + key + "' given twice");
    *slot = v;
  }
  return l;
}

}  // namespace

uint64_t parse_size(std::string_view token, const std::string& what) {
  return number_with_suffix(token, what, {{"B", 1}, {"KiB", 1024}, {"MiB", 1024 * 1024}}, "size");
}

uint64_t parse_count(std::string_view token, const std::string& what) {
  return number_with_suffix(token, what, {{"k", 1000}, {"M", 1000000}}, "count");
}

LibraryLimits BudgetFile::limits_for(const std::string& library) const {
  LibraryLimits l = defaults;
  const auto it = libraries.find(library);
  if (it != libraries.end()) {
    if (it->second.code) l.code = it->second.code;
    if (it->second.rodata) l.rodata = it->second.rodata;
    if (it->second.ram) l.ram = it->second.ram;
    if (it->second.stack) l.stack = it->second.stack;
  }
  return l;
}

BudgetFile parse_budget_file(std::string_view text, const std::string& what) {
  BudgetFile b;
  bool have_defaults = false;
  std::istringstream in{std::string(text)};
  std::string line;
  size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = what + ":" + std::to_string(line_no);
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words_in(line);
    std::vector<std::string> w;
    for (std::string word; words_in >> word;) w.push_back(word);
    if (w.empty()) continue;
    const std::string& key = w[0];
    const auto one_value = [&]() -> const std::string& {
      if (w.size() != 2) throw BudgetError(where + ": '" + key + "' takes exactly one value");
      return w[1];
    };
    if (key == "target") {
      b.target = one_value();
    } else if (key == "clock_mhz") {
      b.clock_mhz = parse_count(one_value(), where);
    } else if (key == "loop_cycles") {
      b.loop_cycles = parse_count(one_value(), where);
    } else if (key == "firmware_ram") {
      b.firmware_ram = parse_size(one_value(), where);
    } else if (key == "default") {
      if (have_defaults) throw BudgetError(where + ": second 'default' line");
      b.defaults = parse_limits(w, 1, where);
      have_defaults = true;
    } else if (key == "library") {
      if (w.size() < 2) throw BudgetError(where + ": 'library' needs a name");
      if (b.libraries.count(w[1]))
        throw BudgetError(where + ": library '" + w[1] + "' listed twice");
      b.libraries[w[1]] = parse_limits(w, 2, where);
    } else {
      throw BudgetError(where + ": unknown key '" + key + "'");
    }
  }
  if (b.target.empty()) throw BudgetError(what + ": missing 'target' line");
  if (b.clock_mhz == 0) throw BudgetError(what + ": missing or zero 'clock_mhz'");
  if (b.loop_cycles == 0) throw BudgetError(what + ": missing or zero 'loop_cycles'");
  if (!have_defaults) throw BudgetError(what + ": missing 'default' limits line");
  return b;
}

BudgetFile load_budget_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw BudgetError(path + ": cannot open budget file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_budget_file(ss.str(), path);
}

}  // namespace kestrel::budget
