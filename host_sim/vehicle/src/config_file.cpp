#include "kestrel/sim/config_file.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kestrel::sim {
namespace {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

}  // namespace

std::string ConfigFile::parse(std::string_view text, std::string_view source_name) {
  source_ = std::string(source_name);
  entries_.clear();
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view raw = text.substr(pos, nl == std::string_view::npos ? text.size() - pos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    const auto hash = raw.find('#');
    if (hash != std::string_view::npos) raw = raw.substr(0, hash);
    const std::string line = trim(raw);
    if (line.empty()) continue;
    const auto eq = line.find('=');
    const std::string where = source_ + ":" + std::to_string(line_no) + ": ";
    if (eq == std::string::npos) return where + "expected 'key = value'";
    const std::string key = trim(std::string_view(line).substr(0, eq));
    const std::string val = trim(std::string_view(line).substr(eq + 1));
    if (key.empty()) return where + "missing key before '='";
    char* end = nullptr;
    const double v = std::strtod(val.c_str(), &end);
    if (val.empty() || end != val.c_str() + val.size() || !std::isfinite(v))
      return where + "value of '" + key + "' is not a finite number: '" + val + "'";
    for (const ConfigEntry& e : entries_)
      if (e.key == key) return where + "'" + key + "' is already set on line " + std::to_string(e.line);
    entries_.push_back({key, v, line_no});
  }
  used_.assign(entries_.size(), false);
  return {};
}

std::string ConfigFile::load(const std::string& path) {
  // A directory opens as a stream and then reads as empty: say so rather than parse nothing.
  // Both refusals are in the words the parameter files' loader (modules/params) uses; the
  // callers print them as they are, and the path says which of their files it was.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return "cannot read '" + path + "' (is a directory)";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open '" + path + "'";
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

void ConfigFile::apply(const ConfigBinding* bindings, std::size_t count) {
  used_.resize(entries_.size(), false);
  for (std::size_t i = 0; i < entries_.size(); ++i)
    for (std::size_t b = 0; b < count; ++b)
      if (entries_[i].key == bindings[b].key) {
        *bindings[b].field = entries_[i].value;
        used_[i] = true;
      }
}

std::string ConfigFile::unknown_keys() const {
  for (std::size_t i = 0; i < entries_.size(); ++i)
    if (i >= used_.size() || !used_[i])
      return source_ + ":" + std::to_string(entries_[i].line) + ": unknown key '" + entries_[i].key + "'";
  return {};
}

}  // namespace kestrel::sim
